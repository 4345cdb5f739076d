// The Klein view (render/views/klein.cpp): the central projection of the hyperboloid.
#include <gtest/gtest.h>

#include <cmath>

#include "render/view_table.h"
#include "render/views/view_model.h"
#include "view_test_support.h"

namespace spinfold::render {
namespace {

TEST(KleinView, AtDistanceRAPointLiesAtTanhRAndIsThePoincarePointDoubled) {
  const Surface h2{SurfaceKind::pseudosphere, 1.3};
  for (const double r : {0.2, 1.0, 4.0}) {  // [radii]
    const Vec3 X = chart_point(h2, r * h2.radius, 2.2).X;
    const glm::dvec3 k = view_model(ViewKind::klein).world_position(h2, X);
    EXPECT_NEAR(glm::length(k), std::tanh(r), 1e-12) << r;
    // k = 2p/(1 + |p|²) of the Poincaré disk's p.
    const glm::dvec2 p(world_position(h2, ViewKind::disk, X));
    const glm::dvec2 expected = 2.0 * p / (1.0 + glm::dot(p, p));
    EXPECT_NEAR(glm::length(glm::dvec2(k) - expected), 0.0, 1e-12) << r;
  }
}

TEST(KleinView, TheStaticDiskIsTheUnitDiskWithItsRimAndAGrid) {
  const StaticGeometry& g = static_geometry(SurfaceKind::pseudosphere, ViewKind::klein);
  double reach = 0.0;
  for (const LitVertex& v : g.surface) reach = std::max(reach, double(glm::length(v.position)));
  EXPECT_NEAR(reach, 1.0, 1e-6);
  std::size_t on_rim = 0;
  for (const Vertex& v : g.grid) on_rim += std::abs(glm::length(v.position) - 1.0f) < 1e-6f;
  EXPECT_GE(on_rim, 2u * 128u);      // the rim's 128 segments
  EXPECT_GT(g.grid.size(), on_rim);  // and the polar grid inside
}

}  // namespace
}  // namespace spinfold::render
