// The surface model (engine/surface_model.h): every kind offers what its catalog row says and holds
// the pieces that serve it; the box chosen from a formula holds a closed surface whole and an
// unbounded one's piece about the origin, a given box is kept, the feature follows the curvature,
// profile surfaces keep their pictures, one surface is resolved once, and a run, its chart-free scene
// and its snapshot's owner share that one object.
#include "engine/surface_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "engine/formula_surface.h"
#include "engine/simulation.h"
#include "formula_surfaces.h"

namespace spinfold {
namespace {

using test::graph_surface;
using test::implicit_surface;

TEST(SurfaceModel, AClosedSurfaceIsBoxedWholeWithAnEighthToSpare) {
  // The triaxial ellipsoid x²/a² + y²/b² + z²/c² = 1 at several sizes: its box holds ±(a, b, c) and
  // is at most an eighth of its largest side wider each way (and a sample step).
  for (const double scale : {0.3, 1.0, 2.5, 9.0}) {
    const double a = 2.0 * scale, b = 1.4 * scale, c = 0.9 * scale;
    const auto shape =
        surface_model_of(implicit_surface("x^2/a^2 + y^2/b^2 + z^2/c^2 - 1", {{"a", a}, {"b", b}, {"c", c}}));
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

TEST(SurfaceModel, AnUnboundedSurfaceIsDrawnInTheCubeAboutTheOrigin) {
  // The monkey saddle's height spans 4h³ on the square of half-side h: 32 > 4·2 at h = 2, 4 ≤ 4·1 at
  // h = 1, so it is drawn on the unit square, z over [−2, 2] and a spare eighth, cut to the cube.
  const auto saddle = surface_model_of(graph_surface("x^3 - 3*x*y^2"));
  EXPECT_FALSE(saddle->closed);
  EXPECT_DOUBLE_EQ(saddle->box[0][0], -1.0);
  EXPECT_DOUBLE_EQ(saddle->box[1][1], 1.0);
  EXPECT_DOUBLE_EQ(saddle->box[2][0], -1.0);
  EXPECT_DOUBLE_EQ(saddle->box[2][1], 1.0);
  // A gentle one keeps the square of h = 2.
  const auto bowl = surface_model_of(graph_surface("0.2*(x^2 + y^2)"));
  EXPECT_DOUBLE_EQ(bowl->box[0][1], 2.0);
  EXPECT_NEAR(bowl->box[2][1], 1.6 + 0.2, 1e-9);
  // A flat graph: z spans a sliver about its height.
  const auto flat = surface_model_of(graph_surface("0.5"));
  EXPECT_LT(flat->box[2][0], 0.5);
  EXPECT_GT(flat->box[2][1], 0.5);
  EXPECT_LT(flat->box[2][1] - flat->box[2][0], 0.5);
  // An implicit cylinder reaches every cube's faces along z.
  const auto cylinder = surface_model_of(implicit_surface("x^2 + y^2 - 0.25"));
  EXPECT_FALSE(cylinder->closed);
  EXPECT_DOUBLE_EQ(cylinder->box[2][1], 2.0);
  EXPECT_NEAR(cylinder->feature, 2.0 / 3.0, 1e-12);  // K = 0: a third of the box's half-size
}

TEST(SurfaceModel, AGivenBoxIsKept) {
  Surface s = implicit_surface("x^2 + y^2 + z^2 - 1");
  s.bounds = SurfaceBounds{{{-1.5, 1.5}, {-1.5, 1.5}, {0.0, 1.5}}};
  const auto shape = surface_model_of(s);
  EXPECT_EQ(shape->box, *s.bounds);
  EXPECT_FALSE(shape->closed);  // the piece drawn is cut by the box
  EXPECT_DOUBLE_EQ(shape->centre.z(), 0.75);
  EXPECT_DOUBLE_EQ(shape->length, 1.5);
}

TEST(SurfaceModel, ProfileSurfacesKeepTheirPictures) {
  for (const SurfaceKind kind :
       {SurfaceKind::torus, SurfaceKind::spheroid, SurfaceKind::bump, SurfaceKind::catenoid}) {
    Surface s;
    s.kind = kind;
    const auto shape = surface_model_of(s);
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
  EXPECT_TRUE(surface_model_of(torus)->closed);
  Surface bump;
  bump.kind = SurfaceKind::bump;
  EXPECT_FALSE(surface_model_of(bump)->closed);
}

TEST(SurfaceModel, OneSurfaceIsResolvedOnceAndAnotherIsAnother) {
  const Surface a = implicit_surface("x^2 + y^2 + z^2 - r^2", {{"r", 1.0}});
  EXPECT_EQ(surface_model_of(a), surface_model_of(a));
  Surface b = a;
  b.parameters["r"] = 2.0;
  EXPECT_NE(surface_model_of(a), surface_model_of(b));
  EXPECT_GT(surface_model_of(b)->length, 1.5 * surface_model_of(a)->length);
  Surface boxed = a;
  boxed.bounds = SurfaceBounds{{{-1.0, 1.0}, {-1.0, 1.0}, {0.0, 1.0}}};
  EXPECT_NE(surface_model_of(boxed), surface_model_of(a));  // the box is part of what is drawn
  Surface same = a;
  same.F = std::string(a.F.begin(), a.F.end());  // equal text, another string: the same model
  EXPECT_EQ(surface_model_of(same), surface_model_of(a));
  // F read through the formula's program equals F from the jet.
  const Vec3 X(0.3, -0.2, 0.7);
  EXPECT_DOUBLE_EQ(surface_model_of(b)->value(X), surface_model_of(b)->implicit->at(X).F);
}

TEST(SurfaceModel, EveryKindHoldsWhatItOffersAndNothingElse) {
  for (const SurfaceRow& row : kSurfaceCatalog) {
    Surface s;
    s.kind = row.kind;
    s.radius = 2.0;
    const auto model = surface_model_of(s);
    SCOPED_TRACE(static_cast<int>(row.kind));
    EXPECT_EQ(model->offered, row.offers);
    EXPECT_EQ(model->surface.kind, row.kind);
    EXPECT_EQ(model->implicit != nullptr, model->offers(Offer::implicit_equation));
    EXPECT_EQ(model->profile.has_value(), model->offers(Offer::profile_chart));
    EXPECT_EQ(model->formula != nullptr, model->offers(Offer::formula));
    if (model->offers(Offer::polar_chart)) {
      // K = σ/R², and the drawn piece the ball of radius R.
      EXPECT_EQ(model->curvature, curvature(s));
      EXPECT_EQ(model->length, 2.0);
      EXPECT_EQ(model->closed, model->offers(Offer::positive_curvature));
    } else {
      EXPECT_TRUE(std::isnan(model->curvature));  // it varies: asked of F at a point
    }
  }
}

TEST(SurfaceModel, TheRadiusMakesAnotherConstantCurvatureModel) {
  const auto one = surface_model_of(Surface{SurfaceKind::pseudosphere, 1.0});
  const auto two = surface_model_of(Surface{SurfaceKind::pseudosphere, 2.0});
  EXPECT_NE(one, two);
  EXPECT_EQ(one->curvature, -1.0);
  EXPECT_EQ(two->curvature, -0.25);
}

TEST(SurfaceModel, ARunAndItsChartFreeSceneHoldTheSurfacesOneModel) {
  Surface torus;
  torus.kind = SurfaceKind::torus;
  for (const Surface& surface :
       {Surface{SurfaceKind::sphere, 1.0}, torus, implicit_surface("x^2 + y^2/4 + z^2 - 1")}) {
    Scene scene;
    scene.surface = surface;
    const Simulation run = start_simulation(scene);
    ASSERT_NE(run.surface, nullptr);
    EXPECT_EQ(run.surface, surface_model_of(scene.surface));
    EXPECT_EQ(run.embedded != nullptr, run.surface->offers(Offer::implicit_equation));
    if (run.embedded) {
      EXPECT_EQ(run.embedded->surface, run.surface);
    }
  }
}

}  // namespace
}  // namespace spinfold
