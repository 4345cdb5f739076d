// Conserved quantities as functions of a state (physics.md §6). Nouns: they only answer.
#pragma once

#include <optional>

#include "engine/scene.h"
#include "engine/state.h"

namespace spinfold {

// The body in the scene's (global) coordinates, read off its chart (physics.md §7 conversions).
// Far out on H² the chart keeps every number moderate; only X and V carry the e^{r/R} growth.
struct GlobalBody {
  Vec3 X;                // embedding position [length]
  Vec3 V;                // embedding velocity [length/time]
  double r = 0.0;        // geodesic distance from the global pole [length]
  double phi = 0.0;      // [rad], meaningful only when !at_pole
  double S = 0.0;        // S(r) = √(X₁² + X₂²) [length]
  double C = 1.0;        // C(r)
  bool at_pole = false;  // φ and the paper's frame (E₁, E₂) are undefined here
  Mat2 L;                // internal matrix in (E₁, E₂) (any fixed frame at a pole)
  Mat2 M;                // L̇ + Cφ̇εL in the same frame [1/time]
  double r_dot = 0.0;    // [length/time]
  double phi_dot = 0.0;  // [rad/time]
  double spin = 0.0;     // s
};
GlobalBody global_body(const Scene& scene, const State& state);

// H (physics.md §4), conserved.
double energy(const Scene& scene, const State& state);
// E_orb = m⟨V,V⟩/2 + V_r and E_def = H − E_orb, conserved separately.
double orbital_energy(const Scene& scene, const State& state);
double deformation_energy(const Scene& scene, const State& state);
// Spin s = p_α and vorticity p_β = −tr((Lε)ᵀP).
double spin(const Scene& scene, const State& state);
double vorticity(const Scene& scene, const State& state);
// p_φ of the scene's chart (= M₃), conserved for every potential here. Far out on H² it is the
// small difference of numbers of size e^{r/R}: angular_momentum_rounding bounds its rounding error.
double angular_momentum(const Scene& scene, const State& state);
double angular_momentum_rounding(const Scene& scene, const State& state);

// The momentum map (physics.md §6) of the body in its chart's coordinates, where every number is
// moderate, and carried to the scene's coordinates by the chart's isometry: M = det(A)·ηAη·M_chart
// (S², H²). `rounding` bounds each global component's absolute rounding error: far out on H² the
// entries of A grow like e^{r/R} and the components keep only their leading digits.
struct ChartMomentum {
  Vec3 local;     // in the chart's coordinates
  Vec3 global;    // in the scene's coordinates
  Vec3 rounding;  // per component of `global`
};
ChartMomentum chart_momentum(const Scene& scene, const State& state);

// True when a value with this rounding bound keeps at least 8 digits of `scale` (its own size plus
// the size of what it is made of in the body's chart).
bool well_conditioned(double rounding, double scale);

// C_x, C_y of the abc model (or no deformation potential), affine bodies only (physics.md §6),
// in the cancellation-free form J(u_M² + v_M²) + A/x² + Cx².
struct SeparatedEnergies {
  double C_x;
  double C_y;
};
std::optional<SeparatedEnergies> separated_energies(const Scene& scene, const State& state);

// Momentum map M = m X × V + K R s ηX (so(3) on S², so(2,1) on H²; on the plane the linear
// momentum and p_φ); conserved only without a radial potential.
std::optional<Vec3> momentum_map(const Scene& scene, const State& state);
// Casimir MᵀηM = m²R²v² + σs² (S², H²); invariant under the chart's isometry, so take M in the
// body's chart (ChartMomentum::local), never the cancelling global one.
double casimir(const Surface& surface, const Vec3& M);

}  // namespace spinfold
