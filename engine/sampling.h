// The one sampling loop: `spinfold simulate`, every run of a sweep (sweep/), the Python package and
// the timeline's replay (engine/timeline.cpp, the API's trajectory) all take it, so that their
// sample times, and so their numbers, are the same to the bit.
#pragma once

#include <algorithm>

#include "engine/simulation.h"

namespace spinfold {

// The time of sample k >= 1 of a run sampled every `every` up to `t_end`: k·every, the last
// t_end exactly.
inline double sample_time(long k, double every, double t_end) {
  return std::min(static_cast<double>(k) * every, t_end);
}

// Calls sample() at the start, then advance(t) and sample() for t = sample_time(k) up to t_end,
// until the run's status stops it or advance returns false (its budget ran out: no sample then).
// Returns false when advance did.
template <typename Advance, typename Sample>
bool sample_run(const Simulation& run, double t_end, double every, Advance&& advance, Sample&& sample) {
  sample();
  for (long k = 1; run.state.status == Status::ok && run.state.t < t_end; ++k) {
    if (!advance(sample_time(k, every, t_end))) return false;
    sample();
  }
  return true;
}

}  // namespace spinfold
