// The guiding centre of a fast spinner on a surface of revolution (physics-surfaces.md §10.2): a
// body whose Larmor radius r_L = m v/|s K| is small against the surface's features gyrates about a
// centre that drifts along the parallel (a line of constant K, B = K s) at the grad-B rate
//   φ̇_d = −m v² K_u / (2 s K² f ρ)   [rad/time],
// the direction set by the sign of s. To O(r_L²): 0.976 of the measured mean rate at r_L = 0.09 on
// the oblate spheroid a = 1, b = 0.6 (the opposite_spins_spheroid preset), 0.998 at r_L = 0.023.
// The picture draws it as an arrow at the body (the drift layer).
#pragma once

#include <optional>

#include "engine/simulation.h"

namespace spinfold {

struct GuidingDrift {
  double phi_rate = 0.0;          // φ̇_d, evaluated at the body [rad/time]
  double larmor_radius = 0.0;     // r_L [length]
  Vec3 direction = Vec3::Zero();  // the drift's unit direction at X, ±∂/∂φ/ρ in ℝ³
};

// The drift of the run's body now; none off a profile chart, with friction or a height potential,
// where s K = 0 or K_u = 0 (no field, or no gradient: the round sphere), on the axis (ρ = 0), or
// where r_L exceeds a quarter of the surface's feature (no guiding centre to speak of).
std::optional<GuidingDrift> guiding_drift(const Simulation& run);

}  // namespace spinfold
