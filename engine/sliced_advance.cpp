#include "engine/sliced_advance.h"

#include <algorithm>

namespace spinfold {

Advanced advance_in_slices(Simulation& run, double t_end, std::uint64_t& attempts,
                           const std::function<bool()>& go_on, std::uint64_t slice) {
  while (true) {
    if (!go_on()) return Advanced::stopped_by_caller;
    std::uint64_t given = std::min(slice, attempts);
    const std::uint64_t before = given;
    const bool reached = advance_within(run, t_end, given);
    attempts -= before - given;
    if (reached) return Advanced::reached;
    if (attempts == 0) return Advanced::out_of_attempts;
  }
}

}  // namespace spinfold
