#include "engine/state.h"

namespace spinfold {

std::string_view status_name(Status status) {
  switch (status) {
    case Status::ok: return "ok";
    case Status::non_finite: return "non_finite";
    case Status::step_failed: return "step_failed";
    case Status::degenerate_frame: return "degenerate_frame";
    case Status::out_of_range: return "out_of_range";
    case Status::diverged: return "diverged";
  }
  return "unknown";
}

}  // namespace spinfold
