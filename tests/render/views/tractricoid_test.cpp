// The tractricoid view (render/views/tractricoid.cpp): the covering map, its strip and rim, the normal.
#include <gtest/gtest.h>

#include <cmath>

#include "render/view_table.h"
#include "render/views/drawing.h"
#include "render/views/view_model.h"
#include "view_test_support.h"

namespace spinfold::render {
namespace {

const ViewModel& tractricoid() {
  return view_model(ViewKind::tractricoid);
}

// The H² point at half-plane coordinates (x, y): the inverse of half_plane_point.
Vec3 from_half_plane(const Surface& h2, double x, double y) {
  const double R = h2.radius, minus = R / y, plus = R * (x * x + y * y) / y;  // X₃ − X₁, X₃ + X₁
  return {0.5 * (plus - minus), -x * R / y, 0.5 * (plus + minus)};
}

TEST(TractricoidView, PointsOfTheStripLandOnTheSurfaceOfRevolution) {
  const Surface h2{SurfaceKind::pseudosphere, 1.0};
  for (const double y : {0.55, 0.7, 2.0, 20.0}) {  // y' = 2y > 1
    const glm::dvec3 w = tractricoid().world_position(h2, from_half_plane(h2, 0.3, y));
    const double rho = glm::length(glm::dvec2(w)), u = std::acosh(1.0 / rho);
    EXPECT_NEAR(rho, 1.0 / (kTractricoidDilation * y), 1e-12) << y;  // ρ = sech u = 1/y'
    EXPECT_NEAR(w.z, u - std::tanh(u), 1e-9) << y;
    EXPECT_NEAR(std::atan2(w.y, w.x), kTractricoidDilation * 0.3, 1e-12) << y;  // θ = x'
  }
}

TEST(TractricoidView, OnlyTheStripAboveTheRimIsOnTheViewAndItWrapsRoundEveryPiInX) {
  const Surface h2{SurfaceKind::pseudosphere, 1.0};
  EXPECT_TRUE(tractricoid().on_view(h2, from_half_plane(h2, 0.0, 0.51)));
  EXPECT_FALSE(tractricoid().on_view(h2, from_half_plane(h2, 0.0, 0.49)));
  const glm::dvec3 a = tractricoid().world_position(h2, from_half_plane(h2, 0.4, 1.5));
  const glm::dvec3 b = tractricoid().world_position(
      h2, from_half_plane(h2, 0.4 + 2 * std::numbers::pi / kTractricoidDilation, 1.5));
  EXPECT_NEAR(glm::length(a - b), 0.0, 1e-12);
}

TEST(TractricoidView, TheNormalIsPerpendicularToTheMeridianAndTheParallel) {
  const Surface h2{SurfaceKind::pseudosphere, 1.0};
  for (const double y : {0.6, 1.0, 4.0}) {
    const glm::dvec3 w = tractricoid().world_position(h2, from_half_plane(h2, 0.2, y));
    const glm::dvec3 n = tractricoid().normal(Surface(SurfaceKind::pseudosphere, 1.0), w);
    EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
    const glm::dvec3 meridian =
        tractricoid().world_position(h2, from_half_plane(h2, 0.2, y * (1 + 1e-6))) - w;
    const glm::dvec3 parallel = tractricoid().world_position(h2, from_half_plane(h2, 0.2 + 1e-6, y)) - w;
    EXPECT_NEAR(glm::dot(glm::normalize(meridian), n), 0.0, 1e-4) << y;
    EXPECT_NEAR(glm::dot(glm::normalize(parallel), n), 0.0, 1e-4) << y;
  }
}

TEST(TractricoidView, TheRimAndTheSeamAreMarkedInTheirOwnColour) {
  const StaticGeometry& g = static_geometry(SurfaceKind::pseudosphere, ViewKind::tractricoid);
  std::size_t seam = 0, rim = 0;
  for (const Vertex& v : g.grid)
    if (v.color == kSeamColor) {
      ++seam;
      rim += std::abs(v.position.z) < 0.01f;  // u = 0, lifted a little off the surface
    }
  EXPECT_GE(rim, 2u * 128u);        // the rim's 128 segments
  EXPECT_GE(seam - rim, 2u * 40u);  // and the seam's 64 but those near the rim
}

}  // namespace
}  // namespace spinfold::render
