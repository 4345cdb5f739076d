#include "engine/splitting.h"

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

}  // namespace

StepResult SplittingComposition::try_step(const StepProblem& problem, const Coords& y, double h,
                                          double /*tolerance*/, Coords& increment) {
  const Scene& scene = problem.scene;
  AbcPotential internal;  // the part of V_def inside the exact flow (isotropic J only, physics.md §13)
  if (const auto* abc = std::get_if<AbcPotential>(&scene.potential.deformation))
    if (isotropic_inertia(scene.body)) internal = *abc;
  BodyKinematics body = chart_kinematics(scene, y);
  kick(scene, problem.chart, 0.5 * weights_.front() * h, body);
  for (std::size_t i = 0; i < weights_.size(); ++i) {
    body = integrable_flow(scene, internal, body, weights_[i] * h);
    const double next = i + 1 < weights_.size() ? weights_[i + 1] : 0.0;
    kick(scene, problem.chart, 0.5 * (weights_[i] + next) * h, body);  // adjacent half-kicks merged
  }
  increment = chart_coords(scene, body) - y;
  return {true, h};
}

}  // namespace spinfold
