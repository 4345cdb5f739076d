// The body's equations of motion in the embedding ℝ³ of an implicit surface F(X) = 0
// (physics-surfaces.md §7, with §5's potentials and §13's friction). Chart-free: regular at axis
// points, and built from F, ∇F and Hess F only, so they hold on any implicit surface.
#pragma once

#include <Eigen/Dense>

#include "engine/body_forces.h"
#include "engine/revolution.h"

namespace spinfold {

// Y = [X, V, e₁, e₂, W₁, W₂] ∈ ℝ¹⁸: position, velocity, the body's frame vectors and their covariant
// rates W_A = De_A/Dt (all tangent) [length, length/time, …].
using Embedded = Eigen::Matrix<double, 18, 1>;
// The rigid body (§7): [X, V, e₁, s] ∈ ℝ¹⁰; e₂ = n × e₁, W_A = (s/I) n × e_A, I = |e₁|² tr J.
using EmbeddedRigid = Eigen::Matrix<double, 10, 1>;

namespace embedded {
inline constexpr int X = 0, V = 3, e1 = 6, e2 = 9, W1 = 12, W2 = 15;
inline constexpr int spin = 9;  // rigid: s
}  // namespace embedded

// The orbit alone (§4, decoupling: the orbit sees the body only through its constant spin s):
// [X, V, E, τ] ∈ ℝ¹⁰, E a tangent vector carried by parallel transport (DE/Dt = 0) and τ the time
// since E was set [length, length/time, 1, time]. The internal motion is the flat one in the frame
// (E, n × E).
using EmbeddedOrbit = Eigen::Matrix<double, 10, 1>;
namespace embedded_orbit {
inline constexpr int X = 0, V = 3, E = 6, tau = 9;
}  // namespace embedded_orbit

struct EmbeddedModel {
  const ImplicitSurface& surface;
  SurfaceBody body;
};

// dY/dt (§7), with g = ∇F, H = Hess F, ν = |g|, n = g/ν, Π = I − n nᵀ, Dn = ΠH/ν:
//   dX/dt = V
//   dV/dt = (1/m) Π[−V_h′(z) ẑ + J^{AB}(Dnᵀ W_A ⟨e_B, Dn V⟩ − Dnᵀ e_A ⟨W_B, Dn V⟩) − γ_t V] − (VᵀHV/ν²) g
//   de_A/dt = W_A − (e_Aᵀ H V/ν²) g
//   dW_A/dt = −(J⁻¹)_{AB} Π(∂V_def/∂e_B + γ_i W_B) − (W_Aᵀ H V/ν²) g
// The normal terms keep ⟨g, V⟩, ⟨g, e_A⟩, ⟨g, W_A⟩ exact invariants of the flow.
void embedded_vector_field(const EmbeddedModel& model, const Embedded& Y, Embedded& dYdt);

// dY/dt for the rigid body: dV/dt = (K s n × V − Π(V_h′ ẑ + γ_t V))/m − (VᵀHV/ν²) g with K from the
// bordered Hessian; de₁/dt = (s/I) n × e₁ − (e₁ᵀHV/ν²) g; ds/dt = −(2γ_i|e₁|²/I) s.
void embedded_rigid_vector_field(const EmbeddedModel& model, const EmbeddedRigid& Y, EmbeddedRigid& dYdt);

// dY/dt of the orbit alone, for a body of constant spin s without internal friction: dV/dt as the rigid
// body's, dE/dt = −(EᵀHV/ν²) g (parallel transport), dτ/dt = 1.
void embedded_orbit_vector_field(const EmbeddedModel& model, double s, const EmbeddedOrbit& Y,
                                 EmbeddedOrbit& dYdt);

// The unit normal n = ∇F/|∇F| at X.
Vec3 embedded_normal(const ImplicitSurface& surface, const Vec3& X);

// s = Σ J^{AB} det[e_A, W_B, n] [angular momentum] (§6).
double embedded_spin(const EmbeddedModel& model, const Embedded& Y);
// det L = det[e₁, e₂, n].
double embedded_det_L(const EmbeddedModel& model, const Embedded& Y);

struct EmbeddedEnergy {
  double orbital = 0.0;      // E_orb = m|V|²/2 + V_h [energy]
  double deformation = 0.0;  // E_def = ½J^{AB}⟨W_A, W_B⟩ + V_def [energy]
  double total() const { return orbital + deformation; }
};
EmbeddedEnergy embedded_energy(const EmbeddedModel& model, const Embedded& Y);
// E = m|V|²/2 + s²/(2I) + V_h for the rigid body.
double embedded_rigid_energy(const EmbeddedModel& model, const EmbeddedRigid& Y);

// p_φ = m (X × V)·ẑ + s n·ẑ: the momentum of the rotation about the z-axis (§6), conserved on a
// surface of revolution about that axis without friction.
double embedded_axial_momentum(const EmbeddedModel& model, const Embedded& Y);

// Rayleigh's R = γ_t/2 |V|² + γ_i/2 Σ|W_A|²: without a height potential's work, dE/dt = −2R (§13).
double embedded_rayleigh(const EmbeddedModel& model, const Embedded& Y);

}  // namespace spinfold
