// Drawing through a view (render/views/drawing.cpp): lifting, polylines, dashes, frames, bodies.
#include "render/views/drawing.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/view_table.h"
#include "view_test_support.h"

namespace spinfold::render {
namespace {

TEST(Drawing, OverlaysAreLiftedAlongTheNormalOnlyWhereTheViewLiftsThem) {
  const glm::dvec3 w(0.3, 0.1, 0.2);
  const Surface sphere(SurfaceKind::sphere, 1.0), h2(SurfaceKind::pseudosphere, 1.0);
  EXPECT_EQ(lifted(view_model(ViewKind::sphere), sphere, w), w);
  EXPECT_EQ(lifted(view_model(ViewKind::disk), sphere, w), w);
  const ViewModel& bowl = view_model(ViewKind::hyperboloid);
  const glm::dvec3 up = lifted(bowl, h2, w) - w;
  EXPECT_NEAR(glm::length(up), bowl.lift(), 1e-15);
  EXPECT_NEAR(glm::dot(glm::normalize(up), bowl.normal(h2, w)), 1.0, 1e-12);
}

TEST(Drawing, APolylineIsOneSegmentPerPairAndClosingAddsOne) {
  const Surface flat{SurfaceKind::plane, 1.0};
  const std::vector<Vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  std::vector<Vertex> open, closed;
  add_polyline(open, flat, view_model(ViewKind::plane), square, kGridColor, false);
  add_polyline(closed, flat, view_model(ViewKind::plane), square, kGridColor, true);
  EXPECT_EQ(open.size(), 2u * 3u);
  ASSERT_EQ(closed.size(), 2u * 4u);
  EXPECT_EQ(closed.back().position, glm::vec3(0, 0, 0));
  // With a clip window, a segment with an end far from it (beyond 3 half-widths) is left out.
  Window2d clip;
  clip.hx = clip.hy = 0.2;
  std::vector<Vertex> clipped;
  add_polyline(clipped, flat, view_model(ViewKind::plane), {{0, 0, 0}, {0.5, 0, 0}, {5, 0, 0}}, kGridColor,
               false, &clip);
  ASSERT_EQ(clipped.size(), 2u);
  EXPECT_EQ(clipped.back().position, glm::vec3(0.5f, 0, 0));
}

TEST(Drawing, SegmentsWithAnEndOffTheViewAreLeftOut) {
  const Surface h2{SurfaceKind::pseudosphere, 1.0};
  const ViewModel& tractricoid = view_model(ViewKind::tractricoid);
  std::vector<Vec3> line;  // along the geodesic from the pole towards the rim (y = e^{−r}), past it and back
  for (int i = 0; i <= 20; ++i)
    line.push_back(chart_point(h2, 3.0 * std::sin(0.157 * i), std::numbers::pi).X);
  std::size_t off = 0;
  for (const Vec3& X : line) off += !tractricoid.on_view(h2, X);
  ASSERT_GT(off, 0u);
  std::vector<Vertex> drawn;
  add_polyline(drawn, h2, tractricoid, line, kGridColor, false);
  EXPECT_LT(drawn.size(), 2u * 20u);
  for (const Vertex& v : drawn) EXPECT_TRUE(std::isfinite(v.position.z));
}

TEST(Drawing, DashesCoverThreeFifthsOfThePathWhateverItsSampling) {
  const Surface flat{SurfaceKind::plane, 1.0};
  for (const int n : {2, 7, 300}) {
    std::vector<Vec3> path;
    for (int i = 0; i < n; ++i) path.push_back(Vec3(3.0 * i / (n - 1), 0.0, 0.0));
    std::vector<Vertex> dashes;
    add_dashed_polyline(dashes, flat, view_model(ViewKind::plane), path, kGridColor);
    double on = 0.0;
    for (std::size_t i = 0; i + 1 < dashes.size(); i += 2)
      on += glm::length(dashes[i + 1].position - dashes[i].position);
    EXPECT_NEAR(on, 3.0 * 0.045 / 0.075, 0.045) << n;  // kDash on, kGap off
  }
}

TEST(Drawing, TheFramesExponentialStartsAtTheBodyAndGoesTheFramesLength) {
  const Snapshot s = testing::body_at(SurfaceKind::sphere, 2.0, 0.7, 0.2, 1.5, 0.5);
  const BodySnapshot& b = s.bodies[0];
  EXPECT_NEAR((exp_frame(s.surface, b, 0.0, 0.0) - b.X).norm(), 0.0, 1e-15);
  // exp of a e₁ lies at the distance a·|e₁| = 1.5a from X along the surface.
  EXPECT_NEAR(testing::geodesic_distance(s.surface, b.X, exp_frame(s.surface, b, 0.4, 0.0)), 0.6, 1e-12);
  EXPECT_NEAR(testing::geodesic_distance(s.surface, b.X, exp_frame(s.surface, b, 0.0, 0.4)), 0.2, 1e-12);
}

TEST(Drawing, ABodyIsAFilledEllipseWithItsOutlineAndTwoArrowsWithBarbs) {
  const Snapshot s = testing::body_at(SurfaceKind::sphere, 1.0, 0.5, 0.0);
  const ViewModel& sphere = view_model(ViewKind::sphere);
  FrameScene scene;
  add_body(scene, s.surface, sphere, 0.25, s.bodies[0]);
  EXPECT_EQ(scene.fills.size(), 3u * (64u + 2u * 7u * 64u));  // a fan ring, then 7 rings of quads
  EXPECT_EQ(scene.lines.size(), 2u * 64u);                    // the closed outline
  EXPECT_EQ(scene.lines.front().color, outline_color(s.bodies[0]));
  scene.lines.clear();
  add_frame_arrows(scene, s.surface, sphere, 0.25, s.bodies[0]);
  EXPECT_EQ(scene.lines.size(), 2u * 2u * (16u + 2u));  // two shafts of 16 segments, two barbs each
  EXPECT_EQ(scene.lines.front().color, kArrowColors[0]);
  EXPECT_EQ(scene.lines.back().color, kArrowColors[1]);
}

}  // namespace
}  // namespace spinfold::render

namespace spinfold::render {
namespace {

// Where a companion starts on the main body (a geodesic companion, simple mode's), the main body is
// drawn last, over it, in every view: its fill is the frame's last, in its own colour.
TEST(Drawing, TheMainBodyIsDrawnOverACompanionAtItsPlace) {
  for (const ViewRow& row : view_table()) {
    for (const SurfaceKind kind : {SurfaceKind::sphere, SurfaceKind::pseudosphere, SurfaceKind::plane}) {
      if (!shows(row.info, kind)) continue;
      Snapshot s = testing::body_at(kind, 1.0, 0.5, 0.3);
      s.bodies.push_back(s.bodies.front());
      s.bodies.back().color = {0.0f, 0.42f, 0.75f};
      ViewOptions view;
      view.kind = row.info.kind;
      view.layers = kSurface | kBody;
      FrameScene scene;
      row.model().add_bodies(scene, s, view);
      ASSERT_FALSE(scene.fills.empty()) << row.info.name;
      EXPECT_FLOAT_EQ(scene.fills.back().color.r, kMainBodyColor[0]) << row.info.name;
      EXPECT_FLOAT_EQ(scene.fills.front().color.r, 0.0f) << row.info.name;
    }
  }
}

}  // namespace
}  // namespace spinfold::render
