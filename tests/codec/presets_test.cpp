// Each preset's one-line claim, checked against the engine.
#include "codec/presets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "codec/scene_json.h"
#include "engine/actions.h"
#include "engine/chart.h"
#include "engine/invariants.h"
#include "engine/paper_coordinates.h"
#include "engine/potentials.h"
#include "engine/simulation.h"

namespace spinfold {
namespace {

Scene preset(std::string_view name) {
  const PresetSource* p = find_preset(name);
  EXPECT_NE(p, nullptr) << name;
  return *parse_scene_text(p->json).scene;
}

double angle_from_axis(const Vec3& X, const Vec3& M) {
  return std::acos(X.dot(M) / (X.norm() * M.norm()));
}

TEST(Presets, GeodesicBodyStaysOnAGreatCircleAndTheSpinningOneDoesNot) {
  for (const auto& [name, expected] : {std::pair{"geodesic_rigid_sphere", std::numbers::pi / 2},
                                       {"spinning_rigid_sphere", std::atan(0.5)}}) {
    const Scene scene = preset(name);
    Simulation run = start_simulation(scene);
    const Vec3 M = *momentum_map(scene, run.state);
    for (int k = 1; k <= 10; ++k) {
      advance_to(run, 1.0 * k);
      EXPECT_NEAR(angle_from_axis(global_embedding(scene, run.state).X, M), expected, 1e-8) << name;
    }
  }
}

TEST(Presets, PseudosphereSpinningBodyClosesACircleTurningAgainstItsSpin) {
  const Scene scene = preset("spinning_rigid_pseudosphere");
  Simulation run = start_simulation(scene);
  const EmbeddedBody b0 = global_embedding(scene, run.state);
  EXPECT_LT(casimir(scene.surface, *momentum_map(scene, run.state)), 0.0);  // a circle
  EXPECT_GT(spin(scene, run.state), 0.0);
  advance_to(run, 0.05);
  const EmbeddedBody b1 = global_embedding(scene, run.state);
  // Turning clockwise: the velocity rotates towards −j(v).
  EXPECT_LT(dot(scene.surface, b1.V - b0.V, rotate_quarter(scene.surface, b0.X, b0.V)), 0.0);
  advance_to(run, 7.255197456936871);
  EXPECT_LT((global_embedding(scene, run.state).X - b0.X).norm(), 1e-8);
}

TEST(Presets, NonSpinningBodyOnH2FollowsAGeodesic) {
  // A geodesic of H² is a plane section through the origin of ℝ^{2,1}: X·M = sR = 0 with s = 0.
  const Scene scene = preset("geodesic_rigid_pseudosphere");
  Simulation run = start_simulation(scene);
  EXPECT_NEAR(spin(scene, run.state), 0.0, 1e-15);
  const Vec3 M = *momentum_map(scene, run.state);
  for (int k = 1; k <= 5; ++k) {
    advance_to(run, 1.0 * k);
    const Vec3 X = global_embedding(scene, run.state).X;
    EXPECT_NEAR(X.dot(M) / (X.norm() * M.norm()), 0.0, 1e-12);
  }
}

TEST(Presets, DeformationCarriesSpinThatBendsThePathOnH2) {
  // α̇ = β̇: the frame's rotation part θ = α − β is still, yet the rotating deformed axes carry spin
  // s ≠ 0; the path's geodesic curvature is K s/(m v) (physics.md §8.5).
  const Scene scene = preset("deforming_spin_pseudosphere");
  Simulation run = start_simulation(scene);
  const double s = spin(scene, run.state);
  EXPECT_GT(std::abs(s), 0.1);
  const EmbeddedBody b0 = global_embedding(scene, run.state);
  const double v = std::sqrt(dot(scene.surface, b0.V, b0.V));
  const double h = 1e-3;
  advance_to(run, h);
  const Vec3 V1 = global_embedding(scene, run.state).V;
  const Vec3 a = tangential(scene.surface, b0.X, (V1 - b0.V) / h);
  const double kappa = dot(scene.surface, a, rotate_quarter(scene.surface, b0.X, b0.V)) / (v * v * v);
  EXPECT_NEAR(kappa, curvature(scene.surface) * s / (scene.body.mass * v),
              1e-2 * std::abs(kappa));  // O(h) difference
}

TEST(Presets, OnThePlaneTheSpinningBodyGoesStraight) {
  const Scene scene = preset("spinning_rigid_plane");
  Simulation run = start_simulation(scene);
  const EmbeddedBody b0 = global_embedding(scene, run.state);
  EXPECT_GT(spin(scene, run.state), 0.1);
  for (int k = 1; k <= 5; ++k) {
    advance_to(run, 2.0 * k);
    EXPECT_LT((global_embedding(scene, run.state).X - (b0.X + run.state.t * b0.V)).norm(), 1e-12);
  }
}

TEST(Presets, PoleCrossingPassesThroughThePole) {
  const Scene scene = preset("pole_crossing_sphere");
  Simulation run = start_simulation(scene);
  advance_to(run, 2.0);  // r = 1 − 0.5t
  EXPECT_LT(paper_coordinates(scene, run.state).r, 1e-8);
  advance_to(run, 4.0);
  EXPECT_NEAR(paper_coordinates(scene, run.state).r, 1.0, 1e-8);
}

TEST(Presets, BreathingEllipseHasTheIsotonicFrequency) {
  const Scene scene = preset("breathing_ellipse_sphere");
  const double C = std::get<AbcPotential>(scene.potential.deformation).C;
  const double period = 2.0 * std::numbers::pi / std::sqrt(8.0 * C / scene.body.inertia);
  Simulation run = start_simulation(scene);
  const auto x2 = [&] { return deformation_invariants(paper_coordinates(scene, run.state).L.value()).a; };
  const double x2_start = x2();
  advance_to(run, 0.5 * period);
  EXPECT_GT(std::abs(x2() - x2_start), 0.1);  // it does breathe
  advance_to(run, period);
  EXPECT_NEAR(x2(), x2_start, 1e-9);
}

TEST(Presets, AnisotropicBodyKeepsItsSpinWhileItsVorticityOscillates) {
  const Scene scene = preset("anisotropic_tumbling_sphere");
  ASSERT_TRUE(scene.body.inertia_matrix.has_value());
  Simulation run = start_simulation(scene);
  const double s0 = spin(scene, run.state), b0 = vorticity(scene, run.state);
  double ds = 0.0, b_min = b0, b_max = b0;
  for (int k = 1; k <= 40; ++k) {
    advance_to(run, 0.5 * k);
    ASSERT_EQ(run.state.status, Status::ok);
    ds = std::max(ds, std::abs(spin(scene, run.state) - s0));
    b_min = std::min(b_min, vorticity(scene, run.state));
    b_max = std::max(b_max, vorticity(scene, run.state));
  }
  EXPECT_LT(ds, 1e-9 * std::abs(s0));
  EXPECT_GT(b_max - b_min, 0.1 * std::abs(b0)) << b_min << " .. " << b_max;
  // The isotropic body with the same trace keeps its vorticity.
  Scene iso = scene;
  iso.body.inertia_matrix.reset();
  iso.body.inertia = 0.2;
  Simulation r = start_simulation(iso);
  const double c0 = vorticity(iso, r.state);
  advance_to(r, 20.0);
  EXPECT_NEAR(vorticity(iso, r.state), c0, 1e-9 * std::abs(c0));
}

TEST(Presets, ActionVariablesAreConstantAndTheFrequenciesArePeriods) {
  const Scene scene = preset("action_variables_sphere");
  Simulation run = start_simulation(scene);  // auto: the closed form
  const ActionVariables a0 = action_variables(scene, run.state);
  ASSERT_TRUE(a0.undefined.empty());
  const PaperCoordinates c0 = paper_coordinates(scene, run.state);
  const double T_r = 1.0 / *a0.nu_r, T_x = 1.0 / *a0.nu_x;
  const auto x2 = [&] { return deformation_invariants(paper_coordinates(scene, run.state).L.value()).a; };
  const double x2_0 = x2();
  advance_to(run, 3.0 * T_x);
  EXPECT_NEAR(x2(), x2_0, 1e-9);
  advance_to(run, 5.0 * T_r);
  const PaperCoordinates c = paper_coordinates(scene, run.state);
  EXPECT_NEAR(c.r, c0.r, 1e-9);
  EXPECT_NEAR(c.r_dot.value(), c0.r_dot.value(), 1e-9);
  const ActionVariables a = action_variables(scene, run.state);
  EXPECT_NEAR(*a.J_r, *a0.J_r, 1e-9);
  EXPECT_NEAR(*a.J_x, *a0.J_x, 1e-9);
  EXPECT_NEAR(*a.J_y, *a0.J_y, 1e-9);
}

TEST(Presets, IncompressibleEllipseBreathesAtConstantArea) {
  const Scene scene = preset("incompressible_breathing_ellipse");
  ASSERT_EQ(scene.body.model, BodyModel::incompressible);
  Simulation run = start_simulation(scene);
  EXPECT_EQ(std::string(run.info->name), "split6");  // auto: the RATTLE composition
  const double area = scene.initial.lambda * scene.initial.mu;
  double x2_min = 1e300, x2_max = 0.0;
  for (int k = 1; k <= 40; ++k) {
    advance_to(run, 0.5 * k);
    ASSERT_EQ(run.state.status, Status::ok);
    const PaperCoordinates c = paper_coordinates(scene, run.state);
    EXPECT_NEAR(c.det_L, area, 1e-14);
    const double x2 = deformation_invariants(c.L.value()).a;
    x2_min = std::min(x2_min, x2);
    x2_max = std::max(x2_max, x2);
  }
  EXPECT_GT(x2_max - x2_min, 0.05);  // it breathes
}

TEST(Presets, SeparableSceneIsW5) {
  const Scene scene = preset("separable_radial_abc");
  Simulation run = start_simulation(scene);
  advance_to(run, 2.0);
  const PaperCoordinates c = paper_coordinates(scene, run.state);
  EXPECT_NEAR(c.r, 1.650073264590784, 1e-8);
  EXPECT_NEAR(*c.phi, 0.7053552271149849, 1e-8);
}

TEST(Presets, DegenerateCrossingHappensAtHalfTime) {
  const Scene scene = preset("degenerate_crossing");
  Simulation run = start_simulation(scene);
  advance_to(run, 1.0);
  ASSERT_EQ(run.events.size(), 1u);
  EXPECT_NEAR(run.events[0].t, 0.5, 1e-9);
}

}  // namespace
}  // namespace spinfold
