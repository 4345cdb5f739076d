// Runs against closed forms: circles of spinning bodies (physics.md §8.5, W3, W4), pole
// crossings, far out on H², bodies started at λ = μ, and the flat limit.
#include <gtest/gtest.h>

#include <numbers>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/invariants.h"
#include "engine/paper_coordinates.h"
#include "test_support.h"

namespace spinfold {
namespace {

using test::isometry_flow;
using test::rigid_scene;
using test::run_to;
using test::set_rigid_motion;

constexpr double kPi = std::numbers::pi;

// W3: m = 1, J = 0.5, R = 1, λ = μ = 1, v = 0.5, s = 1: a circle of angular radius atan(1/2).
TEST(SpinningCircle, SphereW3ClosesAfterOnePeriodAtAngleRhoFromM) {
  Scene scene = rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  scene.initial.r = 1.0;
  set_rigid_motion(scene, 0.5, kPi / 2, 1.0);
  Simulation run = start_simulation(scene);
  const Vec3 X0 = global_embedding(scene, run.state).X;
  const Vec3 M = *momentum_map(scene, run.state);
  const double rho = 0.4636476090008061, period = 5.619851784832581;
  for (int k = 1; k <= 8; ++k) {
    advance_to(run, period * k / 8.0);
    const Vec3 X = global_embedding(scene, run.state).X;
    EXPECT_NEAR(std::acos(X.dot(M) / (X.norm() * M.norm())), rho, 1e-11) << "k = " << k;
  }
  EXPECT_LT((global_embedding(scene, run.state).X - X0).norm(), 1e-10);
  // A great circle would be π/2 from its axis; the non-spinning body is.
  set_rigid_motion(scene, 0.5, kPi / 2, 0.0);
  const Simulation still = run_to(scene, 1.0);
  const Vec3 M0 = *momentum_map(scene, still.state);
  const Vec3 X = global_embedding(scene, still.state).X;
  EXPECT_NEAR(std::acos(X.dot(M0) / (X.norm() * M0.norm())), kPi / 2, 1e-11);
}

// Geodesic curvature κ_g = Ks/(mv) = 2 on S² (W3), measured from three nearby positions.
TEST(SpinningCircle, GeodesicCurvatureIsKsOverMv) {
  Scene scene = rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  scene.initial.r = 1.0;
  set_rigid_motion(scene, 0.5, kPi / 2, 1.0);
  Simulation run = start_simulation(scene);
  const EmbeddedBody b0 = global_embedding(scene, run.state);
  Coords dydt;
  // Acceleration from a central difference of the velocity over ±h.
  const double h = 1e-3;
  advance_to(run, h);
  const Vec3 V1 = global_embedding(scene, run.state).V;
  Scene back = scene;
  back.initial.r_dot = -scene.initial.r_dot;
  back.initial.phi_dot = -scene.initial.phi_dot;
  back.initial.alpha_dot = -scene.initial.alpha_dot;  // time reversal flips the spin too
  const Vec3 Vm1 = -global_embedding(back, run_to(back, h).state).V;
  const Vec3 a = (V1 - Vm1) / (2.0 * h);
  const Vec3 a_tangential = tangential(scene.surface, b0.X, a);
  const double v = b0.V.norm();
  const double kappa =
      dot(scene.surface, a_tangential, rotate_quarter(scene.surface, b0.X, b0.V)) / (v * v * v);
  EXPECT_NEAR(kappa, 2.0, 1e-6);
}

// W4, s = 1 > mvR: a circle of geodesic radius arccoth 2 about X_c = RηM/√(−MᵀηM).
TEST(SpinningCircle, PseudosphereW4Circle) {
  Scene scene = rigid_scene(SurfaceKind::pseudosphere, 1.0, 1.0, 0.5, 1.0);
  scene.initial.r = 1.0;
  set_rigid_motion(scene, 0.5, kPi / 2, 1.0);
  Simulation run = start_simulation(scene);
  const Vec3 M = *momentum_map(scene, run.state);
  EXPECT_NEAR(casimir(scene.surface, M), -0.75, 1e-13);
  Vec3 Xc = raise(scene.surface, M) / std::sqrt(-casimir(scene.surface, M));
  if (Xc.z() < 0) Xc = -Xc;
  const Vec3 X0 = global_embedding(scene, run.state).X;
  const double period = 7.255197456936871;
  for (int k = 1; k <= 8; ++k) {
    advance_to(run, period * k / 8.0);
    const Vec3 X = global_embedding(scene, run.state).X;
    EXPECT_NEAR(std::acosh(-dot(scene.surface, X, Xc)), 0.5493061443340548, 1e-11) << "k = " << k;
  }
  EXPECT_LT((global_embedding(scene, run.state).X - X0).norm(), 1e-10);
}

// W4, s = 0.25 < mvR: a hypercycle at distance arccoth 2 from the geodesic {X·M = 0}.
TEST(SpinningCircle, PseudosphereW4Hypercycle) {
  Scene scene = rigid_scene(SurfaceKind::pseudosphere, 1.0, 1.0, 0.5, 1.0);
  scene.initial.r = 1.0;
  set_rigid_motion(scene, 0.5, kPi / 2, 0.25);
  Simulation run = start_simulation(scene);
  const Vec3 M = *momentum_map(scene, run.state);
  EXPECT_NEAR(casimir(scene.surface, M), 0.1875, 1e-13);
  for (int k = 1; k <= 10; ++k) {
    advance_to(run, 2.0 * k);
    const Vec3 X = global_embedding(scene, run.state).X;
    EXPECT_NEAR(X.dot(M), 0.25, 1e-9);  // the orbit is the section X·M = sR
    EXPECT_NEAR(std::asinh(X.dot(M) / std::sqrt(0.1875)), 0.5493061443340548, 2e-9);
  }
}

// The whole state against the chart-free exact solution (physics.md §8.6) for a rigid body:
// X = G X₀, e₁ = G(U(θ_s + ωt) applied to e₁(0)), through any number of pole crossings.
void expect_exact_rigid_motion(const Scene& scene, double t_end, int samples, double tol) {
  Simulation run = start_simulation(scene);
  const EmbeddedBody b0 = global_embedding(scene, run.state);
  const Vec3 M = *momentum_map(scene, run.state);
  const double m = scene.body.mass, R = scene.surface.radius, s = spin(scene, run.state);
  const double l0 = scene.initial.lambda, sigma = curvature_sign(scene.surface);
  for (int k = 1; k <= samples; ++k) {
    const double t = t_end * k / samples;
    advance_to(run, t);
    ASSERT_EQ(run.state.status, Status::ok);
    const Mat3 G = isometry_flow(scene.surface, M, m, t);
    const EmbeddedBody b = global_embedding(scene, run.state);
    // Body-frame rotation about n: −σst/(mR²) from the flow split, s/(2Jλ₀²)·t internal spin.
    const double angle = -sigma * s * t / (m * R * R) + s * t / (2.0 * scene.body.inertia * l0 * l0);
    const Vec3 e1_0 = b0.e[0], je1_0 = rotate_quarter(scene.surface, b0.X, b0.e[0]);
    const Vec3 e1 = G * (std::cos(angle) * e1_0 + std::sin(angle) * je1_0);
    const double scale = std::max(1.0, b.X.norm());
    EXPECT_LT((b.X - G * b0.X).norm(), tol * scale) << "t = " << t;
    EXPECT_LT((b.V - G * b0.V).norm(), tol * scale) << "t = " << t;
    EXPECT_LT((b.e[0] - e1).norm(), tol * scale) << "t = " << t;
  }
}

TEST(PoleCrossing, NonSpinningBodyThroughTheNorthPoleManyTimes) {
  Scene scene = rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  scene.initial.r = 1.0;
  scene.initial.phi = 0.5;
  set_rigid_motion(scene, 0.5, kPi, 0.0);            // straight at the pole
  expect_exact_rigid_motion(scene, 40.0, 40, 1e-9);  // ≈ 6 pole crossings (period 4π)
}

TEST(PoleCrossing, SpinningBodyWithPphiEqualToSpinPassesThePole) {
  // Aimed at the pole with p_φ = s: the circle through the pole (physics.md §8.2).
  Scene scene = rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  scene.initial.r = 1.0;
  set_rigid_motion(scene, 0.5, kPi, 0.3);
  // p_φ = mS²φ̇ + Cs = s needs φ̇ = s(1 − C)/(mS²); keep the speed 0.5.
  const double S = std::sin(1.0), C = std::cos(1.0), s = 0.3;
  scene.initial.phi_dot = s * (1.0 - C) / (S * S);
  scene.initial.r_dot = -std::sqrt(0.25 - S * S * scene.initial.phi_dot * scene.initial.phi_dot);
  scene.initial.alpha_dot = s / (2.0 * 0.5) - C * scene.initial.phi_dot;
  const Simulation start = start_simulation(scene);
  EXPECT_NEAR(angular_momentum(scene, start.state), s, 1e-14);
  expect_exact_rigid_motion(scene, 30.0, 60, 1e-9);
}

TEST(PoleCrossing, PseudosphereGeodesicThroughTheOrigin) {
  Scene scene = rigid_scene(SurfaceKind::pseudosphere, 1.0, 1.0, 0.5, 1.0);
  scene.initial.r = 2.0;
  set_rigid_motion(scene, 1.0, kPi, 0.0);
  expect_exact_rigid_motion(scene, 4.0, 16, 1e-9);
}

TEST(PoleCrossing, StartingExactlyAtThePoleIsRegular) {
  Scene scene = rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  scene.initial.r = 0.0;
  scene.initial.r_dot = 0.5;
  scene.initial.alpha_dot = 1.0;
  const Simulation run = start_simulation(scene);
  const PaperCoordinates c = paper_coordinates(scene, run.state);
  EXPECT_FALSE(c.phi.has_value());
  EXPECT_FALSE(c.L.has_value());
  EXPECT_NEAR(c.r, 0.0, 1e-15);
  EXPECT_TRUE(std::isfinite(energy(scene, run.state)));
  expect_exact_rigid_motion(scene, 20.0, 20, 1e-9);
}

// Far out on H² (r/R from 1 to 41): a radial geodesic r(t) = r₀ + vt, φ fixed.
TEST(FarOutOnH2, RadialGeodesicReachesFortyRadii) {
  Scene scene = rigid_scene(SurfaceKind::pseudosphere, 1.0, 1.0, 0.5, 1.0);
  scene.initial.r = 1.0;
  scene.initial.phi = 0.7;
  set_rigid_motion(scene, 2.0, 0.0, 0.0);
  Simulation run = start_simulation(scene);
  const double H0 = energy(scene, run.state);
  for (double t = 5.0; t <= 20.0; t += 5.0) {
    advance_to(run, t);
    const PaperCoordinates c = paper_coordinates(scene, run.state);
    EXPECT_NEAR(c.r / (1.0 + 2.0 * t), 1.0, 1e-10) << "t = " << t;
    EXPECT_NEAR(*c.phi, 0.7, 1e-10);
    EXPECT_NEAR(*c.r_dot, 2.0, 1e-10);
    EXPECT_NEAR(energy(scene, run.state), H0, 1e-10);
  }
  EXPECT_GT(run.recentres, 5u);  // the chart followed the body out
}

// A spinning deformable body on an unbounded hypercycle to r/R > 30: position against the exact
// isometry flow, and invariants.
TEST(FarOutOnH2, SpinningDeformableBodyOnAHypercycle) {
  Scene scene;
  scene.surface = {SurfaceKind::pseudosphere, 1.0};
  scene.body = {1.0, 0.2, BodyModel::affine};
  scene.potential.deformation = AbcPotential{0.0, 0.0, 0.4};
  scene.initial = {};
  scene.initial.r = 1.0;
  scene.initial.lambda = 1.2;
  scene.initial.mu = 0.8;
  scene.initial.r_dot = 1.5;
  scene.initial.phi_dot = 0.3;
  scene.initial.alpha_dot = 0.5;
  scene.integrator = {"dop853", 0.01, 1e-13};
  Simulation run = start_simulation(scene);
  const EmbeddedBody b0 = global_embedding(scene, run.state);
  const Vec3 M = *momentum_map(scene, run.state);
  const double H0 = energy(scene, run.state), s0 = spin(scene, run.state), pb0 = vorticity(scene, run.state);
  const auto sep0 = *separated_energies(scene, run.state);
  const double t_end = 22.0;
  advance_to(run, t_end);
  ASSERT_EQ(run.state.status, Status::ok);
  const PaperCoordinates c = paper_coordinates(scene, run.state);
  EXPECT_GT(c.r, 30.0);
  const Vec3 X_exact = isometry_flow(scene.surface, M, scene.body.mass, t_end) * b0.X;
  const PolarCoordinates exact = polar_coordinates(scene.surface, X_exact);
  EXPECT_NEAR(c.r, exact.r, 1e-9 * exact.r);
  EXPECT_NEAR(*c.phi, exact.phi, 1e-9);
  EXPECT_NEAR(energy(scene, run.state), H0, 1e-10 * std::abs(H0));
  EXPECT_NEAR(spin(scene, run.state), s0, 1e-10);
  EXPECT_NEAR(vorticity(scene, run.state), pb0, 1e-10);
  const auto sep = *separated_energies(scene, run.state);
  EXPECT_NEAR(sep.C_x, sep0.C_x, 1e-10);
  EXPECT_NEAR(sep.C_y, sep0.C_y, 1e-10);
}

// λ = μ at the start (the undeformed body): x = (λ − μ)/√2 then moves as the linear oscillator
// Jẍ = −2Cx through x = 0 (physics.md §8.3, L_x = 0), while the body moves on the sphere.
TEST(Isotropic, StartAtLambdaEqualsMuFollowsTheLinearOscillator) {
  Scene scene;
  scene.surface = {SurfaceKind::sphere, 1.0};
  scene.body = {1.0, 0.2, BodyModel::affine};
  scene.potential.deformation = AbcPotential{0.0, 0.05, 0.5};
  scene.initial = {};
  scene.initial.r = 1.1;
  scene.initial.lambda = scene.initial.mu = 1.0;
  scene.initial.lambda_dot = 0.1;
  scene.initial.mu_dot = -0.1;
  scene.initial.phi_dot = 0.4;
  scene.initial.alpha_dot = 0.7;
  scene.integrator = {"dop853", 0.01, 1e-13};
  Simulation run = start_simulation(scene);
  const PaperCoordinates c0 = paper_coordinates(scene, run.state);
  EXPECT_FALSE(c0.alpha.has_value());
  EXPECT_TRUE(c0.theta.has_value());
  const double omega = std::sqrt(2.0 * 0.5 / 0.2), x_dot0 = 0.2 / std::numbers::sqrt2;
  for (int k = 1; k <= 40; ++k) {
    const double t = 0.25 * k;
    advance_to(run, t);
    const PaperCoordinates c = paper_coordinates(scene, run.state);
    const double x = std::abs(x_dot0 * std::sin(omega * t) / omega);
    EXPECT_NEAR((c.lambda - c.mu) / std::numbers::sqrt2, x, 1e-10) << "t = " << t;
  }
}

// The flat limit: on the plane a free body moves in a straight line, and a sphere of large R
// approaches it as 1/R².
TEST(FlatLimit, PlaneIsStraightAndLargeSpheresConverge) {
  Scene plane;
  plane.surface = {SurfaceKind::plane, 1.0};
  plane.body = {1.0, 0.2, BodyModel::affine};
  plane.potential.deformation = AbcPotential{0.0, 0.0, 0.3};
  plane.initial = {};
  plane.initial.r = 2.0;
  plane.initial.lambda = 1.2;
  plane.initial.mu = 0.9;
  plane.initial.r_dot = -0.3;  // straight through the chart's pole at t = 20/3
  plane.initial.alpha_dot = 0.5;
  plane.integrator = {"dop853", 0.01, 1e-13};
  const double T = 8.0;
  Simulation flat = start_simulation(plane);
  const EmbeddedBody b0 = global_embedding(plane, flat.state);
  advance_to(flat, T);
  const EmbeddedBody b = global_embedding(plane, flat.state);
  EXPECT_LT((b.X - (b0.X + T * b0.V)).norm(), 1e-10);  // crosses the plane's chart pole too
  EXPECT_GT(flat.recentres, 0u);
  const PaperCoordinates cf = paper_coordinates(plane, flat.state);

  double previous = 0.0;
  for (double R : {1e2, 1e3}) {
    Scene sphere = plane;
    sphere.surface = {SurfaceKind::sphere, R};
    const Simulation curved = run_to(sphere, T);
    const PaperCoordinates cs = paper_coordinates(sphere, curved.state);
    const double dphi = std::remainder(*cs.phi - *cf.phi, 2.0 * kPi);
    const double diff = std::abs(cs.r - cf.r) + std::abs(dphi) + (*cs.L - *cf.L).norm();
    EXPECT_LT(diff, 50.0 / (R * R));
    if (previous > 0.0) {
      EXPECT_NEAR(previous / diff, 100.0, 30.0);  // error ∝ 1/R²
    }
    previous = diff;
  }
}

}  // namespace
}  // namespace spinfold
