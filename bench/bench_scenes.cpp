#include "bench/bench_scenes.h"

#include <cmath>
#include <numbers>

#include "engine/chart.h"
#include "engine/invariants.h"
#include "engine/simulation.h"
#include "engine/worked_examples.h"

namespace spinfold::bench {

namespace {

Scene rigid_spinning(SurfaceKind kind) {
  Scene s;
  s.surface = {kind, 1.0};
  s.body = {1.0, 0.5, BodyModel::rigid};
  s.initial.r = 1.0;
  s.initial.lambda = s.initial.mu = 1.0;
  const double S = polar_S(s.surface, 1.0), C = polar_C(s.surface, 1.0);
  s.initial.phi_dot = 0.5 / S;                        // speed 0.5 along E₂
  s.initial.alpha_dot = 1.0 - C * s.initial.phi_dot;  // spin s = 1 (physics.md W3, W4)
  return s;
}

Scene deforming(SurfaceKind kind) {
  Scene s;
  s.surface = {kind, 1.0};
  s.body = {1.0, 0.3, BodyModel::affine};
  s.potential.deformation = AbcPotential{0.02, 0.1, 0.4};
  s.initial = {1.2, 0.0, 0.3, -0.4, 1.4, 0.6, 0.1, 0.5, 0.6, -0.2, 0.1, -0.05};
  if (offers(kind, Offer::negative_curvature)) {
    s.initial.alpha_dot = 2.0;  // spin > mvR: a bounded orbit (a circle for the orbit's centre)
    s.initial.phi_dot = 0.3;
  }
  return s;
}

}  // namespace

std::vector<BenchScene> work_precision_scenes() {
  std::vector<BenchScene> scenes;
  scenes.push_back(
      {"sphere_rigid", "S², spinning rigid body (W3), no potential", rigid_spinning(SurfaceKind::sphere)});
  scenes.push_back({"pseudosphere_rigid", "H², spinning rigid body on a circle (W4)",
                    rigid_spinning(SurfaceKind::pseudosphere)});
  scenes.push_back(
      {"sphere_deforming_abc", "S², deforming spinning body, abc potential", deforming(SurfaceKind::sphere)});
  scenes.push_back({"pseudosphere_deforming_abc", "H², deforming spinning body, abc potential, bounded",
                    deforming(SurfaceKind::pseudosphere)});
  const Scene w5 = w5_scene();
  scenes.push_back({"sphere_radial_abc", "S², radial + abc potentials (W5), numerical reference", w5});
  Scene polar = deforming(SurfaceKind::sphere);
  polar.potential.deformation = PolarPotential{0.05, -1.0, PolarForm::cot2};
  polar.initial.r = 1.3;
  scenes.push_back({"sphere_polar", "S², polar deformation potential, numerical reference", polar});
  // Anisotropic inertia (physics.md §13): W5 with J = [[0.3, 0.08], [0.08, 0.15]] (no closed form),
  // and the free deforming body with the same J (closed form: the free internal drift is J-independent).
  Scene w5_aniso = w5;
  w5_aniso.body.inertia_matrix = InertiaMatrix{0.3, 0.08, 0.08, 0.15};
  scenes.push_back(
      {"sphere_anisotropic_abc", "S², W5 with anisotropic inertia, numerical reference", w5_aniso});
  Scene free_aniso = deforming(SurfaceKind::sphere);
  free_aniso.potential.deformation = std::monostate{};
  free_aniso.body.inertia_matrix = InertiaMatrix{0.3, 0.08, 0.08, 0.15};
  scenes.push_back(
      {"sphere_anisotropic_free", "S², free deforming body with anisotropic inertia", free_aniso});
  return scenes;
}

double state_error(const Scene& scene, const State& a, const State& b) {
  return embedded_state_error(scene, a, b);
}

}  // namespace spinfold::bench
