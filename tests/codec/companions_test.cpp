// Companions: each its own run on the same surface, advanced with the main body. The preset claims
// (physics.md §8.5, §8.6): the geodesic companion stays on its geodesic, the spinning body on its
// circle of geodesic curvature K s/(m v); statuses are per body; advancing in pieces changes nothing.
#include <gtest/gtest.h>

#include <cmath>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "engine/chart.h"
#include "engine/invariants.h"
#include "engine/simulation.h"
#include "tests/engine/test_support.h"

namespace spinfold {
namespace {

Scene preset(std::string_view name) {
  const PresetSource* source = find_preset(name);
  EXPECT_NE(source, nullptr) << name;
  SceneParse parsed = parse_scene_text(source->json);
  EXPECT_TRUE(parsed.scene) << describe_errors(parsed.errors);
  return *parsed.scene;
}

Vec3 position(const Simulation& run) {
  return global_embedding(run.scene, run.state).X;
}

// The unit normal of the plane through the origin that holds the body's start and start velocity:
// a geodesic of S² (a great circle) or of H² (a section of the hyperboloid) stays in that plane.
Vec3 geodesic_plane_normal(const Simulation& run) {
  const EmbeddedBody b = global_embedding(run.scene, run.state);
  return b.X.cross(b.V).normalized();
}

// The largest value of `measure` over (0, t_end], sampled every 0.05 (the run is advanced).
template <typename F>
double worst_over(Simulation& run, double t_end, F&& measure) {
  double worst = 0.0;
  for (double t = 0.05; t <= t_end + 1e-12; t += 0.05) {
    advance_to(run, t);
    EXPECT_EQ(run.state.status, Status::ok);
    worst = std::max(worst, measure(run));
  }
  return worst;
}

TEST(Companions, OnTheSphereTheGeodesicCompanionKeepsItsGreatCircleAndTheSpinningBodyCircles) {
  const Scene scene = preset("spin_vs_geodesic_sphere");
  ASSERT_EQ(scene.companions.size(), 1u);
  EXPECT_TRUE(scene.companions[0].geodesic);
  Simulation run = start_simulation(scene);
  const Vec3 n = geodesic_plane_normal(run.companions[0]);
  // The spinning body: s = 1, m = 1, v = 0.5, K = 1: κ_g = 2, a circle of geodesic radius
  // ρ = atan(1/2) about the axis of its momentum map (physics.md §8.5, W3).
  const Vec3 axis = momentum_map(run.scene, run.state)->normalized();
  const double rho = std::atan(0.5);
  const double off_circle = worst_over(run, 20.0, [&](const Simulation& r) {
    const double on_plane = std::abs(position(r.companions[0]).dot(n));
    const double angle = std::acos(std::clamp(position(r).dot(axis), -1.0, 1.0));
    return std::max(on_plane, std::abs(angle - rho));
  });
  EXPECT_LT(off_circle, 1e-9);
  // And they part: after a quarter period the spinning body is far from the great circle.
  Simulation later = start_simulation(scene);
  advance_to(later, 5.619851784832581 / 4);
  EXPECT_GT(std::abs(position(later).dot(n)), 0.1);
}

TEST(Companions, OnH2TheGeodesicCompanionKeepsItsGeodesicAndTheSpinningBodyCloses) {
  const Scene scene = preset("spin_vs_geodesic_pseudosphere");
  Simulation run = start_simulation(scene);
  const Vec3 n = geodesic_plane_normal(run.companions[0]);
  // |s| = 1 > m v R = 0.5: a circle with tanh ρ = 1/2 about X_c = R ηM/√(−MᵀηM) (physics.md §8.5,
  // W4): −⟨X, X_c⟩_η/R² = cosh ρ.
  const Vec3 M = *momentum_map(run.scene, run.state);
  const Vec3 etaM(M.x(), M.y(), -M.z());
  const double minkowski = M.x() * M.x() + M.y() * M.y() - M.z() * M.z();
  ASSERT_LT(minkowski, 0.0);
  Vec3 centre = etaM / std::sqrt(-minkowski);
  if (centre.z() < 0) centre = -centre;
  const double cosh_rho = std::cosh(std::atanh(0.5));
  const double worst = worst_over(run, 15.0, [&](const Simulation& r) {
    const Vec3 X = position(r);
    const double eta_dot = X.x() * centre.x() + X.y() * centre.y() - X.z() * centre.z();
    const Vec3 G = position(r.companions[0]);
    return std::max(std::abs(G.dot(n)) / G.norm(), std::abs(-eta_dot - cosh_rho));
  });
  EXPECT_LT(worst, 1e-9);
}

TEST(Companions, AFanOfSpinsShrinksTheCircle) {
  const Scene scene = preset("spin_fan_sphere");
  ASSERT_EQ(scene.companions.size(), 4u);
  EXPECT_EQ(scene.companions[2].label, "spin = 1");
  const Simulation run = start_simulation(scene);
  // ρ/R = atan2(m v R, s) for each body (physics.md §8.5): decreasing as s grows.
  double previous = M_PI;
  std::vector<const Simulation*> bodies = {&run};
  for (const Simulation& c : run.companions) bodies.push_back(&c);
  for (const Simulation* body : bodies) {
    const double s = spin(body->scene, body->state);
    const Vec3 M = *momentum_map(body->scene, body->state);
    const double rho = std::acos(std::clamp(position(*body).dot(M.normalized()), -1.0, 1.0));
    EXPECT_NEAR(rho, std::atan2(0.5, s), 1e-12) << "s = " << s;
    EXPECT_LT(rho, previous);
    previous = rho;
  }
}

TEST(Companions, DeformationCarriedSpinLeavesTheGeodesicOnH2) {
  const Scene scene = preset("deforming_spin_vs_geodesic_pseudosphere");
  Simulation run = start_simulation(scene);
  const Vec3 n = geodesic_plane_normal(run.companions[0]);
  const Vec3 n_main = geodesic_plane_normal(run);  // the same plane: same start and velocity
  EXPECT_LT((n - n_main).norm(), 1e-12);
  double left = 0.0;
  const double worst = worst_over(run, 10.0, [&](const Simulation& r) {
    left = std::max(left, std::abs(position(r).dot(n)) / position(r).norm());
    return std::abs(position(r.companions[0]).dot(n)) / position(r.companions[0]).norm();
  });
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(left, 0.05);
}

TEST(Companions, OppositeSpinsCircleInOppositeSensesAsMirrorImages) {
  const Scene scene = preset("opposite_spins_sphere");
  Simulation run = start_simulation(scene);
  // Mirror images in the plane of the great circle both would follow without spin.
  const Vec3 n = geodesic_plane_normal(run);
  const double worst = worst_over(run, 12.0, [&](const Simulation& r) {
    const Vec3 X = position(r);
    const Vec3 mirrored = X - 2.0 * X.dot(n) * n;
    return (mirrored - position(r.companions[0])).norm();
  });
  EXPECT_LT(worst, 1e-9);
}

TEST(Companions, ACompanionThatStopsDoesNotStopTheOthers) {
  Scene scene = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  test::set_rigid_motion(scene, 0.5, M_PI / 2, 1.0);
  scene.on_degenerate = OnDegenerate::stop;
  // The companion: the free affine body whose frame is squashed at t = 0.5.
  const Scene squashed = test::degenerate_crossing_scene();
  Companion c;
  c.label = "squashed";
  c.body = squashed.body;
  c.initial = squashed.initial;
  c.initial.r = scene.initial.r;
  c.integrator = squashed.integrator;
  scene.companions.push_back(c);
  ASSERT_TRUE(validate_scene(scene).empty());
  Simulation run = start_simulation(scene);
  advance_to(run, 2.0);
  EXPECT_EQ(run.state.status, Status::ok);
  EXPECT_EQ(run.state.t, 2.0);
  EXPECT_EQ(run.companions[0].state.status, Status::degenerate_frame);
  EXPECT_LT(run.companions[0].state.t, 0.6);  // squashed near t = 0.5 (its start moved to r = 1)
  EXPECT_GT(run.companions[0].state.t, 0.4);
}

TEST(Companions, AdvancingInPiecesGivesTheSameBitsForEveryBody) {
  const Scene scene = preset("spin_fan_sphere");
  Scene stepping = scene;
  for (Companion& c : stepping.companions) c.integrator.name = "dop853";
  stepping.integrator.name = "dop853";
  for (const Scene& s : {scene, stepping}) {
    Simulation once = start_simulation(s);
    advance_to(once, 3.7);
    Simulation pieces = start_simulation(s);
    for (double t = 0.3; t < 3.7; t += 0.45) advance_to(pieces, t);
    advance_to(pieces, 3.7);
    EXPECT_TRUE(test::same_bits(once.state, pieces.state));
    ASSERT_EQ(once.companions.size(), pieces.companions.size());
    for (std::size_t i = 0; i < once.companions.size(); ++i)
      EXPECT_TRUE(test::same_bits(once.companions[i].state, pieces.companions[i].state)) << i;
  }
}

TEST(Companions, RetuneReachesTheCompanions) {
  Scene scene = preset("opposite_spins_sphere");
  Simulation run = start_simulation(scene);
  advance_to(run, 1.0);
  Scene heavier = scene;
  heavier.body.mass = 2.0;
  heavier.companions[0].body.mass = 2.0;
  retune(run, heavier);
  EXPECT_EQ(run.companions[0].scene.body.mass, 2.0);
  EXPECT_EQ(run.companions[0].state.t, 1.0);
  advance_to(run, 2.0);
  EXPECT_EQ(run.companions[0].state.t, 2.0);
}

}  // namespace
}  // namespace spinfold
