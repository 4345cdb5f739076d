// spin, speed and heading ↔ the paper's rates (engine/initial_rates.h): round trips at λ = μ and
// λ ≠ μ on every surface, physics.md §10's worked numbers, the errors, and the claim people rely on
// (spin 0 and no potentials: a geodesic).
#include "engine/initial_rates.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "test_support.h"

namespace spinfold {
namespace {

constexpr SurfaceKind kSurfaces[] = {SurfaceKind::sphere, SurfaceKind::pseudosphere, SurfaceKind::plane};

// An affine body off the poles with every rate nonzero: λ ≠ μ unless `isotropic`.
Scene moving_scene(SurfaceKind kind, bool isotropic) {
  Scene s;
  s.surface = {kind, 1.7};
  s.body = {1.3, 0.4, BodyModel::affine};
  InitialState& q = s.initial;
  q.r = 1.1;
  q.phi = 0.3;
  q.alpha = 0.2;
  q.beta = -0.4;
  q.lambda = 1.25;
  q.mu = isotropic ? 1.25 : 0.6;
  q.r_dot = -0.35;
  q.phi_dot = 0.45;
  q.alpha_dot = 0.7;
  q.beta_dot = -0.15;
  q.lambda_dot = 0.05;
  q.mu_dot = -0.02;
  return s;
}

void expect_relative(double actual, double expected, double tolerance, const char* what) {
  EXPECT_LE(std::abs(actual - expected), tolerance * std::abs(expected)) << what << ": " << actual;
}

TEST(InitialRates, SpinRoundTripsThroughAlphaDot) {
  for (const SurfaceKind kind : kSurfaces)
    for (const bool isotropic : {true, false})
      for (const double s : {0.0, 0.8, -2.5, 1e-3}) {
        Scene scene = moving_scene(kind, isotropic);
        scene.initial.spin = s;
        ASSERT_TRUE(resolve_initial_rates(scene).empty());
        // Relative to the spin, or to the terms that cancel in it when it is small against them.
        const InitialState& q = scene.initial;
        const double J = scene.body.inertia, C = polar_C(scene.surface, q.r);
        const double terms = J * ((q.lambda * q.lambda + q.mu * q.mu) * std::abs(C * q.phi_dot) +
                                  2.0 * q.lambda * q.mu * std::abs(q.beta_dot));
        EXPECT_LE(std::abs(spin_of(scene) - s), 1e-14 * std::max(std::abs(s), terms)) << spin_of(scene);
        if (std::abs(s) > terms) expect_relative(spin_of(scene), s, 1e-14, "spin");
        // Only alpha_dot changed.
        EXPECT_EQ(scene.initial.r_dot, -0.35);
        EXPECT_EQ(scene.initial.phi_dot, 0.45);
        EXPECT_EQ(scene.initial.beta_dot, -0.15);
      }
}

// The rigid model's spin 2Jλ₀²(α̇ − β̇ + Cφ̇) (physics.md §8.5, §8.8) is the general formula at λ = μ.
TEST(InitialRates, RigidSpinIsTheGeneralFormulaAtLambdaEqualsMu) {
  for (const SurfaceKind kind : kSurfaces) {
    Scene scene = moving_scene(kind, true);
    scene.body.model = BodyModel::rigid;
    scene.initial.lambda_dot = scene.initial.mu_dot = 0.0;
    const InitialState& q = scene.initial;
    const double l0 = q.lambda, C = polar_C(scene.surface, q.r);
    const double rigid = 2.0 * scene.body.inertia * l0 * l0 * (q.alpha_dot - q.beta_dot + C * q.phi_dot);
    expect_relative(spin_of(scene), rigid, 1e-14, "rigid spin");
  }
}

TEST(InitialRates, SpeedAndHeadingRoundTrip) {
  for (const SurfaceKind kind : kSurfaces)
    for (const double h : {0.0, 0.4, 1.5707963267948966, 2.9, -0.8, -2.2})
      for (const double v : {0.3, 4.0}) {
        Scene scene = moving_scene(kind, false);
        scene.initial.speed = v;
        scene.initial.heading = h;
        ASSERT_TRUE(resolve_initial_rates(scene).empty());
        const double S = polar_S(scene.surface, scene.initial.r);
        EXPECT_EQ(scene.initial.r_dot, v * std::cos(h));
        EXPECT_EQ(scene.initial.phi_dot, v * std::sin(h) / S);
        expect_relative(speed_of(scene), v, 1e-15, "speed");
        EXPECT_NEAR(heading_of(scene), h, 1e-15);
        EXPECT_EQ(scene.initial.alpha_dot, 0.7);  // no spin given: the rate stays
      }
}

// The spin is converted with the φ̇ that speed and heading give.
TEST(InitialRates, SpinUsesTheResolvedPhiDot) {
  for (const SurfaceKind kind : kSurfaces)
    for (const bool isotropic : {true, false}) {
      Scene scene = moving_scene(kind, isotropic);
      scene.initial.speed = 0.9;
      scene.initial.heading = 1.2;
      scene.initial.spin = 0.6;
      ASSERT_TRUE(resolve_initial_rates(scene).empty());
      expect_relative(spin_of(scene), 0.6, 1e-14, "spin");
      expect_relative(speed_of(scene), 0.9, 1e-15, "speed");
      EXPECT_NEAR(heading_of(scene), 1.2, 1e-15);
    }
}

// physics.md §10 W1 (sphere) and W2 (pseudosphere), given by their spin p_α.
TEST(InitialRates, WorkedExamplesW1AndW2) {
  Scene w1;
  w1.surface = {SurfaceKind::sphere, 1.0};
  w1.body = {2.0, 0.5, BodyModel::affine};
  w1.initial = {.r = 1,
                .phi = 0.5,
                .alpha = 0.25,
                .beta = -0.5,
                .lambda = 1.5,
                .mu = 0.5,
                .r_dot = 0.2,
                .phi_dot = -0.3,
                .alpha_dot = 0.0,
                .beta_dot = 0.1,
                .lambda_dot = 0.05,
                .mu_dot = -0.02,
                .spin = 0.22238663529944763};
  ASSERT_TRUE(resolve_initial_rates(w1).empty());
  EXPECT_NEAR(w1.initial.alpha_dot, 0.4, 1e-14);
  expect_relative(spin_of(w1), 0.22238663529944763, 1e-14, "W1 p_alpha");

  Scene w2;
  w2.surface = {SurfaceKind::pseudosphere, 2.0};
  w2.body = {1.0, 0.2, BodyModel::affine};
  w2.initial = {.r = 1.5,
                .phi = -1,
                .alpha = 0,
                .beta = 0.7,
                .lambda = 1,
                .mu = 0.6,
                .r_dot = -0.1,
                .phi_dot = 0.2,
                .alpha_dot = 0.0,
                .beta_dot = -0.3,
                .lambda_dot = 0,
                .mu_dot = 0.1,
                .spin = 0.3872307706864203};
  ASSERT_TRUE(resolve_initial_rates(w2).empty());
  EXPECT_NEAR(w2.initial.alpha_dot, 0.9, 1e-14);
  expect_relative(spin_of(w2), 0.3872307706864203, 1e-14, "W2 p_alpha");
}

// physics.md §10 W3: a rigid body with v = 0.5 and s = 1 on the unit sphere turns on a circle of
// geodesic radius ρ = arctan(1/2) about M (angle from M/|M| constant).
TEST(InitialRates, WorkedExampleW3CircleFromSpinAndSpeed) {
  Scene scene = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  scene.initial.r = 1.0;
  scene.initial.speed = 0.5;
  scene.initial.heading = 0.3;
  scene.initial.spin = 1.0;
  ASSERT_TRUE(resolve_initial_rates(scene).empty());
  Simulation run = start_simulation(scene);
  const GlobalBody b0 = global_body(scene, run.state);
  // M = m X × V + s X/R (physics.md §6 on S²): the axis of the circle.
  const Vec3 axis = (scene.body.mass * b0.X.cross(b0.V) + 1.0 * b0.X).normalized();
  for (double t = 0.5; t <= 5.619851784832581; t += 0.5) {
    advance_to(run, t);
    EXPECT_NEAR(std::acos(global_body(scene, run.state).X.normalized().dot(axis)), 0.4636476090008061, 1e-9)
        << "t = " << t;
  }
}

// The claim people rely on: zero spin and no potentials is a geodesic. The rigid body started with
// spin 0 and speed v stays on the great circle of its start (|⟨X, n⟩| ≤ 1e-9, n ∝ X₀ × V₀), while
// the same start with spin 1 leaves it.
TEST(InitialRates, ZeroSpinFollowsAGreatCircle) {
  for (const double heading : {0.0, 0.9, 2.4}) {
    Scene scene = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
    scene.initial.r = 1.0;
    scene.initial.phi = 0.4;
    scene.initial.beta_dot = 0.3;  // only α̇ − β̇ matters: the spin absorbs it
    scene.initial.speed = 0.5;
    scene.initial.heading = heading;
    scene.initial.spin = 0.0;
    ASSERT_TRUE(resolve_initial_rates(scene).empty());
    EXPECT_NE(scene.initial.alpha_dot, 0.0);  // what a teacher could not have guessed
    Simulation run = start_simulation(scene);
    const GlobalBody b0 = global_body(scene, run.state);
    const Vec3 n = b0.X.cross(b0.V).normalized();
    double worst = 0.0;
    for (double t = 0.25; t <= 20.0; t += 0.25) {
      advance_to(run, t);
      ASSERT_EQ(run.state.status, Status::ok);
      worst = std::max(worst, std::abs(global_body(scene, run.state).X.dot(n)));
    }
    EXPECT_LE(worst, 1e-9) << "heading " << heading;

    Scene spinning = scene;
    spinning.initial.spin = 1.0;
    ASSERT_TRUE(resolve_initial_rates(spinning).empty());
    Simulation other = start_simulation(spinning);
    advance_to(other, 3.0);
    EXPECT_GT(std::abs(global_body(spinning, other.state).X.dot(n)), 0.1) << "heading " << heading;
  }
}

// ---- errors: the scene is left as it was ----------------------------------------------------

struct Named {
  std::string field, value, reason;
};

Named only_error(Scene& scene) {
  const Scene before = scene;
  const std::vector<FieldError> errors = resolve_initial_rates(scene);
  EXPECT_EQ(errors.size(), 1u);
  EXPECT_EQ(scene.initial.r_dot, before.initial.r_dot);
  EXPECT_EQ(scene.initial.phi_dot, before.initial.phi_dot);
  EXPECT_EQ(scene.initial.alpha_dot, before.initial.alpha_dot);
  if (errors.empty()) return {};
  return {errors[0].field, errors[0].value, errors[0].reason};
}

TEST(InitialRates, SpeedAndHeadingComeTogether) {
  Scene speed_only = moving_scene(SurfaceKind::sphere, false);
  speed_only.initial.speed = 1.0;
  speed_only.initial.spin = 0.5;  // not applied either
  Named e = only_error(speed_only);
  EXPECT_EQ(e.field, "initial.heading");
  EXPECT_EQ(e.value, "null");
  EXPECT_NE(e.reason.find("is missing"), std::string::npos) << e.reason;

  Scene heading_only = moving_scene(SurfaceKind::plane, false);
  heading_only.initial.heading = 1.0;
  e = only_error(heading_only);
  EXPECT_EQ(e.field, "initial.speed");
  EXPECT_NE(e.reason.find("is missing"), std::string::npos) << e.reason;
}

TEST(InitialRates, AHeadingOffE1AtAPoleIsRefused) {
  for (const SurfaceKind kind : kSurfaces) {
    Scene scene = moving_scene(kind, false);
    scene.initial.r = 0.0;
    scene.initial.speed = 0.5;
    scene.initial.heading = 0.25;
    const Named e = only_error(scene);
    EXPECT_EQ(e.field, "initial.heading");
    EXPECT_EQ(e.value, "0.25");
    EXPECT_NE(e.reason.find("at a pole"), std::string::npos) << e.reason;
  }
  Scene south = moving_scene(SurfaceKind::sphere, false);
  south.initial.r = std::numbers::pi * south.surface.radius;
  south.initial.speed = 0.5;
  south.initial.heading = 1.0;
  EXPECT_EQ(only_error(south).field, "initial.heading");

  // Along E₁ (or at rest) a pole is fine: a radial start.
  Scene radial = moving_scene(SurfaceKind::sphere, false);
  radial.initial.r = 0.0;
  radial.initial.speed = 0.5;
  radial.initial.heading = std::numbers::pi;
  ASSERT_TRUE(resolve_initial_rates(radial).empty());
  EXPECT_EQ(radial.initial.phi_dot, 0.0);
  EXPECT_EQ(radial.initial.r_dot, -0.5);
}

TEST(InitialRates, ARateThatOverflowsIsRefused) {
  Scene scene = moving_scene(SurfaceKind::sphere, false);
  scene.body.inertia = 1e-100;
  scene.initial.lambda = scene.initial.mu = 1e-100;
  scene.initial.spin = 1e100;
  const Named e = only_error(scene);
  EXPECT_EQ(e.field, "initial.spin");
  EXPECT_EQ(e.value, "1e+100");
  EXPECT_NE(e.reason.find("not a finite number"), std::string::npos) << e.reason;
}

// Nothing set: nothing changes.
TEST(InitialRates, RatesAloneAreKept) {
  Scene scene = moving_scene(SurfaceKind::pseudosphere, false);
  const Scene before = scene;
  EXPECT_TRUE(resolve_initial_rates(scene).empty());
  EXPECT_EQ(scene.initial.r_dot, before.initial.r_dot);
  EXPECT_EQ(scene.initial.phi_dot, before.initial.phi_dot);
  EXPECT_EQ(scene.initial.alpha_dot, before.initial.alpha_dot);
}

}  // namespace
}  // namespace spinfold
