// Which way a sampled path bends (engine/path_bending.h): κ_g of circles whose geodesic curvature
// is known in closed form on S², H² (near and far out), the plane, the torus and a formula sphere,
// its sign turned by running the other way, geodesics at 0, and the spinning body's path on the
// torus at K s/(m v) — the claim the bending layer draws.
#include "engine/path_bending.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "engine/readout.h"
#include "engine/trail.h"
#include "formula_surfaces.h"

namespace spinfold {
namespace {

constexpr double kPi = std::numbers::pi;

// n points of X(φ), φ from 0 to `turn` (negative: the other way).
std::vector<Vec3> sampled(const std::function<Vec3(double)>& X, double turn, int n = 2000) {
  std::vector<Vec3> path;
  for (int i = 0; i <= n; ++i) path.push_back(X(turn * i / n));
  return path;
}

// Every κ_g of the path within `tol` (relative, and absolute where the expected value is 0).
void expect_all_near(const std::vector<double>& kappa, double expected, double tol) {
  for (const double k : kappa) ASSERT_NEAR(k, expected, tol * std::max(1.0, std::abs(expected)));
}

TEST(PathBending, ALatitudeOfTheSphereBendsLeftByCotThetaOverR) {
  const double R = 2.0, theta = 0.6;
  const auto model = surface_model_of(Surface{SurfaceKind::sphere, R});
  const auto X = [&](double phi) {
    return Vec3(R * std::sin(theta) * std::cos(phi), R * std::sin(theta) * std::sin(phi),
                R * std::cos(theta));
  };
  const double expected = 1.0 / (std::tan(theta) * R);  // counterclockwise seen from outside: left
  expect_all_near(geodesic_curvatures(*model, sampled(X, 2.0 * kPi)), expected, 1e-5);
  expect_all_near(geodesic_curvatures(*model, sampled(X, -2.0 * kPi)), -expected, 1e-5);
}

TEST(PathBending, AGeodesicCircleOfH2BendsByCothRNearAndFarOut) {
  const double R = 1.5;
  const auto model = surface_model_of(Surface{SurfaceKind::pseudosphere, R});
  for (const double r : {0.8, 8.0}) {  // far out the embedding is ~e^{r/R}: Minkowski lengths
    const auto X = [&](double phi) {
      const double S = R * std::sinh(r / R);
      return Vec3(S * std::cos(phi), S * std::sin(phi), R * std::cosh(r / R));
    };
    expect_all_near(geodesic_curvatures(*model, sampled(X, 2.0 * kPi)), 1.0 / (std::tanh(r / R) * R), 1e-5);
  }
}

TEST(PathBending, ACircleOfThePlaneAndOfAFormulaSphere) {
  const auto plane = surface_model_of(Surface{SurfaceKind::plane, 1.0});
  expect_all_near(
      geodesic_curvatures(*plane,
                          sampled([](double p) { return Vec3(2 * std::cos(p), 2 * std::sin(p), 0); }, -kPi)),
      -0.5, 1e-6);
  // The sphere of radius 2 written as F = 0: ∇F's normal, the same κ_g as the built-in sphere's.
  const auto sphere = surface_model_of(test::implicit_surface("x^2 + y^2 + z^2 - 4"));
  const double theta = 1.1;
  const auto X = [&](double phi) {
    return Vec3(2 * std::sin(theta) * std::cos(phi), 2 * std::sin(theta) * std::sin(phi),
                2 * std::cos(theta));
  };
  expect_all_near(geodesic_curvatures(*sphere, sampled(X, kPi)), 1.0 / (2.0 * std::tan(theta)), 1e-5);
}

TEST(PathBending, TheTorussEquatorsDoNotBendItsTopCircleDoesAndARepeatedPointIsZero) {
  Surface s;
  s.kind = SurfaceKind::torus;  // a = 1, c = 2.5
  const auto torus = surface_model_of(s);
  const auto parallel = [](double rho, double z) {
    return sampled([=](double p) { return Vec3(rho * std::cos(p), rho * std::sin(p), z); }, kPi);
  };
  // The outer and inner equators (ρ extremal: dρ/du = 0) are geodesics; the top circle, whose
  // normal is ẑ, bends left by 1/ρ = 1/c.
  expect_all_near(geodesic_curvatures(*torus, parallel(3.5, 0.0)), 0.0, 1e-9);
  expect_all_near(geodesic_curvatures(*torus, parallel(1.5, 0.0)), 0.0, 1e-9);
  expect_all_near(geodesic_curvatures(*torus, parallel(2.5, 1.0)), 1.0 / 2.5, 1e-5);
  const std::vector<Vec3> paused{Vec3(3.5, 0, 0), Vec3(3.5, 0, 0), Vec3(3.5, 0, 0)};
  expect_all_near(geodesic_curvatures(*torus, paused), 0.0, 0.0);
}

TEST(PathBending, TheSpinningBodyOnTheTorusBendsByKsOverMv) {
  // physics-surfaces.md §5: with no force but the spin's, κ_g = K s/(m v); on the torus K changes
  // sign between the outer and inner bands, and so does the bending the layer colours.
  Scene scene;
  scene.surface.kind = SurfaceKind::torus;
  scene.body = {1.0, 0.5, BodyModel::rigid};
  scene.initial.u = 0.0;
  scene.initial.u_dot = 0.9;
  scene.initial.phi_dot = 0.4 / 3.5;
  scene.initial.alpha_dot = 1.0;
  scene.integrator = {"dop853", 0.01, 1e-12};
  Simulation run = start_simulation(scene);
  const Readout r0 = readout(run);
  ASSERT_GT(std::abs(r0.spin), 0.5);
  Trail trail;
  trail.spacing = 0.002;
  ASSERT_TRUE(advance_sampling_trail(run, trail, 12.0));
  std::vector<Vec3> path;
  for (const TrailPoint& p : trail.points) path.push_back(p.X);
  const std::vector<double> kappa = geodesic_curvatures(*run.surface, path);
  int positive = 0, negative = 0;
  for (std::size_t i = 1; i + 1 < path.size(); ++i) {
    const double K = bordered_hessian_curvature(run.surface->implicit->at(path[i]));
    const double expected = K * r0.spin / (scene.body.mass * *r0.speed);
    ASSERT_NEAR(kappa[i], expected, 1e-3 * std::max(1.0, std::abs(expected))) << "t = " << trail.points[i].t;
    if (expected > 0.05) ++positive;
    if (expected < -0.05) ++negative;
  }
  EXPECT_GT(positive, 100);  // the path crossed both bands
  EXPECT_GT(negative, 100);
}

}  // namespace
}  // namespace spinfold
