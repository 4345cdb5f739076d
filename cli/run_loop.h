// The sampling loop of `spinfold simulate`, which every run of `spinfold sweep` takes too, so that a
// sweep's row is the run simulate makes, to the bit.
#pragma once

#include <algorithm>

#include "engine/simulation.h"

namespace spinfold::cli {

// Calls sample() at the start, then advance(t) and sample() for t = k·every up to t_end (the
// last at t_end exactly), until the run's status stops it or advance returns false (its budget
// ran out: no sample then).
template <typename Advance, typename Sample>
void sample_run(Simulation& run, double t_end, double every, Advance&& advance, Sample&& sample) {
  sample();
  for (long k = 1; run.state.status == Status::ok && run.state.t < t_end; ++k) {
    if (!advance(std::min(static_cast<double>(k) * every, t_end))) return;
    sample();
  }
}

}  // namespace spinfold::cli
