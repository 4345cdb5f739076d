// The surfaces and their polar chart (engine/surface.h, physics.md §1), against the closed forms
// written out here and against derivatives taken numerically.
#include "engine/surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "engine/revolution.h"
#include "engine/scene_fields.h"

namespace spinfold {
namespace {

const Surface kSurfaces[] = {
    {SurfaceKind::sphere, 2.0}, {SurfaceKind::pseudosphere, 2.0}, {SurfaceKind::plane, 2.0}};

// The catalog's offers are consistent for every kind: each runs either in the polar chart (with one
// sign of K) or by the chart-free equations on its F; a profile chart or a formula comes with an F;
// every profile chart has its entry, named as the scene names the kind.
TEST(Surface, EveryKindOffersOneConsistentSetOfCapabilities) {
  ASSERT_EQ(std::size(kSurfaceCatalog), std::size(kSurfaceKindNames));
  std::size_t profiles = 0;
  for (const EnumName<SurfaceKind>& n : kSurfaceKindNames) {
    const SurfaceKind k = n.value;
    SCOPED_TRACE(std::string(n.name));
    const bool polar = offers(k, Offer::polar_chart), implicit = offers(k, Offer::implicit_equation);
    EXPECT_NE(polar, implicit);
    Surface s;
    s.kind = k;
    EXPECT_EQ(chart_free(s), implicit);
    const int signs = offers(k, Offer::positive_curvature) + offers(k, Offer::negative_curvature) +
                      offers(k, Offer::zero_curvature);
    EXPECT_EQ(signs, polar ? 1 : 0);
    if (offers(k, Offer::profile_chart) || offers(k, Offer::formula)) {
      EXPECT_TRUE(implicit);
    }
    EXPECT_FALSE(offers(k, Offer::profile_chart) && offers(k, Offer::formula));
    EXPECT_EQ((surfaces_offering(Offer::polar_chart) & surface_bit(k)) != 0, polar);
    EXPECT_EQ(kSurfaceCatalog[static_cast<unsigned>(k)].profile != nullptr, offers(k, Offer::profile_chart));
    if (offers(k, Offer::profile_chart)) {
      ++profiles;
      EXPECT_EQ(revolution_entry(k).kind, k);
      EXPECT_EQ(revolution_entry(k).name, n.name);
      EXPECT_EQ(find_revolution(n.name), &revolution_entry(k));
    } else {
      EXPECT_THROW(revolution_entry(k), std::logic_error);
      EXPECT_EQ(find_revolution(n.name), nullptr);
    }
    if (polar) {
      EXPECT_NO_THROW(curvature_sign(s));
    } else {
      EXPECT_THROW(curvature_sign(s), std::logic_error);
    }
  }
  EXPECT_EQ(revolution_catalog().size(), profiles);
  EXPECT_FALSE(offers(static_cast<SurfaceKind>(99), Offer::implicit_equation));
}

// The scene's defaults and the profile chart's parameter record agree (they once did not: the
// spheroid's polar radius was 0.6 in one and 1.0 in the other).
TEST(Surface, ProfileParametersDefaultAsTheScene) {
  const Surface scene;
  const RevolutionSurface profile;
  EXPECT_EQ(profile.tube_radius, scene.tube_radius);
  EXPECT_EQ(profile.center_radius, scene.center_radius);
  EXPECT_EQ(profile.equatorial_radius, scene.equatorial_radius);
  EXPECT_EQ(profile.polar_radius, scene.polar_radius);
  EXPECT_EQ(profile.height, scene.height);
  EXPECT_EQ(profile.width, scene.width);
  EXPECT_EQ(profile.neck_radius, scene.neck_radius);
}

TEST(Surface, CurvatureIsSignOverRadiusSquared) {
  EXPECT_EQ(curvature_sign(kSurfaces[0]), 1.0);
  EXPECT_EQ(curvature_sign(kSurfaces[1]), -1.0);
  EXPECT_EQ(curvature_sign(kSurfaces[2]), 0.0);
  EXPECT_EQ(curvature(kSurfaces[0]), 0.25);
  EXPECT_EQ(curvature(kSurfaces[1]), -0.25);
  EXPECT_EQ(curvature(kSurfaces[2]), 0.0);
}

// A given curvature sets kind and radius (R = 1/√|K|); below kFlatCurvature it is the plane of
// length scale 1; without one the surface is left as it is.
TEST(Surface, ResolveCurvatureFromAGivenK) {
  Surface s;
  s.curvature_given = 4.0;
  resolve_curvature(s);
  EXPECT_EQ(s.kind, SurfaceKind::sphere);
  EXPECT_DOUBLE_EQ(s.radius, 0.5);
  s.curvature_given = -0.25;
  resolve_curvature(s);
  EXPECT_EQ(s.kind, SurfaceKind::pseudosphere);
  EXPECT_DOUBLE_EQ(s.radius, 2.0);
  s.curvature_given = -1e-30;
  resolve_curvature(s);
  EXPECT_EQ(s.kind, SurfaceKind::plane);
  EXPECT_EQ(s.radius, 1.0);
  Surface untouched{SurfaceKind::pseudosphere, 3.0};
  resolve_curvature(untouched);
  EXPECT_EQ(untouched.kind, SurfaceKind::pseudosphere);
  EXPECT_EQ(untouched.radius, 3.0);
}

// S(r) = R sin(r/R), R sinh(r/R), r; C = S′ (checked by a central difference).
TEST(Surface, PolarSAndItsDerivative) {
  const double r = 1.3, R = 2.0;
  EXPECT_DOUBLE_EQ(polar_S(kSurfaces[0], r), R * std::sin(r / R));
  EXPECT_DOUBLE_EQ(polar_S(kSurfaces[1], r), R * std::sinh(r / R));
  EXPECT_DOUBLE_EQ(polar_S(kSurfaces[2], r), r);
  EXPECT_DOUBLE_EQ(polar_C(kSurfaces[0], r), std::cos(r / R));
  EXPECT_DOUBLE_EQ(polar_C(kSurfaces[1], r), std::cosh(r / R));
  EXPECT_EQ(polar_C(kSurfaces[2], r), 1.0);
  const double h = 1e-5;
  for (const Surface& s : kSurfaces)
    EXPECT_NEAR((polar_S(s, r + h) - polar_S(s, r - h)) / (2 * h), polar_C(s, r), 1e-9) << curvature(s);
}

// The chart point lies on the surface (⟨X, X⟩ = σR² on S² and H², X₃ = 0 on the plane); E₁ and E₂
// are unit, orthogonal and tangent; E₁ = ∂X/∂r and S E₂ = ∂X/∂φ numerically; E₂ = j E₁.
TEST(Surface, ChartPointFrameIsOrthonormalAndTangent) {
  const double h = 1e-6;
  for (const Surface& s : kSurfaces)
    for (const double r : {0.0, 0.4, 1.7, 2.9})
      for (const double phi : {0.0, 1.0, -2.5}) {
        const ChartPoint p = chart_point(s, r, phi);
        const double R = s.radius;
        if (offers(s, Offer::zero_curvature))
          EXPECT_EQ(p.X.z(), 0.0);
        else
          EXPECT_NEAR(dot(s, p.X, p.X), curvature_sign(s) * R * R, 1e-12);
        EXPECT_NEAR(dot(s, p.E1, p.E1), 1.0, 1e-12);
        EXPECT_NEAR(dot(s, p.E2, p.E2), 1.0, 1e-12);
        EXPECT_NEAR(dot(s, p.E1, p.E2), 0.0, 1e-12);
        if (!offers(s, Offer::zero_curvature)) {
          EXPECT_NEAR(dot(s, p.E1, p.X), 0.0, 1e-12);
          EXPECT_NEAR(dot(s, p.E2, p.X), 0.0, 1e-12);
        }
        const Vec3 dX_dr = (chart_point(s, r + h, phi).X - chart_point(s, r - h, phi).X) / (2 * h);
        const Vec3 dX_dphi = (chart_point(s, r, phi + h).X - chart_point(s, r, phi - h).X) / (2 * h);
        EXPECT_LT((dX_dr - p.E1).norm(), 1e-8) << r << " " << phi;
        EXPECT_LT((dX_dphi - polar_S(s, r) * p.E2).norm(), 1e-8) << r << " " << phi;
        EXPECT_LT((rotate_quarter(s, p.X, p.E1) - p.E2).norm(), 1e-12) << r << " " << phi;
      }
}

// polar_coordinates inverts chart_point for r > 0; r < 0 is the point (|r|, φ + π).
TEST(Surface, PolarCoordinatesInvertTheChart) {
  for (const Surface& s : kSurfaces) {
    const PolarCoordinates q = polar_coordinates(s, chart_point(s, 1.1, 0.7).X);
    EXPECT_NEAR(q.r, 1.1, 1e-14);
    EXPECT_NEAR(q.phi, 0.7, 1e-14);
    EXPECT_NEAR(q.rho, std::abs(polar_S(s, 1.1)), 1e-14);
    EXPECT_LT((chart_point(s, -1.1, 0.7).X - chart_point(s, 1.1, 0.7 + std::numbers::pi).X).norm(), 1e-14);
  }
  EXPECT_EQ(polar_coordinates(kSurfaces[0], {0.0, 0.0, 2.0}).r, 0.0);  // the pole
  EXPECT_NEAR(polar_coordinates(kSurfaces[0], {0.0, 0.0, -2.0}).r, 2.0 * std::numbers::pi,
              1e-15);  // antipode
}

// ⟨a, b⟩ is Minkowski (η = diag(1, 1, −1)) on H² only; raise applies η.
TEST(Surface, DotAndRaiseUseTheMinkowskiMetricOnlyOnH2) {
  const Vec3 a{1.0, 2.0, 3.0}, b{-1.0, 0.5, 2.0};
  EXPECT_EQ(dot(kSurfaces[0], a, b), 6.0);
  EXPECT_EQ(dot(kSurfaces[1], a, b), -6.0);
  EXPECT_EQ(dot(kSurfaces[2], a, b), 6.0);
  EXPECT_EQ(raise(kSurfaces[1], a), Vec3(1.0, 2.0, -3.0));
  EXPECT_EQ(raise(kSurfaces[0], a), a);
}

// The tangential part removes the normal component: P(X) = 0, P(E) = E for a tangent E, and P(w)
// is tangent for any w.
TEST(Surface, TangentialProjects) {
  const Vec3 w{0.3, -1.2, 0.8};
  for (const Surface& s : kSurfaces) {
    const ChartPoint p = chart_point(s, 0.9, 2.0);
    EXPECT_LT((tangential(s, p.X, p.E1) - p.E1).norm(), 1e-14);
    EXPECT_LT((tangential(s, p.X, p.E2) - p.E2).norm(), 1e-14);
    if (offers(s, Offer::zero_curvature)) {
      EXPECT_EQ(tangential(s, p.X, w), Vec3(0.3, -1.2, 0.0));
    } else {
      EXPECT_LT(tangential(s, p.X, p.X).norm(), 1e-14);
      EXPECT_NEAR(dot(s, tangential(s, p.X, w), p.X), 0.0, 1e-14);
    }
  }
}

TEST(Surface, UnitNormal) {
  EXPECT_EQ(unit_normal(kSurfaces[0], {0.0, 0.0, 2.0}), Vec3(0.0, 0.0, 1.0));
  EXPECT_EQ(unit_normal(kSurfaces[1], {2.0, 0.0, 4.0}), Vec3(1.0, 0.0, 2.0));
  EXPECT_EQ(unit_normal(kSurfaces[2], {5.0, 1.0, 0.0}), Vec3::UnitZ());
}

}  // namespace
}  // namespace spinfold
