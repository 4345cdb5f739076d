// A run as a pure function of its timeline: the scene at t = 0 and the parameter changes after.
#pragma once

#include <cstdint>
#include <functional>
#include <span>

#include "engine/simulation.h"
#include "engine/trail.h"

namespace spinfold {

// The parameters in force from time t on (applied with retune).
struct ParameterChange {
  double t = 0.0;  // [time], ≥ 0 and not before the previous change
  Scene scene;     // the whole scene after the change
};

// Rebuilds the run at `until` [time] from t = 0: advances to each change, retunes, and advances on,
// recording the trail (`trail` starts empty, with the spacing and cap wanted). The state and trail are
// bit-identical to those of a run advanced in any other pattern through the same changes. False when
// max_attempts ran out first (the run then stands where it got to).
bool replay(const Scene& scene, std::span<const ParameterChange> changes, double until, Simulation& run,
            Trail& trail, std::uint64_t max_attempts = kNoStepLimit);

// The run's samples at t = 0 and at k·every up to `until` (the last at `until` exactly), as
// `spinfold simulate` samples a run, with the changes applied on the way as replay applies them
// (a sample at a change's time comes after it). `sample` sees the run at each sample time: the
// rows of a trajectory whatever pattern the run was advanced in. Stops after the sample where the
// run's status stopped it; false when max_attempts (for the whole replay) ran out first.
bool replay_sampled(const Scene& scene, std::span<const ParameterChange> changes, double until, double every,
                    const std::function<void(const Simulation&)>& sample,
                    std::uint64_t max_attempts = kNoStepLimit);

}  // namespace spinfold
