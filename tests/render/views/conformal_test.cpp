// The conformal view (render/views/conformal.cpp): T_K and its inverse, per-frame background, clipping.
#include <gtest/gtest.h>

#include <cmath>

#include "render/view_table.h"
#include "render/views/drawing.h"
#include "render/views/view_model.h"
#include "view_test_support.h"

namespace spinfold::render {
namespace {

const ViewModel& conformal() {
  return view_model(ViewKind::conformal);
}

TEST(ConformalViewModel, TheDistanceInvertsTheRadiusForEveryCurvature) {
  for (const double K : {4.0, 1e-3, 0.0, -1e-3, -0.25})
    for (const double r : {0.0, 0.1, 1.0, 3.0}) {
      if (K > 0.0 && r >= std::numbers::pi / std::sqrt(K)) continue;  // the antipode and beyond
      EXPECT_NEAR(conformal_distance(K, conformal_radius(K, r)), r, 1e-12 * (1.0 + r)) << K << " " << r;
    }
  // T_K(r) = r(1 + Kr²/12 + O(K²r⁴)): continuous through K = 0.
  EXPECT_NEAR(conformal_radius(1e-6, 2.0), 2.0 * (1.0 + 1e-6 * 4.0 / 12.0), 1e-12);
  EXPECT_NEAR(conformal_radius(-1e-6, 2.0), 2.0 * (1.0 - 1e-6 * 4.0 / 12.0), 1e-12);
  // H²'s boundary |w| = 2R is infinitely far.
  EXPECT_EQ(conformal_distance(-0.25, 4.0), std::numeric_limits<double>::infinity());
}

TEST(ConformalViewModel, ItsBackgroundIsDrawnPerFrameAndTrailsAreClippedToTheWindow) {
  EXPECT_FALSE(conformal().uses_static());
  ViewOptions view;
  view.kind = ViewKind::conformal;
  view.target = std::array<double, 3>{7.0, -2.0, 0.0};
  const std::optional<Window2d> clip = conformal().clip(view);
  ASSERT_TRUE(clip);
  EXPECT_EQ(clip->centre, glm::dvec2(7.0, -2.0));
  EXPECT_DOUBLE_EQ(clip->hy, kPlaneHalfHeight);
  for (const ViewRow& row : view_table()) {
    if (row.info.kind == ViewKind::conformal) continue;
    EXPECT_FALSE(row.model().clip(view)) << row.info.name;
  }
}

TEST(ConformalViewModel, TheScaleIsInLengthsSoTheBodyLooksTheSameOnAnySphere) {
  for (const double R : {1.0, 1e6}) {
    const Surface sphere{SurfaceKind::sphere, R};
    EXPECT_EQ(conformal().body_scale_length(sphere), 1.0);
    // A point at distance d from the pole lands at about d whatever R.
    const glm::dvec3 w = conformal().world_position(sphere, chart_point(sphere, 0.5, 0.0).X);
    EXPECT_NEAR(glm::length(w), 0.5, R > 10.0 ? 1e-4 : 0.05);
  }
}

TEST(ConformalViewModel, OnH2TheDiskIsABackdropWhereTheFrameReachesPastItsBoundary) {
  const Snapshot s = testing::body_at(SurfaceKind::pseudosphere, 1.0, 0.0, 0.0);
  ViewOptions view;
  view.kind = ViewKind::conformal;
  view.layers = kSurface;
  const FrameScene centred = build_scene(s, view);  // the window (±4 by ±3) holds the disk |w| < 2
  EXPECT_FALSE(centred.backdrop.empty());
  EXPECT_NE(centred.clear_color, centred.surface_color);
  view.target = std::array<double, 3>{40.0, 0.0, 0.0};  // far beyond the rim: nothing of the disk
  EXPECT_TRUE(build_scene(s, view).backdrop.empty());
}

// Near the rim of a large H² the frame spans thousands of grid spacings (the unbounded-input hunt:
// R = 1e4, a body far out, 96×72): lines closer than pixels are not drawn, the rim still is. Drawing
// them took 11 s (2000 lines of 16384 pieces each), and a frame route timed out.
TEST(ConformalViewModel, AGridFinerThanThePixelsIsNotDrawnButTheRimIs) {
  const double R = 1e4;
  const Snapshot s = testing::body_at(SurfaceKind::pseudosphere, R, 10.0 * R, 0.0);
  ViewOptions view;
  view.kind = ViewKind::conformal;
  view.layers = kGrid;
  view.width = 96, view.height = 72;
  view.target = std::array<double, 3>{2.0 * R - 1.0, 0.0, 0.0};  // the window across the rim |w| = 2R
  const FrameScene rim = build_scene(s, view);
  EXPECT_FALSE(rim.grid_lines.empty());                                   // the ideal boundary
  for (const Vertex& v : rim.grid_lines) EXPECT_EQ(v.color, kSeamColor);  // and no grid line
  // Near the centre the grid is drawn as always.
  view.target = std::array<double, 3>{0.0, 0.0, 0.0};
  const FrameScene centre = build_scene(testing::body_at(SurfaceKind::pseudosphere, 1.0, 0.5, 0.0), view);
  EXPECT_GT(centre.grid_lines.size(), 20u);
}

}  // namespace
}  // namespace spinfold::render
