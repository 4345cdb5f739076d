// The shape a picture asks of any surface whose curvature varies (engine/surface_shape.h): the box
// chosen from a formula holds a closed surface whole and an unbounded one's piece about the origin,
// a given box is kept, the feature follows the curvature, profile surfaces keep their pictures, and
// one surface is resolved once.
#include "engine/surface_shape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "engine/formula_surface.h"
#include "formula_surfaces.h"

namespace spinfold {
namespace {

using test::graph_surface;
using test::implicit_surface;

TEST(SurfaceShape, AClosedSurfaceIsBoxedWholeWithAnEighthToSpare) {
  // The triaxial ellipsoid x²/a² + y²/b² + z²/c² = 1 at several sizes: its box holds ±(a, b, c) and
  // is at most an eighth of its largest side wider each way (and a sample step).
  for (const double scale : {0.3, 1.0, 2.5, 9.0}) {
    const double a = 2.0 * scale, b = 1.4 * scale, c = 0.9 * scale;
    const auto shape =
        surface_shape_of(implicit_surface("x^2/a^2 + y^2/b^2 + z^2/c^2 - 1", {{"a", a}, {"b", b}, {"c", c}}));
    EXPECT_TRUE(shape->closed) << scale;
    const double half[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(shape->box[k][0], -half[k]) << scale << " axis " << k;
      EXPECT_GT(shape->box[k][1], half[k]) << scale << " axis " << k;
      // The cube searched is the first of side 2h > 2a; the samples beside a sign change are within
      // a step (2h/24) of the surface.
      const double step = 2.0 * std::exp2(std::floor(std::log2(a)) + 1.0) / 24.0;
      EXPECT_LT(shape->box[k][1], half[k] + (2.0 * a + 2.0 * step) / 8.0 + step) << scale << " axis " << k;
    }
    EXPECT_NEAR(shape->length, 0.5 * (shape->box[0][1] - shape->box[0][0]), 1e-12);
    // The feature: 1/√max|K|, K largest at (±a, 0, 0): a²/(b²c²)... within the smallest half-extent.
    const double largest_K = a * a / (b * b * c * c);
    EXPECT_NEAR(shape->feature, 1.0 / std::sqrt(largest_K), 0.05 / std::sqrt(largest_K)) << scale;
  }
}

TEST(SurfaceShape, AnUnboundedSurfaceIsDrawnInTheCubeAboutTheOrigin) {
  // The monkey saddle's height spans 4h³ on the square of half-side h: 32 > 4·2 at h = 2, 4 ≤ 4·1 at
  // h = 1, so it is drawn on the unit square, z over [−2, 2] and a spare eighth, cut to the cube.
  const auto saddle = surface_shape_of(graph_surface("x^3 - 3*x*y^2"));
  EXPECT_FALSE(saddle->closed);
  EXPECT_DOUBLE_EQ(saddle->box[0][0], -1.0);
  EXPECT_DOUBLE_EQ(saddle->box[1][1], 1.0);
  EXPECT_DOUBLE_EQ(saddle->box[2][0], -1.0);
  EXPECT_DOUBLE_EQ(saddle->box[2][1], 1.0);
  // A gentle one keeps the square of h = 2.
  const auto bowl = surface_shape_of(graph_surface("0.2*(x^2 + y^2)"));
  EXPECT_DOUBLE_EQ(bowl->box[0][1], 2.0);
  EXPECT_NEAR(bowl->box[2][1], 1.6 + 0.2, 1e-9);
  // A flat graph: z spans a sliver about its height.
  const auto flat = surface_shape_of(graph_surface("0.5"));
  EXPECT_LT(flat->box[2][0], 0.5);
  EXPECT_GT(flat->box[2][1], 0.5);
  EXPECT_LT(flat->box[2][1] - flat->box[2][0], 0.5);
  // An implicit cylinder reaches every cube's faces along z.
  const auto cylinder = surface_shape_of(implicit_surface("x^2 + y^2 - 0.25"));
  EXPECT_FALSE(cylinder->closed);
  EXPECT_DOUBLE_EQ(cylinder->box[2][1], 2.0);
  EXPECT_NEAR(cylinder->feature, 2.0 / 3.0, 1e-12);  // K = 0: a third of the box's half-size
}

TEST(SurfaceShape, AGivenBoxIsKept) {
  Surface s = implicit_surface("x^2 + y^2 + z^2 - 1");
  s.bounds = SurfaceBounds{{{-1.5, 1.5}, {-1.5, 1.5}, {0.0, 1.5}}};
  const auto shape = surface_shape_of(s);
  EXPECT_EQ(shape->box, *s.bounds);
  EXPECT_FALSE(shape->closed);  // the piece drawn is cut by the box
  EXPECT_DOUBLE_EQ(shape->centre.z(), 0.75);
  EXPECT_DOUBLE_EQ(shape->length, 1.5);
}

TEST(SurfaceShape, ProfileSurfacesKeepTheirPictures) {
  for (const SurfaceKind kind :
       {SurfaceKind::torus, SurfaceKind::spheroid, SurfaceKind::bump, SurfaceKind::catenoid}) {
    Surface s;
    s.kind = kind;
    const auto shape = surface_shape_of(s);
    const RevolutionSurface r = revolution_surface(s);
    const ProfilePicture picture = revolution_entry(r.kind).picture(r);
    EXPECT_EQ(shape->feature, picture.feature);
    EXPECT_EQ(shape->length, picture.length);
    EXPECT_EQ(shape->centre, Vec3::Zero());
    // F at a point of the profile is the profile's own.
    const Vec3 X = revolution_frame(r, 0.3, 0.4).X;
    EXPECT_EQ(shape->value(X), RevolutionImplicit(r).at(X).F);
  }
  Surface torus;
  torus.kind = SurfaceKind::torus;
  EXPECT_TRUE(surface_shape_of(torus)->closed);
  Surface bump;
  bump.kind = SurfaceKind::bump;
  EXPECT_FALSE(surface_shape_of(bump)->closed);
}

TEST(SurfaceShape, OneSurfaceIsResolvedOnceAndAnotherIsAnother) {
  const Surface a = implicit_surface("x^2 + y^2 + z^2 - r^2", {{"r", 1.0}});
  EXPECT_EQ(surface_shape_of(a), surface_shape_of(a));
  Surface b = a;
  b.parameters["r"] = 2.0;
  EXPECT_NE(surface_shape_of(a), surface_shape_of(b));
  EXPECT_GT(surface_shape_of(b)->length, 1.5 * surface_shape_of(a)->length);
  // F read through the formula's program equals F from the jet.
  const Vec3 X(0.3, -0.2, 0.7);
  EXPECT_DOUBLE_EQ(surface_shape_of(b)->value(X), surface_shape_of(b)->implicit->at(X).F);
}

TEST(SurfaceShape, ConstantCurvatureHasNone) {
  EXPECT_THROW(surface_shape_of(Surface{SurfaceKind::sphere, 1.0}), std::logic_error);
}

}  // namespace
}  // namespace spinfold
