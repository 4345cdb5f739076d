// Potential energies U = V_r + V_def (physics.md §5).
#pragma once

#include "engine/scene.h"

namespace spinfold {

// Γ = V_r·S² with S measured from the global pole: g R² on S², g on H² and the plane.
double radial_strength(const Surface& surface, const RadialPotential& radial);

// V_r at a point given by its global embedding X: Γ/ρ², ρ² = X₁² + X₂² (= S(r)²).
// Written through ρ² so that it stays accurate near the poles, where 1 − cos² would cancel.
double radial_potential(const Surface& surface, const RadialPotential& radial, const Vec3& X_global);
// ∂V_r/∂X (an ambient covector) at the global point X: −2Γ/ρ⁴ (X₁, X₂, 0).
Vec3 radial_potential_gradient(const Surface& surface, const RadialPotential& radial, const Vec3& X_global);

// The deformation invariants a = x² and b = y² of L, without cancellation (physics.md §2):
// with u = (L₁₁ − L₂₂)/2, v = (L₁₂ + L₂₁)/2, p = (L₁₁ + L₂₂)/2, q = (L₂₁ − L₁₂)/2,
// a = 2(u² + v²), b = 2(p² + q²).
struct DeformationInvariants {
  double a;  // x² = ‖L‖²/2 − det L
  double b;  // y² = ‖L‖²/2 + det L
};
DeformationInvariants deformation_invariants(const Mat2& L);

// V(a, b) and its partial derivatives V_a = ∂V/∂a, V_b = ∂V/∂b.
struct DeformationEnergy {
  double value = 0.0;
  double dV_da = 0.0;
  double dV_db = 0.0;
};
DeformationEnergy deformation_potential(const DeformationPotential& potential, double a, double b);

// ∂V/∂L = V_a (L − cof L) + V_b (L + cof L), cof L = [[L₂₂, −L₂₁], [−L₁₂, L₁₁]] (physics.md §4).
Mat2 deformation_gradient(const DeformationEnergy& energy, const Mat2& L);

bool has_deformation_potential(const Potentials& potentials);

}  // namespace spinfold
