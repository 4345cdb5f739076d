#include "engine/path_circle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "engine/readout.h"
#include "test_support.h"

namespace spinfold {
namespace {

using test::rigid_scene;
using test::set_rigid_motion;
constexpr double kPi = std::numbers::pi;

// A run of `laps` predicted laps with its trail sampled 200 times a lap.
CircleReadout after_laps(const Scene& scene, double laps) {
  Simulation run = start_simulation(scene);
  const Readout r = readout(run);
  const PredictedCircle p = predicted_circle(scene, r.spin, r.speed.value_or(0.0));
  Trail trail;
  trail.spacing = p.radius ? p.period / 200 : 0.05;
  advance_sampling_trail(run, trail, p.radius ? laps * p.period : 5.0);
  return circle_readout(run, trail);
}

// physics.md's worked examples W3 and W4, as printed: the predicted radius is theirs, and the path
// the engine integrates lies on a circle of that radius (fitted through its points: another
// computation than the formula's).
TEST(PathCircle, TheWorkedExamplesCirclesArePredictedAndMeasured) {
  Scene w3 = rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  set_rigid_motion(w3, 0.5, kPi / 2, 1.0);
  const CircleReadout c3 = after_laps(w3, 1.25);
  ASSERT_TRUE(c3.predicted.radius && c3.measured);
  // Predicted from the state's s and v (their round-off: ~1e-13).
  EXPECT_NEAR(*c3.predicted.radius, 0.4636476090008061, 1e-12);
  EXPECT_NEAR(c3.predicted.period, 5.619851784832581, 1e-12);
  EXPECT_NEAR(*c3.measured, 0.4636476090008061, 1e-9);
  EXPECT_EQ(circle_line(w3, c3), "circle radius = 0.4636 (predicted 0.4636)");

  Scene w4 = rigid_scene(SurfaceKind::pseudosphere, 1.0, 1.0, 0.5, 1.0);
  set_rigid_motion(w4, 0.5, kPi / 2, 1.0);
  const CircleReadout c4 = after_laps(w4, 1.25);
  ASSERT_TRUE(c4.predicted.radius && c4.measured);
  EXPECT_NEAR(*c4.predicted.radius, 0.5493061443340548, 1e-12);
  EXPECT_NEAR(c4.predicted.period, 7.255197456936871, 1e-11);
  EXPECT_NEAR(*c4.measured, 0.5493061443340548, 1e-9);

  // W4 with s = 0.25: a hypercycle, no circle; the plane: a straight line.
  set_rigid_motion(w4, 0.5, kPi / 2, 0.25);
  const CircleReadout hyper = after_laps(w4, 1.0);
  EXPECT_FALSE(hyper.predicted.radius || hyper.measured);
  EXPECT_EQ(circle_line(w4, hyper), "no circle: a hypercycle: |s| < m v R");
  set_rigid_motion(w4, 0.5, kPi / 2, 0.0);
  EXPECT_EQ(circle_line(w4, after_laps(w4, 1.0)), "no circle: a geodesic: no spin (s = 0)");
  Scene flat = rigid_scene(SurfaceKind::plane, 1.0, 1.0, 0.5, 1.0);
  set_rigid_motion(flat, 0.5, kPi / 2, 1.0);
  EXPECT_EQ(circle_line(flat, after_laps(flat, 1.0)), "no circle: a straight line: no curvature (K = 0)");
}

// Before an eighth of a lap the fit would rest on a short arc: the line says it is measuring.
TEST(PathCircle, AShortPathIsStillMeasuring) {
  Scene w3 = rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  set_rigid_motion(w3, 0.5, kPi / 2, 1.0);
  const CircleReadout early = after_laps(w3, 0.1);
  EXPECT_TRUE(early.predicted.radius);
  EXPECT_FALSE(early.measured);
  EXPECT_EQ(circle_line(w3, early), "circle radius: predicted 0.4636 (measuring)");
}

// The fit alone, on circles made from their definition (points at geodesic distance ρ from a
// centre): any radius on S² (the smaller of the two), circles on H² far from its vertex, and none
// through points of a geodesic of H² (a plane through the origin: no circle).
TEST(PathCircle, TheFitGivesTheRadiusOfCirclesMadeFromTheirDefinition) {
  for (const double rho : {1e-4, 0.3, kPi / 2, 2.5}) {
    const Surface sphere{SurfaceKind::sphere, 2.0};
    const ChartPoint centre = chart_point(sphere, 1.1, 0.4);
    std::vector<Vec3> points;
    for (int k = 0; k < 40; ++k) {
      const double a = 0.9 * k / 40.0;  // a quarter-turn's arc and more
      const Vec3 dir = std::cos(a) * centre.E1 + std::sin(a) * centre.E2;
      points.push_back(std::cos(rho / 2.0) * centre.X + 2.0 * std::sin(rho / 2.0) * dir);
    }
    double off = 1.0;
    const auto fit = circle_through(sphere, points, &off);
    ASSERT_TRUE(fit) << rho;
    EXPECT_NEAR(*fit, std::min(rho, 2.0 * kPi - rho), 1e-10 * std::max(1.0, rho)) << rho;
    EXPECT_LT(off, 1e-12);
  }
  const Surface h2{SurfaceKind::pseudosphere, 1.0};
  for (const double far : {0.0, 3.0, 8.0}) {
    const ChartPoint centre = chart_point(h2, far, 1.0);
    std::vector<Vec3> points;
    for (int k = 0; k < 40; ++k) {
      const double a = 2.0 * k / 40.0, rho = 0.7;
      const Vec3 dir = std::cos(a) * centre.E1 + std::sin(a) * centre.E2;
      points.push_back(std::cosh(rho) * centre.X + std::sinh(rho) * dir);
    }
    const auto fit = circle_through(h2, points);
    ASSERT_TRUE(fit) << far;
    EXPECT_NEAR(*fit, 0.7, 1e-8 * std::exp(far)) << far;
  }
  std::vector<Vec3> geodesic;
  for (int k = 0; k < 40; ++k) geodesic.push_back(chart_point(h2, -2.0 + 0.1 * k, 0.3).X);
  EXPECT_FALSE(circle_through(h2, geodesic));
}

}  // namespace
}  // namespace spinfold
