// Hamilton's equations in the singularity-free (L, P) form on a polar chart (physics.md §4).
#pragma once

#include "engine/scene.h"
#include "engine/state.h"

namespace spinfold {

// ε = [[0, −1], [1, 0]].
Mat2 epsilon();
// L and M = L̇ + Cφ̇εL = PJ⁻¹ for either model; the rigid model has L = λ₀U(θ), M = ωεL with
// ω = s/(2Jλ₀²) (physics.md §8.8).
struct InternalState {
  Mat2 L;
  Mat2 M;  // [1/time]
};
InternalState internal_state(const Scene& scene, const Coords& y);

// Spin s = tr((εL)ᵀP) (affine) or the stored s (rigid) [angular momentum].
double spin_of(const Scene& scene, const Coords& y);

// The orbit's potential at a chart point, V_r + V_h, and its chart derivatives: the radial potential
// about the pole (physics.md §5) and the height potential V_h(z) of the embedded height z
// (physics-surfaces.md §5; among the constant kinds only the sphere has one).
struct OrbitPotential {
  double value = 0.0;   // [energy]
  double d_dr = 0.0;    // [energy/length]
  double d_dphi = 0.0;  // [energy]
};
OrbitPotential orbit_potential(const Scene& scene, const Chart& chart, double r, double phi);

// H = p_r²/2m + (p_φ − Cs)²/(2mS²) + ½tr(PJ⁻¹Pᵀ) + V_r + V_h + V_def   (rigid: s²/(4Jλ₀²) for the internal
// part, J = tr(J)/2); ½tr(PJ⁻¹Pᵀ) = ‖P‖²/2J for isotropic J (physics.md §4, §13)
double hamiltonian(const Scene& scene, const Chart& chart, const Coords& y);

// H split into its kinetic part (orbital, spin and deformation rates) and its potential part.
struct EnergyParts {
  double kinetic = 0.0;    // [energy]
  double potential = 0.0;  // [energy]
};
EnergyParts energy_parts(const Scene& scene, const Chart& chart, const Coords& y);

// dy/dt = X_H(y) + Q (Q: Rayleigh friction, physics-surfaces.md §13, absent without it):
//   ṙ = p_r/m, φ̇ = Π/(mS²), ṗ_r = CΠ²/(mS³) − KsΠ/(mS) − ∂V/∂r − γ_t p_r/m,
//   ṗ_φ = −∂V/∂φ − γ_t S²φ̇ − γ_i C tr((εL)ᵀM), Π = p_φ − Cs, M = PJ⁻¹,
//   L̇ = PJ⁻¹ − Cφ̇εL, Ṗ = −∂V/∂L − Cφ̇εP − γ_i M
//   (rigid: θ̇ = s/(2Jλ₀²) − Cφ̇, ṡ = −γ_i s/J, and tr((εL)ᵀM) = s/J; physics.md §13).
// V = V_r + V_h; ∂V/∂φ vanishes in the global chart, not in a moved one (the potential's centre or
// axis is off the chart's pole).
void vector_field(const Scene& scene, const Chart& chart, const Coords& y, Coords& dydt);

}  // namespace spinfold
