// The disk view (render/views/disk.cpp): stereographic (S²) and Poincaré (H²) projection, the disk.
#include <gtest/gtest.h>

#include <cmath>

#include "render/view_table.h"
#include "render/views/view_model.h"
#include "view_test_support.h"

namespace spinfold::render {
namespace {

const ViewModel& disk() {
  return view_model(ViewKind::disk);
}

TEST(DiskView, TheSphereMapsStereographicallyAndH2ToThePoincareDisk) {
  const Surface sphere{SurfaceKind::sphere, 2.0}, h2{SurfaceKind::pseudosphere, 2.0};
  for (const double r : {0.1, 0.9, 2.5}) {  // [radii]
    const glm::dvec3 s = disk().world_position(sphere, chart_point(sphere, r * 2.0, 0.6).X);
    const glm::dvec3 h = disk().world_position(h2, chart_point(h2, r * 2.0, 0.6).X);
    EXPECT_NEAR(glm::length(s), std::tan(r / 2), 1e-12) << r;   // |w| = tan(θ/2)
    EXPECT_NEAR(glm::length(h), std::tanh(r / 2), 1e-12) << r;  // |w| = tanh(r/2)
    EXPECT_EQ(s.z, 0.0);
    // Conformal and centred: the direction φ about the pole is kept (up to the chart's orientation).
    EXPECT_NEAR(std::remainder(std::atan2(s.y, s.x) - std::atan2(h.y, h.x), 2 * std::numbers::pi), 0.0,
                1e-12);
  }
}

TEST(DiskView, FarOutOnH2PointsStayInsideTheUnitDisk) {
  const Surface h2{SurfaceKind::pseudosphere, 1.0};
  const glm::dvec3 w = disk().world_position(h2, chart_point(h2, 300.0, 1.0).X);
  EXPECT_TRUE(std::isfinite(w.x) && std::isfinite(w.y));
  EXPECT_LE(glm::length(w), 1.0);
}

TEST(DiskView, TheDiskIsTheUnitDiskForH2AndReachesPastTheEquatorForTheSphere) {
  const auto reach = [](SurfaceKind kind) {
    double r = 0.0;
    for (const LitVertex& v : static_geometry(kind, ViewKind::disk).surface)
      r = std::max(r, double(glm::length(v.position)));
    return r;
  };
  EXPECT_NEAR(reach(SurfaceKind::pseudosphere), 1.0, 1e-6);
  EXPECT_NEAR(reach(SurfaceKind::sphere), 3.0, 1e-6);  // tan(θ/2) = 3: θ ≈ 143°
  EXPECT_FALSE(static_geometry(SurfaceKind::pseudosphere, ViewKind::disk).grid.empty());
  EXPECT_FALSE(static_geometry(SurfaceKind::sphere, ViewKind::disk).grid.empty());
}

// The disk is centred with a margin, as before aiming learnt to slide it: a body clear of the
// boxes leaves it there; the window follows view.target only when aiming sets one.
TEST(DiskView, AimingLeavesTheWholeDiskCentredWhenTheBodyIsClearOfTheBoxes) {
  Snapshot s = testing::body_at(SurfaceKind::pseudosphere, 1.0, 1.0, -0.6);
  s.hud_lines = {"t = 1.000", "energy error = 0.00e+00"};
  ViewOptions view;
  view.kind = ViewKind::disk;
  aim_camera_at_body(view, s);
  EXPECT_EQ(view.zoom, 1.0);
  FrameScene scene;
  scene.view_projection = disk().camera(view);
  const std::optional<glm::dvec2> centre = pixel_position(scene, view, glm::dvec3(0.0));
  ASSERT_TRUE(centre);
  EXPECT_NEAR(centre->x, 320.0, 1e-3);
  EXPECT_NEAR(centre->y, 240.0, 1e-3);
  // The rim's top 1/1.08 of the way from the centre to the frame's top edge.
  EXPECT_NEAR(pixel_position(scene, view, glm::dvec3(0, 1, 0))->y, 240.0 * (1 - 1 / 1.08), 1e-3);
  // A target set by aiming moves the window.
  view.target = std::array<double, 3>{0.5, 0.0, 0.0};
  scene.view_projection = disk().camera(view);
  EXPECT_NEAR(pixel_position(scene, view, glm::dvec3(0.5, 0.0, 0.0))->x, 320.0, 1e-3);
}

}  // namespace
}  // namespace spinfold::render
