// A run as a pure function of its timeline: the scene at t = 0 and the parameter changes after.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "engine/simulation.h"
#include "engine/trail.h"

namespace spinfold {

// The parameters in force from time t on (applied with retune).
struct ParameterChange {
  double t = 0.0;  // [time], ≥ 0 and not before the previous change
  Scene scene;     // the whole scene after the change
};

// Rebuilds the run at `until` [time] from t = 0: advances to each change up to `until`, retunes, and
// advances on, recording the trail (`trail` gives the spacing and cap wanted; its points are dropped).
// TimelineReplay asked once. The state and trail are bit-identical to those of a run advanced in any
// other pattern through the same changes. False when max_attempts ran out first (the run then stands
// where it got to).
bool replay(const Scene& scene, std::span<const ParameterChange> changes, double until, Simulation& run,
            Trail& trail, std::uint64_t max_attempts = kNoStepLimit);

// A replay that goes forward in steps: the run and its trail as they stand at each time asked
// for, advanced from t = 0 through the changes as replay() advances (replay is this, asked once).
// Recordings draw their frames from one (record/clip.h).
class TimelineReplay {
 public:
  // The run at t = 0; `trail` gives the spacing and cap wanted (its points are dropped).
  TimelineReplay(const Scene& scene, std::vector<ParameterChange> changes, Trail trail = {});
  // Advances to `t` (not before the current time) through the changes up to it, recording the
  // trail. False when a change's time could not be reached or max_attempts ran out on the way to a
  // change; else advance_sampling_trail's answer for the last stretch (true when the run stopped on its
  // own: its status says so).
  bool advance_to(double t, std::uint64_t max_attempts = kNoStepLimit);
  const Simulation& run() const { return run_; }
  const Trail& trail() const { return trail_; }
  // Moves the run and trail out (the replay is done with).
  Simulation take_run() { return std::move(run_); }
  Trail take_trail() { return std::move(trail_); }

 private:
  std::vector<ParameterChange> changes_;
  std::size_t next_ = 0;  // the first change not yet applied
  Simulation run_;
  Trail trail_;
};

// The run's samples at t = 0 and at k·every up to `until` (the last at `until` exactly), as
// `spinfold simulate` samples a run, with the changes applied on the way as replay applies them
// (a sample at a change's time comes after it). `sample` sees the run at each sample time: the
// rows of a trajectory whatever pattern the run was advanced in. Stops after the sample where the
// run's status stopped it; false when max_attempts (for the whole replay) ran out first.
bool replay_sampled(const Scene& scene, std::span<const ParameterChange> changes, double until, double every,
                    const std::function<void(const Simulation&)>& sample,
                    std::uint64_t max_attempts = kNoStepLimit);

}  // namespace spinfold
