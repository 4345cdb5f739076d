#include "engine/timeline.h"

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

}  // namespace spinfold
