// Points and geodesics on an implicit surface, checked against closed forms: the sphere's great
// circles (a spheroid with a = b), the torus's outer equator (a geodesic), and RK4's order.
#include "engine/surface_geodesics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace spinfold {
namespace {

RevolutionSurface spheroid(double a, double b) {
  RevolutionSurface s{.kind = SurfaceKind::spheroid, .equatorial_radius = a, .polar_radius = b};
  return s;
}

TEST(SurfaceGeodesics, ProjectionLandsOnTheSurface) {
  RevolutionSurface torus{.kind = SurfaceKind::torus, .tube_radius = 0.7, .center_radius = 2.0};
  const RevolutionImplicit F(torus);
  for (const Vec3& off : {Vec3(2.9, 0.1, 0.3), Vec3(1.1, 0.4, -0.2), Vec3(-0.5, 2.2, 0.65)}) {
    const Vec3 p = project_onto_surface(F, off);
    // On the torus: its distance from the centre circle is the tube radius.
    EXPECT_NEAR(std::hypot(std::hypot(p.x(), p.y()) - 2.0, p.z()), 0.7, 1e-14) << off.transpose();
    EXPECT_LT((p - off).norm(), 0.35);  // near where it started
  }
}

TEST(SurfaceGeodesics, TheExponentialMapOfASphereShapedSpheroidIsTheGreatCircle) {
  const RevolutionImplicit F(spheroid(1.3, 1.3));
  const Vec3 X(1.3 * std::sin(0.8), 0.0, 1.3 * std::cos(0.8));
  const Vec3 e(std::cos(0.8) * 0.6, 0.8, -std::sin(0.8) * 0.6);  // unit, tangent
  for (const double len : {0.2, 0.5, 1.0}) {
    const Vec3 v = len * e;
    const Vec3 exact = std::cos(len / 1.3) * X + 1.3 * std::sin(len / 1.3) * e;
    const double err8 = (implicit_exponential_map(F, X, v, 8) - exact).norm();
    const double err16 = (implicit_exponential_map(F, X, v, 16) - exact).norm();
    EXPECT_LT(err8, 1e-6 * len) << len;
    // Fourth order: halving the step divides the error by about 16 (projection keeps it on S²).
    if (err16 > 1e-15) {
      EXPECT_GT(err8 / err16, 8.0) << len;
    }
  }
}

TEST(SurfaceGeodesics, TheTorussOuterEquatorIsAGeodesic) {
  RevolutionSurface torus{.kind = SurfaceKind::torus, .tube_radius = 1.0, .center_radius = 2.5};
  const RevolutionImplicit F(torus);
  const Vec3 X(3.5, 0.0, 0.0);
  const Vec3 p = implicit_exponential_map(F, X, Vec3(0.0, 1.4, 0.0), 16);
  EXPECT_NEAR(p.z(), 0.0, 1e-12);
  EXPECT_NEAR(std::atan2(p.y(), p.x()), 1.4 / 3.5, 1e-8);
  EXPECT_NEAR(std::hypot(p.x(), p.y()), 3.5, 1e-12);
}

TEST(SurfaceGeodesics, AZeroVectorStaysPut) {
  const RevolutionImplicit F(spheroid(1.0, 0.6));
  const Vec3 X(1.0, 0.0, 0.0);
  EXPECT_EQ(implicit_exponential_map(F, X, Vec3::Zero()), X);
}

}  // namespace
}  // namespace spinfold
