#include "engine/timeline.h"

#include <algorithm>

namespace spinfold {

bool replay(const Scene& scene, std::span<const ParameterChange> changes, double until, Simulation& run,
            Trail& trail, std::uint64_t max_attempts) {
  run = start_simulation(scene);
  for (const ParameterChange& change : changes) {
    if (!advance_recording(run, trail, change.t, max_attempts) || run.state.t != change.t) return false;
    retune_recording(run, trail, change.scene);
  }
  return advance_recording(run, trail, until, max_attempts);
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
  sample(run);
  // The loop of cli/run_loop.h: the same sample times to the bit.
  for (long k = 1; run.state.status == Status::ok && run.state.t < until; ++k) {
    const double t = std::min(static_cast<double>(k) * every, until);
    if (!changes_up_to(t) || !advance_within(run, t, max_attempts)) return false;
    sample(run);
  }
  return true;
}

}  // namespace spinfold
