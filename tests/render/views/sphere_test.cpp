// The sphere view (render/views/sphere.cpp): projection, circumscribed mesh, limb, aiming.
#include <gtest/gtest.h>

#include <cmath>

#include "render/view_table.h"
#include "render/views/view_model.h"
#include "view_test_support.h"

namespace spinfold::render {
namespace {

using testing::body_at;

const ViewModel& sphere() {
  return view_model(ViewKind::sphere);
}

TEST(SphereView, PointsLandOnTheUnitSphereAndTheNormalIsRadial) {
  const Surface s{SurfaceKind::sphere, 2.5};
  for (const double theta : {0.1, 1.0, 2.0, 3.0}) {
    const Vec3 X = chart_point(s, theta * s.radius, 0.8).X;
    const glm::dvec3 w = sphere().world_position(s, X);
    EXPECT_NEAR(glm::length(w), 1.0, 1e-12);
    EXPECT_NEAR(glm::length(sphere().normal(Surface(SurfaceKind::sphere, 1.0), w) - w), 0.0, 1e-12);
  }
  EXPECT_EQ(sphere().lift(), 0.0);  // on the sphere exactly: the mesh is circumscribed
}

TEST(SphereView, TheMeshIsCircumscribedEveryFaceJustOutsideTheUnitSphere) {
  const StaticGeometry& g = static_geometry(SurfaceKind::sphere, ViewKind::sphere);
  ASSERT_FALSE(g.surface.empty());
  ASSERT_FALSE(g.grid.empty());
  double nearest = 1e9;
  for (std::size_t i = 0; i + 2 < g.surface.size(); i += 3) {
    const glm::dvec3 a(g.surface[i].position), b(g.surface[i + 1].position), c(g.surface[i + 2].position);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    if (glm::length(n) < 1e-12) continue;  // the poles' degenerate quads
    nearest = std::min(nearest, std::abs(glm::dot(glm::normalize(n), a)));
  }
  EXPECT_GE(nearest, 1.0 - 1e-6);  // no face cuts into the sphere (float rounding aside)
  EXPECT_LT(nearest, 1.0 + 1e-3);  // and none stands far off it
}

TEST(SphereView, PointsNearTheLimbOrBeyondItAreHiddenFromTheCamera) {
  const glm::dvec3 eye(0.0, 0.0, 3.4);
  EXPECT_FALSE(sphere().hidden(Surface(SurfaceKind::sphere, 1.0), {0.0, 0.0, 1.0}, eye));
  EXPECT_FALSE(sphere().hidden(Surface(SurfaceKind::sphere, 1.0), {std::sin(0.9), 0.0, std::cos(0.9)},
                               eye));  // 52° from the camera's direction
  EXPECT_TRUE(sphere().hidden(Surface(SurfaceKind::sphere, 1.0), {std::sin(1.2), 0.0, std::cos(1.2)},
                              eye));  // 69°: seen edge-on
  EXPECT_TRUE(sphere().hidden(Surface(SurfaceKind::sphere, 1.0), {0.0, 0.0, -1.0}, eye));
}

TEST(SphereView, AimingTurnsTheCameraToABodyOnTheFarSide) {
  const Snapshot s = body_at(SurfaceKind::sphere, 1.0, 2.4, 3.5);  // behind the default camera
  ViewOptions view;
  const FrameScene before = build_scene(s, view);
  const glm::dvec4 h = glm::inverse(glm::dmat4(before.view_projection)) * glm::dvec4(0, 0, 1, 0);
  EXPECT_TRUE(sphere().hidden(Surface(SurfaceKind::sphere, 1.0),
                              world_position(s.surface, view.kind, s.bodies[0].X), glm::dvec3(h) / h.w));
  aim_camera_at_body(view, s);
  const FrameScene after = build_scene(s, view);
  const std::optional<glm::dvec2> px = testing::pixel_of(after, view, s.surface, s.bodies[0].X);
  ASSERT_TRUE(px);
  EXPECT_NEAR(px->x, 0.5 * view.width, 0.25 * view.width);
  EXPECT_NEAR(px->y, 0.5 * view.height, 0.25 * view.height);
  EXPECT_FALSE(view.target);  // the sphere's camera always orbits its centre
}

}  // namespace
}  // namespace spinfold::render
