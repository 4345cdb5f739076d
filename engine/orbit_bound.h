// Whether a body on a surface of revolution is held or gets away, from what its orbit conserves
// (physics-surfaces.md §6, §10.3): without friction or a potential, p_φ and the orbital energy are
// constants and the profile coordinate obeys (m/2) f(u)² u̇² + V_eff(u) = E_orb, with
//   V_eff(u) = (p_φ − s C(u))² / (2 m ρ(u)²),   C = dρ/ds the frame's connection (1 on a top axis),
// so the body moves between the turning points where V_eff = E_orb, and escapes along an unbounded
// profile (the bump's plane, the catenoid's flares) where no turning point lies that way. The HUD
// tags each body on such a surface "trapped" or "escapes"; tests check it against the runs.
#pragma once

#include <optional>
#include <string>

#include "engine/simulation.h"

namespace spinfold {

struct OrbitBound {
  // held: between turning points u_low and u_high (an axis end of the profile stands for one);
  // escapes: no turning point towards an unbounded end; none: no verdict (`why_none` says why:
  // no profile chart, a closed profile that holds every orbit, friction or a height potential).
  enum class Verdict { none, held, escapes };
  Verdict verdict = Verdict::none;
  double u_low = 0.0, u_high = 0.0;  // [u's unit] the range allowed (±inf towards an escape)
  // For a start on an axis point (the bump's top): the spin |s| above which the body is held, at
  // the start's speed v: s_crit = m v / max_u |C_axis − C(u)|/ρ(u) (5.64742 v on the bump h = w = 1).
  std::optional<double> critical_spin;
  std::string why_none;
};

// Of the run's body now (a companion's run too). The turning points are searched from u within
// 40 features (ProfilePicture::feature) each way, at 1/64 of one, then bisected: beyond that
// V_eff falls as 1/ρ² on every unbounded profile we have (the curvature has died away).
OrbitBound orbit_bound(const Simulation& run);

// The HUD's words for it, appended to the body's line: "  trapped (|s| > s_crit = 2.8237)",
// "  escapes", …; "" where there is no verdict.
std::string orbit_bound_note(const OrbitBound& bound);

}  // namespace spinfold
