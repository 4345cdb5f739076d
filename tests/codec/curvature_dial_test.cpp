// The curvature dial (physics.md §16): a surface given by K, continuous through K = 0 — the scene
// field, the spin–curvature bending κ_g = K s/(m v) at every K, runs at K = ±1e-12 against the
// plane, and a run carried live across K = 0.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "codec/scene_json.h"
#include "engine/invariants.h"
#include "engine/simulation.h"
#include "engine/timeline.h"
#include "engine/trail.h"

namespace spinfold {
namespace {

// A spinning rigid body (m = 1, s = 1) moving at v = 0.5 across the radius at r = 0.5: V_r = 0, so
// its path has constant geodesic curvature K s/(m v) (physics.md §8.5).
Scene spinning(double K, const std::string& integrator = "auto", double dt = 0.01) {
  const std::string text = R"({"surface": {"curvature": )" + std::to_string(K) +
                           R"(}, "body": {"mass": 1, "inertia": 0.5, "model": "rigid"},
      "initial": {"r": 0.5, "phi": 0.3, "lambda": 1, "mu": 1, "speed": 0.5, "heading": 1.5707963267948966,
                  "spin": 1},
      "integrator": {"name": ")" +
                           integrator + R"(", "dt": )" + std::to_string(dt) + R"(, "tolerance": 1e-12}})";
  SceneParse parsed = parse_scene_text(text);
  EXPECT_TRUE(parsed.scene) << (parsed.errors.empty()
                                    ? ""
                                    : parsed.errors[0].field + ": " + parsed.errors[0].reason);
  Scene scene = *parsed.scene;
  scene.surface.curvature_given = K;  // exactly K (the text above rounds it to 6 digits)
  resolve_curvature(scene.surface);
  return scene;
}

struct Motion {
  double heading;  // ψ = atan2(Sφ̇, ṙ) [rad]
  double C, phi_dot, speed;
};

Motion motion(const Simulation& run) {
  const GlobalBody g = global_body(run.scene, run.state);
  return {std::atan2(g.S * g.phi_dot, g.r_dot), g.C, g.phi_dot, std::hypot(g.r_dot, g.S * g.phi_dot)};
}

// κ_g = (ψ̇ + Cφ̇)/v: the velocity's turning rate against the parallel-transported frame (E₁ turns
// by C dφ), ψ̇ by a central difference over ±h.
double geodesic_curvature_at(const Scene& scene, double t) {
  constexpr double h = 1e-4;
  Simulation before = start_simulation(scene), at = start_simulation(scene), after = start_simulation(scene);
  advance_to(before, t - h);
  advance_to(at, t);
  advance_to(after, t + h);
  const Motion m = motion(at);
  const double dpsi = std::remainder(motion(after).heading - motion(before).heading, 2 * std::numbers::pi);
  return (dpsi / (2 * h) + m.C * m.phi_dot) / m.speed;
}

TEST(CurvatureDial, SurfaceFromCurvatureWrittenBackAsGiven) {
  for (const double K : {4.0, 0.25, 1e-12, 0.0, -1e-12, -0.25, -4.0}) {
    Scene s = spinning(K);
    const SurfaceKind kind = K > 0   ? SurfaceKind::sphere
                             : K < 0 ? SurfaceKind::pseudosphere
                                     : SurfaceKind::plane;
    EXPECT_EQ(s.surface.kind, kind) << K;
    if (K != 0.0) {
      EXPECT_DOUBLE_EQ(s.surface.radius, 1.0 / std::sqrt(std::abs(K))) << K;
      EXPECT_DOUBLE_EQ(curvature(s.surface), K) << K;
    }
    const nlohmann::json written = scene_to_json(s);
    EXPECT_EQ(written["surface"], (nlohmann::json{{"curvature", K}})) << K;
    const SceneParse again = parse_scene(written);
    ASSERT_TRUE(again.scene) << K;
    EXPECT_EQ(scene_to_json(*again.scene), written) << K;
  }
}

TEST(CurvatureDial, BothFormsOrABadCurvatureAreRefusedNamingTheField) {
  const SceneParse both = parse_scene_text(R"({"surface": {"curvature": 1, "kind": "sphere"}})");
  ASSERT_FALSE(both.scene);
  EXPECT_EQ(both.errors.at(0).field, "surface.curvature");
  EXPECT_NE(both.errors.at(0).reason.find("not both"), std::string::npos) << both.errors.at(0).reason;
  const SceneParse text = parse_scene_text(R"({"surface": {"curvature": "flat"}})");
  ASSERT_FALSE(text.scene);
  EXPECT_EQ(text.errors.at(0).field, "surface.curvature");
  // On a sphere of K = 4 (R = 0.5) the body at r = 2 would be past the antipode.
  const SceneParse far = parse_scene_text(R"({"surface": {"curvature": 4}, "initial": {"r": 2}})");
  ASSERT_FALSE(far.scene);
  EXPECT_EQ(far.errors.at(0).field, "initial.r");
}

// The headline: the same spinning body bends one way for K > 0, goes straight at K = 0 and bends the
// other way for K < 0, with κ_g = K s/(m v) at every K of the dial.
TEST(CurvatureDial, GeodesicCurvatureIsKsOverMvAtEveryK) {
  for (const double K : {-4.0, -2.0, -1.0, -0.5, -0.1, -1e-12, 0.0, 1e-12, 0.1, 0.5, 1.0, 2.0, 4.0}) {
    const Scene scene = spinning(K, "dop853");
    const double expected = K * 1.0 / (1.0 * 0.5);
    for (const double t : {0.5, 1.3, 2.9}) {
      const double kappa = geodesic_curvature_at(scene, t);
      EXPECT_NEAR(kappa, expected, 1e-6 * std::max(1.0, std::abs(expected))) << "K = " << K << ", t = " << t;
    }
  }
}

// At K = ±1e-12 the sphere and H² of R = 1e6 are the plane to round-off: the body's place, frame and
// rates agree with the plane's run (the physical difference, ~K r² ≈ 1e-11 here, is below the bound).
TEST(CurvatureDial, RunsAtTinyCurvatureAgreeWithThePlane) {
  for (const char* integrator : {"auto", "dop853", "split4", "gauss6"}) {
    Simulation plane = start_simulation(spinning(0.0, integrator));
    ASSERT_TRUE(advance_to(plane, 10.0));
    const GlobalBody p = global_body(plane.scene, plane.state);
    for (const double K : {1e-12, -1e-12}) {
      Simulation run = start_simulation(spinning(K, integrator));
      ASSERT_TRUE(advance_to(run, 10.0));
      ASSERT_EQ(run.state.status, Status::ok);
      const GlobalBody g = global_body(run.scene, run.state);
      EXPECT_NEAR(g.r, p.r, 1e-9) << integrator << " K = " << K;
      EXPECT_NEAR(std::remainder(g.phi - p.phi, 2 * std::numbers::pi), 0.0, 1e-9)
          << integrator << " K = " << K;
      EXPECT_NEAR(g.r_dot, p.r_dot, 1e-9) << integrator << " K = " << K;
      EXPECT_NEAR(g.phi_dot, p.phi_dot, 1e-9) << integrator << " K = " << K;
      EXPECT_LT((g.L - p.L).norm(), 1e-9) << integrator << " K = " << K;
      EXPECT_NEAR(energy(run.scene, run.state), energy(plane.scene, plane.state), 1e-12)
          << integrator << " K = " << K;
    }
  }
}

// Dialled live from K = 1 through 0 to K = −1: the body keeps its place (r, φ), velocity and frame
// at each change, and the trail is carried along onto each new surface; a replay of the same
// timeline gives the same bits.
TEST(CurvatureDial, ALiveDialContinuesThroughZero) {
  const Scene start = spinning(1.0, "split4");
  std::vector<ParameterChange> changes;
  double t = 0.0;
  for (const double K : {0.5, 0.0, -0.5, -1.0}) {
    Scene next = start;
    next.surface.curvature_given = K;
    resolve_curvature(next.surface);
    changes.push_back({t += 0.75, next});
  }
  Simulation live = start_simulation(start);
  Trail trail;
  for (const ParameterChange& change : changes) {
    ASSERT_TRUE(advance_sampling_trail(live, trail, change.t));
    const GlobalBody before = global_body(live.scene, live.state);
    retune_carrying_trail(live, trail, change.scene);
    const GlobalBody after = global_body(live.scene, live.state);
    EXPECT_NEAR(after.r, before.r, 1e-12 * (1 + before.r)) << change.t;
    EXPECT_NEAR(std::remainder(after.phi - before.phi, 2 * std::numbers::pi), 0.0, 1e-12) << change.t;
    EXPECT_NEAR(after.r_dot, before.r_dot, 1e-12) << change.t;
    EXPECT_NEAR(after.S * after.phi_dot, before.S * before.phi_dot, 1e-12) << change.t;
    EXPECT_LT((after.L - before.L).norm(), 1e-12) << change.t;
    // The trail lies on the new surface: ⟨X, X⟩ = σR² (the plane: X₃ = 0).
    for (const TrailPoint& p : trail.points) {
      const Surface& s = live.scene.surface;
      const double expected =
          offers(s, Offer::zero_curvature) ? 0.0 : curvature_sign(s) * s.radius * s.radius;
      const double got = offers(s, Offer::zero_curvature) ? p.X.z() : dot(s, p.X, p.X);
      EXPECT_NEAR(got, expected, 1e-9 * (1 + std::abs(expected))) << change.t;
    }
  }
  ASSERT_TRUE(advance_sampling_trail(live, trail, 3.5));
  EXPECT_EQ(live.scene.surface.kind, SurfaceKind::pseudosphere);

  Simulation rebuilt;
  Trail rebuilt_trail;
  ASSERT_TRUE(replay(start, changes, 3.5, rebuilt, rebuilt_trail));
  EXPECT_EQ(rebuilt.state.y, live.state.y);
  ASSERT_EQ(rebuilt_trail.points.size(), trail.points.size());
  for (std::size_t i = 0; i < trail.points.size(); ++i)
    EXPECT_EQ(rebuilt_trail.points[i].X, trail.points[i].X);
}

}  // namespace
}  // namespace spinfold
