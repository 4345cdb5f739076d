// The body on a surface of revolution in the chart (u, φ) (physics-surfaces.md §3, §4, §13): the (L, P)
// Hamiltonian with S → ρ(u), C → C(u) = ρ_u/f, and the conversions between the chart and the
// embedding (§7 "Conversions"). Singular where ρ = 0 (an axis point, §8): there the chart-free
// equations (embedded_dynamics.h) are used.
#pragma once

#include <Eigen/Dense>

#include "engine/body_forces.h"
#include "engine/embedded_dynamics.h"
#include "engine/revolution.h"

namespace spinfold {

// w = [u, φ, L₁₁, L₁₂, L₂₁, L₂₂, p_u, p_φ, P₁₁, P₁₂, P₂₁, P₂₂] (§11's layout); L in the frame
// (E₁ = X_u/f, E₂ = X_φ/ρ), P = M J with M = L̇ + C φ̇ ε L.
using RevolutionCoords = Eigen::Matrix<double, 12, 1>;
// The rigid body: [u, φ, θ, p_u, p_φ, s] (L = λ₀ U(θ)).
using RevolutionRigidCoords = Eigen::Matrix<double, 6, 1>;

namespace revolution_coord {
inline constexpr int u = 0, phi = 1, L = 2, p_u = 6, p_phi = 7, P = 8;
inline constexpr int theta = 2, rigid_p_u = 3, rigid_p_phi = 4, spin = 5;
}  // namespace revolution_coord

struct RevolutionModel {
  RevolutionSurface surface;
  SurfaceBody body;
};

// The generalised state: chart position, L, and their rates.
struct RevolutionRates {
  double u = 0.0, phi = 0.0;
  Mat2 L = Mat2::Identity();
  double u_dot = 0.0, phi_dot = 0.0;
  Mat2 L_dot = Mat2::Zero();
};

// p_u = m f² u̇, p_φ = m ρ² φ̇ + C s, P = (L̇ + C φ̇ ε L) J, s = tr((εL)ᵀ P).
RevolutionCoords revolution_coords(const RevolutionModel& model, const RevolutionRates& rates);

// s = tr((εL)ᵀ P) [angular momentum].
double revolution_spin(const RevolutionCoords& w);

// H = p_u²/(2mf²) + (p_φ − Cs)²/(2mρ²) + ½tr(PJ⁻¹Pᵀ) + V_h(z(u)) + V_def(L) (§4), split as E_orb + E_def.
EmbeddedEnergy revolution_energy(const RevolutionModel& model, const RevolutionCoords& w);

// Hamilton's equations with Π = p_φ − Cs and §13's friction (M = P J⁻¹):
//   u̇ = p_u/(mf²), φ̇ = Π/(mρ²), L̇ = PJ⁻¹ − Cφ̇εL, Ṗ = −∂V_def/∂L − Cφ̇εP − γ_i M,
//   ṗ_u = p_u² f_u/(mf³) + Π²ρ_u/(mρ³) + C_u sΠ/(mρ²) − V_h′(z) z_u − γ_t p_u/m,
//   ṗ_φ = −γ_t ρ² φ̇ − γ_i C tr((εL)ᵀ M).
void revolution_vector_field(const RevolutionModel& model, const RevolutionCoords& w, RevolutionCoords& dwdt);

// The rigid body (§4): u̇, φ̇, ṗ_u as above, θ̇ = s/I − Cφ̇, ṡ = −(2γ_iλ₀²/I) s, ṗ_φ = −γ_t ρ²φ̇ + C ṡ,
// with I = λ₀² tr J.
void revolution_rigid_vector_field(const RevolutionModel& model, double lambda0,
                                   const RevolutionRigidCoords& w, RevolutionRigidCoords& dwdt);

// Chart → embedding: X, E₁, E₂ at (u, φ); V = f u̇ E₁ + ρ φ̇ E₂; e_A = E_B L_BA; W_A = E_B M_BA.
Embedded embed(const RevolutionModel& model, const RevolutionCoords& w);
EmbeddedRigid embed_rigid(const RevolutionModel& model, double lambda0, const RevolutionRigidCoords& w);

// Embedding → chart, away from axis points: u from the surface's inverse map, φ = atan2(y, x),
// L_BA = ⟨E_B, e_A⟩, M_BA = ⟨E_B, W_A⟩, P = M J, p_u = m f² ⟨V, E₁⟩/f, p_φ = m ρ ⟨V, E₂⟩ + C s.
RevolutionCoords chart_of(const RevolutionModel& model, const Embedded& Y);

}  // namespace spinfold
