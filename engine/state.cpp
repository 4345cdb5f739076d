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
    case Status::event_stop: return "event_stop";
    case Status::inconsistent: return "inconsistent";
    case Status::event_unresolved: return "event_unresolved";
    case Status::too_many_events: return "too_many_events";
  }
  return "unknown";
}

std::string_view status_description(Status status) {
  switch (status) {
    case Status::ok: return "ok: every step so far passed its checks";
    case Status::non_finite:
      return "stopped: a step produced a number that is not finite; the state is the last good one "
             "(lower dt or the tolerance, or change the parameters)";
    case Status::step_failed:
      return "stopped: the step size collapsed (a stiff or singular motion, or an implicit stage that "
             "did not converge); the state is the last good one";
    case Status::degenerate_frame:
      return "stopped: det L reached 0 and the scene asks to stop there (on_degenerate: stop); the state "
             "is the last one with det L > 0";
    case Status::out_of_range:
      return "stopped: the body went farther than 250 R out on the pseudosphere, beyond what the global "
             "coordinates hold in double; the state is the last one within";
    case Status::diverged:
      return "stopped: the energy error grew as large as the energy itself, so the step is beyond this "
             "integrator's stability; the state is the last good one (lower dt, or use auto)";
    case Status::event_stop:
      return "stopped: a watched field crossed its level as many times as the run asked to stop at (an "
             "event's stop=N); the state is the crossing's";
    case Status::event_unresolved:
      return "stopped: an event's levels (level + k·period) are closer together than double precision "
             "tells apart where its field now is (a period below 1e-12 of the field's size), or were "
             "crossed more than 2^53 times; the state is the start of the step that met them (choose a "
             "larger period)";
    case Status::too_many_events:
      return "stopped: det L crossed zero more than 100000 times in the run (each crossing is kept to be "
             "reported); the state is the last before the crossing past that (run it in shorter pieces, "
             "or stop at the first crossing: on_degenerate stop)";
    case Status::inconsistent:
      return "stopped: the closed form failed its consistency check (its start or its conserved quantities "
             "disagree with the run's by more than 1e-8, or can no longer be checked to that, e.g. a motion "
             "whose energy grew 1e6-fold); the state is the last one that passed (use dop853 or gauss6)";
  }
  return "unknown";
}

}  // namespace spinfold
