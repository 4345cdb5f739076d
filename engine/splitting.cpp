#include "engine/splitting.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/body_forces.h"
#include "engine/chart.h"
#include "engine/exact_solution.h"
#include "engine/inertia.h"
#include "engine/potentials.h"

namespace spinfold {

namespace {

// Flow of H_B for time h: X and L stay, V and M receive the potential forces (physics.md §7).
void kick(const Scene& scene, const Chart& chart, double h, BodyKinematics& body) {
  const Surface& surface = scene.surface;
  if (scene.potential.radial) {
    // ∂V_r/∂X at the global point, pulled back to chart coordinates (covector: Aᵀ), then raised
    // and projected: the surface gradient P(η ∂V_r/∂X).
    const Vec3 covector = chart.A.transpose() * radial_potential_gradient(surface, *scene.potential.radial,
                                                                          chart.A * body.X + chart.b);
    body.V -= (h / scene.body.mass) * tangential(surface, body.X, raise(surface, covector));
  }
  if (!std::holds_alternative<std::monostate>(scene.potential.height)) {
    // V_h(z) of the global point's height (the sphere): ∂V_h/∂X = V_h′ ẑ, pulled back and projected
    // as above.
    const double z = (chart.A * body.X + chart.b).z();
    const Vec3 covector =
        chart.A.transpose() * Vec3(0.0, 0.0, height_slope(scene.potential.height, scene.body.mass, z));
    body.V -= (h / scene.body.mass) * tangential(surface, body.X, raise(surface, covector));
  }
  if (scene.body.model == BodyModel::incompressible) return;  // its deformation forces act in rattle()
  // The deformation forces outside the exact flow: the polar potential, and the abc potential when
  // the inertia is anisotropic (its internal closed form needs isotropic J). P −= h ∂V/∂L, M = PJ⁻¹.
  const bool abc_kicked =
      !isotropic_inertia(scene.body) && std::holds_alternative<AbcPotential>(scene.potential.deformation);
  if (std::holds_alternative<PolarPotential>(scene.potential.deformation) || abc_kicked) {
    const DeformationInvariants inv = deformation_invariants(body.L);
    const Mat2 force =
        deformation_gradient(deformation_potential(scene.potential.deformation, inv.a, inv.b), body.L);
    const Inertia inertia = inertia_of(scene.body);
    if (inertia.isotropic)
      body.M -= (h / inertia.J) * force;
    else
      body.M -= h * rate_from_momentum(inertia, force);
  }
}

// cof X = [[X₂₂, −X₂₁], [−X₁₂, X₁₁]] = ∂ det X/∂X.
Mat2 cofactor(const Mat2& X) {
  Mat2 c;
  c << X(1, 1), -X(1, 0), -X(0, 1), X(0, 0);
  return c;
}

// −∂V/∂L for the scene's deformation potential.
Mat2 deformation_force(const Scene& scene, const Mat2& L) {
  if (!has_deformation_potential(scene.potential)) return Mat2::Zero();
  const DeformationInvariants inv = deformation_invariants(L);
  return -deformation_gradient(deformation_potential(scene.potential.deformation, inv.a, inv.b), L);
}

// One RATTLE step of the internal motion at a fixed point on the level set det L = c (physics.md §15):
//   P½ = P + (h/2)(F(L) − λ cof L),  L′ = L + h P½ J⁻¹ with λ such that det L′ = c,
//   P′ = P½ + (h/2)(F(L′) − μ cof L′) with μ such that tr(cof(L′)ᵀ P′ J⁻¹) = 0 (d det L/dt = 0).
// det(A − κB) = det A − κ tr(cof(A)ᵀB) + κ² det B is quadratic in κ = λh²/2: the root nearest 0.
// Symmetric and symplectic; the constraint residual is round-off. Commutes with left rotations.
void rattle(const Scene& scene, double h, BodyKinematics& body) {
  const Inertia inertia = inertia_of(scene.body);
  const double c = scene.initial.lambda * scene.initial.mu;
  const Mat2 L = body.L, P = momentum_from_rate(inertia, body.M), G = cofactor(L);
  const Mat2 A = L + h * rate_from_momentum(inertia, P + 0.5 * h * deformation_force(scene, L));
  const Mat2 B = rate_from_momentum(inertia, G);
  const double a2 = B.determinant(), a1 = -cofactor(A).cwiseProduct(B).sum(), a0 = A.determinant() - c;
  // a2 κ² + a1 κ + a0 = 0; κ → 0 with h: the root −2a0/(a1 ∓ √(a1² − 4a2a0)) with the sign of a1.
  const double disc = std::max(0.0, a1 * a1 - 4.0 * a2 * a0);
  const double denominator = a1 + std::copysign(std::sqrt(disc), a1);
  const double kappa = denominator != 0.0 ? -2.0 * a0 / denominator : 0.0;
  const Mat2 L1 = A - kappa * B;
  const Mat2 P_half = P + 0.5 * h * deformation_force(scene, L) - (kappa / h) * G;  // λh/2 = κ/h
  const Mat2 G1 = cofactor(L1);
  const Mat2 Q = P_half + 0.5 * h * deformation_force(scene, L1);
  const double mu = G1.cwiseProduct(rate_from_momentum(inertia, Q)).sum() /
                    G1.cwiseProduct(rate_from_momentum(inertia, G1)).sum();  // (h/2)μ
  body.L = L1;
  body.M = rate_from_momentum(inertia, Q - mu * G1);
}

}  // namespace

StepResult SplittingComposition::try_step(const StepProblem& problem, const Coords& y, double h,
                                          double /*tolerance*/, Coords& increment) {
  // The flows it composes are the constant-curvature chart's (physics.md §10): a field given as a
  // function (a surface whose curvature varies) is not theirs to split.
  if (problem.field) throw std::logic_error("a splitting method steps only the scene's chart equations");
  const Scene& scene = problem.scene;
  AbcPotential internal;  // the part of V_def inside the exact flow (isotropic J only, physics.md §13)
  if (const auto* abc = std::get_if<AbcPotential>(&scene.potential.deformation))
    if (isotropic_inertia(scene.body)) internal = *abc;
  BodyKinematics body = chart_kinematics(scene, y);
  kick(scene, problem.chart, 0.5 * weights_.front() * h, body);
  for (std::size_t i = 0; i < weights_.size(); ++i) {
    body = integrable_flow(scene, internal, body, weights_[i] * h);
    // The RATTLE step commutes with the orbit's flow and the radial kicks (both only turn L and P by
    // left rotations or leave them), so each Strang sub-step stays symmetric (physics.md §15).
    if (scene.body.model == BodyModel::incompressible) rattle(scene, weights_[i] * h, body);
    const double next = i + 1 < weights_.size() ? weights_[i + 1] : 0.0;
    kick(scene, problem.chart, 0.5 * (weights_[i] + next) * h, body);  // adjacent half-kicks merged
  }
  increment = chart_coords(scene, body) - y;
  return {true, h};
}

}  // namespace spinfold
