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

// Radial potential and its chart derivatives at a chart point.
struct RadialTerms {
  double value = 0.0;
  double d_dr = 0.0;
  double d_dphi = 0.0;
};
RadialTerms radial_terms(const Scene& scene, const Chart& chart, double r, double phi);

// H = p_r²/2m + (p_φ − Cs)²/(2mS²) + ½tr(PJ⁻¹Pᵀ) + V_r + V_def   (rigid: s²/(4Jλ₀²) for the internal
// part, J = tr(J)/2); ½tr(PJ⁻¹Pᵀ) = ‖P‖²/2J for isotropic J (physics.md §4, §13)
double hamiltonian(const Scene& scene, const Chart& chart, const Coords& y);

// H split into its kinetic part (orbital, spin and deformation rates) and its potential part.
struct EnergyParts {
  double kinetic = 0.0;    // [energy]
  double potential = 0.0;  // [energy]
};
EnergyParts energy_parts(const Scene& scene, const Chart& chart, const Coords& y);

// dy/dt = X_H(y):
//   ṙ = p_r/m, φ̇ = Π/(mS²), ṗ_r = CΠ²/(mS³) − KsΠ/(mS) − ∂V_r/∂r, ṗ_φ = −∂V_r/∂φ, Π = p_φ − Cs,
//   L̇ = PJ⁻¹ − Cφ̇εL, Ṗ = −∂V/∂L − Cφ̇εP   (rigid: θ̇ = s/(2Jλ₀²) − Cφ̇, ṡ = 0; physics.md §13).
// ∂V_r/∂φ vanishes in the global chart; in a moved chart the radial centre is off the chart pole.
void vector_field(const Scene& scene, const Chart& chart, const Coords& y, Coords& dydt);

}  // namespace spinfold
