// The half-plane view (render/views/halfplane.cpp): the Cayley transform, the window, aiming.
#include <gtest/gtest.h>

#include <cmath>

#include "render/view_table.h"
#include "render/views/view_model.h"
#include "view_test_support.h"

namespace spinfold::render {
namespace {

TEST(HalfPlaneView, ThePoleGoesToIAndDistancesAreThoseOfTheHalfPlaneMetric) {
  const Surface h2{SurfaceKind::pseudosphere, 0.8};
  const glm::dvec3 pole = view_model(ViewKind::halfplane).world_position(h2, chart_point(h2, 0.0, 0.0).X);
  EXPECT_NEAR(pole.x, 0.0, 1e-15);
  EXPECT_NEAR(pole.y, 1.0, 1e-15);
  // cosh(d/R) = 1 + |a − b|²/(2 a_y b_y).
  const Vec3 A = chart_point(h2, 0.7, 0.4).X, B = chart_point(h2, 2.1, 2.9).X;
  const glm::dvec2 a(view_model(ViewKind::halfplane).world_position(h2, A)),
      b(view_model(ViewKind::halfplane).world_position(h2, B));
  EXPECT_GT(a.y, 0.0);
  EXPECT_GT(b.y, 0.0);
  const double d = testing::geodesic_distance(h2, A, B);
  EXPECT_NEAR(std::cosh(d / h2.radius), 1.0 + glm::dot(a - b, a - b) / (2.0 * a.y * b.y), 1e-9);
}

TEST(HalfPlaneView, TheWindowScalesWithItsCentresHeightSoThePictureIsTheSameAtAnyHeight) {
  ViewOptions view;
  view.kind = ViewKind::halfplane;
  for (const double y : {0.01, 1.0, 300.0}) {
    view.target = std::array<double, 3>{2.0, y, 0.0};
    FrameScene scene;
    scene.view_projection = view_model(ViewKind::halfplane).camera(view);
    EXPECT_NEAR(pixel_position(scene, view, {2.0, y, 0.0})->y, 240.0, 1e-3) << y;
    EXPECT_NEAR(pixel_position(scene, view, {2.0, 0.0, 0.0})->y, 240.0 * (1.0 + 1.0 / 1.08), 1e-3) << y;
  }
}

TEST(HalfPlaneView, AimingCentresALoneBodyAtItsOwnHeight) {
  for (const double r : {0.0, 2.0, 6.0}) {
    const Snapshot s = testing::body_at(SurfaceKind::pseudosphere, 1.0, r, 0.3);
    ViewOptions view;
    view.kind = ViewKind::halfplane;
    aim_camera_at_body(view, s);
    ASSERT_TRUE(view.target);
    const glm::dvec2 body(view_model(ViewKind::halfplane).world_position(s.surface, s.bodies[0].X));
    EXPECT_DOUBLE_EQ((*view.target)[1], body.y) << r;  // the main body's height, never lower
    EXPECT_NEAR((*view.target)[0], body.x, 0.3 * body.y) << r;
  }
}

}  // namespace
}  // namespace spinfold::render
