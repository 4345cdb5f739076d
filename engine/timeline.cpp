#include "engine/timeline.h"

#include <algorithm>

#include "engine/sampling.h"

namespace spinfold {

TimelineReplay::TimelineReplay(const Scene& scene, std::vector<ParameterChange> changes, Trail trail)
    : changes_(std::move(changes)), run_(start_simulation(scene)), trail_(std::move(trail)) {
  trail_.points.clear();
  trail_.companions.clear();
}

bool TimelineReplay::advance_to(double t, std::uint64_t max_attempts) {
  // Advance to each change, retune, advance on: the changes land at their own times exactly,
  // whatever times were asked for before (so every pattern of calls gives the same run).
  for (; next_ < changes_.size() && changes_[next_].t <= t; ++next_) {
    if (!advance_sampling_trail(run_, trail_, changes_[next_].t, max_attempts) ||
        run_.state.t != changes_[next_].t)
      return false;
    retune_carrying_trail(run_, trail_, changes_[next_].scene);
  }
  return advance_sampling_trail(run_, trail_, t, max_attempts);
}

bool replay(const Scene& scene, std::span<const ParameterChange> changes, double until, Simulation& run,
            Trail& trail, std::uint64_t max_attempts) {
  TimelineReplay replay(scene, {changes.begin(), changes.end()}, std::move(trail));
  const bool complete = replay.advance_to(until, max_attempts);
  run = replay.take_run();
  trail = replay.take_trail();
  return complete;
}

bool replay_sampled(const Scene& scene, std::span<const ParameterChange> changes, double until, double every,
                    const std::function<void(const Simulation&)>& sample, std::uint64_t max_attempts) {
  Simulation run = start_simulation(scene);
  std::size_t next = 0;
  const auto changes_up_to = [&](double t) {
    for (; next < changes.size() && changes[next].t <= t; ++next) {
      if (!advance_within(run, changes[next].t, max_attempts) || run.state.t != changes[next].t) return false;
      retune(run, changes[next].scene);
    }
    return true;
  };
  if (!changes_up_to(0.0)) return false;
  // The one sampling loop (engine/sampling.h): the sample times of `spinfold simulate` to the bit.
  return sample_run(
      run, until, every, [&](double t) { return changes_up_to(t) && advance_within(run, t, max_attempts); },
      [&] { sample(run); });
}

}  // namespace spinfold
