// Action variables J_i = ∮ p_i dq_i of the separable scenes and their frequencies ν_i = ∂E/∂J_i
// (physics.md §8.10, §14). Nouns: they only answer.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/paper_coordinates.h"
#include "engine/scene.h"
#include "engine/state.h"

namespace spinfold {

// Actions in the paper's normalisation J = ∮ p dq (so J_φ = 2πp_φ) [mass·length²/time], and
// ν = ∂E/∂J [1/time], the number of cycles per unit time: r(t), x²(t) and y²(t) repeat with the
// periods 1/ν_r, 1/ν_x, 1/ν_y. A value that is undefined at this state is absent and `undefined`
// names it ("J_r", "nu_x", ...) with the reason (an unbounded orbit on H², a separatrix, no
// deformation potential to bound x², a rigid body).
struct ActionVariables {
  std::optional<double> J_r, J_phi, J_alpha, J_beta, J_x, J_y;  // [mass·length²/time]
  std::optional<double> nu_r, nu_x, nu_y;                       // [1/time]
  // ∂E/∂J_φ [1/time]: φ advances by 2πν_φ/ν_r per period of r (the mean precession of the orbit)
  std::optional<double> nu_phi;
  std::vector<UndefinedValue> undefined;
};

// Why the scene has no action variables here (not separable: the polar potential, anisotropic
// inertia, the plane), or nullopt when it has them.
std::optional<std::string> actions_unsupported_reason(const Scene& scene);

// The action variables at a state of a supported scene (physics.md §8.10):
//   J_φ = 2πp_φ, J_α = 2πs, J_β = 2πp_β; with E′ = E_orb, k = 8π²mΓ (Γ = V_r S², §5),
//   S²: J_r = √(8π²mR²E′ + J_α²) − ½√(k + (J_φ+J_α)²) − ½√(k + (J_φ−J_α)²),
//   H² (bounded, J_α² > 8π²mR²E′): J_r = −√(J_α² − 8π²mR²E′) + ½√(k + (J_φ+J_α)²) − ½√(k + (J_φ−J_α)²),
//   abc with C > 0: J_x = πC_x√(J/2C) − π√(2JA + p_γ²), J_y = πC_y√(J/2C) − π√(2JB + p_δ²),
//   ν_r = √|8π²mR²E′ ± J_α²|/(4π²mR²), ν_x = ν_y = √(2C/J)/π, and ν_φ = ∂E/∂J_φ from J_r's
//   dependence on J_φ at fixed J_r (physics.md §14).
ActionVariables action_variables(const Scene& scene, const State& state);

// H recomputed from the actions (the inverse of the formulas above): E_orb(J_r, J_φ, J_α) +
// C_x(J_x, J_α, J_β) + C_y(J_y, J_α, J_β) (rigid: + s²/(4Jλ₀²)); nullopt when an action it needs is
// undefined.
std::optional<double> energy_from_actions(const Scene& scene, const ActionVariables& actions);

}  // namespace spinfold
