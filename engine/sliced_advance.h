// A run advanced in slices of step attempts, asked between them whether to go on: the clock of
// --max-seconds, Python's Ctrl-C, a progress line. Every front door that bounds a run by time or
// signals advances through it. The numbers do not depend on the slices (advance_within's promise:
// a run's state does not depend on where it was stopped).
#pragma once

#include <cstdint>
#include <functional>

#include "engine/simulation.h"

namespace spinfold {

enum class Advanced {
  reached,           // at t_end, or stopped there by a status of its own
  out_of_attempts,   // `attempts` ran out first
  stopped_by_caller  // go_on() said false before a slice
};

// Advances `run` toward t_end in slices of at most `slice` of `attempts` (what is spent is taken
// off), calling go_on() before each slice; go_on may also throw (Python's KeyboardInterrupt).
Advanced advance_in_slices(Simulation& run, double t_end, std::uint64_t& attempts,
                           const std::function<bool()>& go_on, std::uint64_t slice = 4096);

}  // namespace spinfold
