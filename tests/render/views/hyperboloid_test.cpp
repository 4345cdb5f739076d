// The hyperboloid view (render/views/hyperboloid.cpp): the sheet, its normal and lift.
#include <gtest/gtest.h>

#include <cmath>

#include "render/view_table.h"
#include "render/views/view_model.h"
#include "view_test_support.h"

namespace spinfold::render {
namespace {

TEST(HyperboloidView, PointsLandOnTheUnitSheetWithItsVertexAtTheOrigin) {
  const Surface h2{SurfaceKind::pseudosphere, 1.7};
  EXPECT_NEAR(glm::length(view_model(ViewKind::hyperboloid).world_position(h2, chart_point(h2, 0.0, 0.0).X)),
              0.0, 1e-12);
  for (const double r : {0.5, 2.0, 5.0}) {
    const glm::dvec3 w =
        view_model(ViewKind::hyperboloid).world_position(h2, chart_point(h2, r * h2.radius, 1.1).X);
    const double x3 = w.z + 1.0;
    EXPECT_NEAR(x3 * x3 - w.x * w.x - w.y * w.y, 1.0, 1e-9 * x3 * x3) << r;
  }
}

TEST(HyperboloidView, TheNormalIsPerpendicularToTheSheetAndOverlaysAreLiftedAlongIt) {
  const Surface h2{SurfaceKind::pseudosphere, 1.0};
  for (const double r : {0.0, 1.0, 3.0}) {
    const glm::dvec3 w = view_model(ViewKind::hyperboloid).world_position(h2, chart_point(h2, r, 0.3).X);
    const glm::dvec3 n = view_model(ViewKind::hyperboloid).normal(Surface(SurfaceKind::pseudosphere, 1.0), w);
    EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
    // The sheet's tangent along r (and along φ away from the vertex).
    const glm::dvec3 along_r =
        view_model(ViewKind::hyperboloid).world_position(h2, chart_point(h2, r + 1e-5, 0.3).X) - w;
    EXPECT_NEAR(glm::dot(glm::normalize(along_r), n), 0.0, 1e-4) << r;
    if (r > 0.0) {
      const glm::dvec3 along_phi =
          view_model(ViewKind::hyperboloid).world_position(h2, chart_point(h2, r, 0.3 + 1e-5).X) - w;
      EXPECT_NEAR(glm::dot(glm::normalize(along_phi), n), 0.0, 1e-4) << r;
    }
  }
  EXPECT_GT(view_model(ViewKind::hyperboloid).lift(), 0.0);
  EXPECT_GT(view_model(ViewKind::hyperboloid).depth_bias(), 0.0f);
}

TEST(HyperboloidView, TheMeshLiesOnTheSheet) {
  const StaticGeometry& g = static_geometry(SurfaceKind::pseudosphere, ViewKind::hyperboloid);
  ASSERT_FALSE(g.surface.empty());
  for (std::size_t i = 0; i < g.surface.size(); i += 97) {
    const glm::dvec3 w(g.surface[i].position);
    const double x3 = w.z + 1.0;
    EXPECT_NEAR(std::sqrt(1.0 + w.x * w.x + w.y * w.y), x3, 1e-4 * x3);
  }
}

}  // namespace
}  // namespace spinfold::render
