// The plane view (render/views/plane.cpp): no static geometry, a background that follows the camera.
#include <gtest/gtest.h>

#include <cmath>

#include "render/view_table.h"
#include "render/views/view_model.h"
#include "view_test_support.h"

namespace spinfold::render {
namespace {

TEST(PlaneView, PointsAreTheirOwnCoordinatesInRadii) {
  const Surface flat{SurfaceKind::plane, 2.0};
  EXPECT_EQ(view_model(ViewKind::plane).world_position(flat, Vec3(3.0, -1.0, 0.0)),
            glm::dvec3(1.5, -0.5, 0.0));
}

TEST(PlaneView, ItHasNoStaticGeometryAndItsBackgroundIsDrawnPerFrameOnlyForItsLayers) {
  const StaticGeometry& g = static_geometry(SurfaceKind::plane, ViewKind::plane);
  EXPECT_TRUE(g.surface.empty());
  EXPECT_TRUE(g.grid.empty());
  const Snapshot s = testing::body_at(SurfaceKind::plane, 1.0, 0.5, 0.0);
  ViewOptions view;
  view.kind = ViewKind::plane;
  view.layers = kBody;
  const FrameScene bare = build_scene(s, view);
  EXPECT_TRUE(bare.grid_lines.empty());
  EXPECT_NE(bare.clear_color, bare.surface_color);
  view.layers = kSurface | kGrid;
  const FrameScene full = build_scene(s, view);
  EXPECT_FALSE(full.grid_lines.empty());
  EXPECT_EQ(full.clear_color, full.surface_color);  // the plane fills the frame
}

TEST(PlaneView, AimingCentresTheWindowOnTheBodies) {
  Snapshot s = testing::body_at(SurfaceKind::plane, 1.0, 4.0, 0.5);
  s.bodies.push_back(s.bodies[0]);
  s.bodies[1].X = Vec3(-2.0, 1.0, 0.0);
  ViewOptions view;
  view.kind = ViewKind::plane;
  aim_camera_at_body(view, s);
  ASSERT_TRUE(view.target);
  const glm::dvec3 a = view_model(ViewKind::plane).world_position(s.surface, s.bodies[0].X);
  EXPECT_NEAR((*view.target)[0], 0.5 * (a.x - 2.0), 1e-12);
  EXPECT_NEAR((*view.target)[1], 0.5 * (a.y + 1.0), 1e-12);
}

}  // namespace
}  // namespace spinfold::render
