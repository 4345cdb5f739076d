// The chart view (render/views/chart.cpp): φ across and u down fill [−1, 1]², the background's
// colour has K's sign band by band and shows it without the curvature layer, the seam tears the
// path instead of drawing a line across the map, and a body anywhere is in the frame.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/revolution.h"
#include "render/view_table.h"
#include "render/views/drawing.h"
#include "render/views/view_model.h"
#include "view_test_support.h"

namespace spinfold::render {
namespace {

using testing::body_on;
using testing::in_frame;
using testing::pixel_of;

const ViewModel& chart() {
  return view_model(ViewKind::chart);
}

TEST(ChartView, PhiRunsAcrossAndUDownTheDrawnRange) {
  Surface torus;
  torus.kind = SurfaceKind::torus;
  const RevolutionSurface s = revolution_surface(torus);
  const auto at = [&](double u, double phi) {
    return chart().world_position(torus, revolution_frame(s, u, phi).X);
  };
  EXPECT_NEAR(at(0.0, 0.0).x, 0.0, 1e-12);
  EXPECT_NEAR(at(0.0, 0.0).y, 0.0, 1e-12);           // u = 0: the middle of −π … π
  EXPECT_NEAR(at(-kPi / 2, kPi / 2).x, 0.5, 1e-12);  // φ = π/2
  EXPECT_NEAR(at(-kPi / 2, kPi / 2).y, 0.5, 1e-12);  // u = −π/2 (the top circle) above the middle
  EXPECT_NEAR(at(3.0, -3.0).x, -3.0 / kPi, 1e-12);
}

TEST(ChartView, TheBackgroundIsKBandByBandWithOrWithoutTheCurvatureLayer) {
  Surface bump;
  bump.kind = SurfaceKind::bump;
  const auto g = static_geometry(bump, ViewKind::chart);
  ASSERT_FALSE(g->surface.empty());
  const RevolutionSurface s = revolution_surface(bump);
  const ProfilePicture p = bump_entry.picture(s);
  for (const LitVertex& v : g->surface) {
    const double u = p.u_min + (1.0 - v.position.y) / 2.0 * (p.u_max - p.u_min);
    const double K = bump_entry.profile(s, u).K;
    if (K > 0.05) {
      EXPECT_GT(v.tint.r, v.tint.b) << u;
    }
    if (K < -0.05) {
      EXPECT_GT(v.tint.b, v.tint.r) << u;
    }
  }
  ViewOptions view;
  view.kind = ViewKind::chart;
  view.layers = kSurface | kBody;  // no curvature layer
  EXPECT_TRUE(build_scene(body_on(SurfaceKind::bump, 0.5, 0.0), view).tint_by_curvature);
}

TEST(ChartView, ThePathIsTornAtTheSeamNotDrawnAcrossTheMap) {
  Surface torus;
  torus.kind = SurfaceKind::torus;
  const RevolutionSurface s = revolution_surface(torus);
  const std::vector<Vec3> across{revolution_frame(s, 0.2, kPi - 0.01).X,
                                 revolution_frame(s, 0.2, -kPi + 0.01).X};
  std::vector<Vertex> lines;
  add_polyline(lines, torus, chart(), across, kGridColor, false);
  EXPECT_TRUE(lines.empty());
  const std::vector<Vec3> along{revolution_frame(s, 0.2, 0.3).X, revolution_frame(s, 0.25, 0.35).X};
  add_polyline(lines, torus, chart(), along, kGridColor, false);
  EXPECT_EQ(lines.size(), 2u);
}

TEST(ChartView, ABodyAnywhereIsInTheFrame) {
  for (const SurfaceKind kind :
       {SurfaceKind::torus, SurfaceKind::spheroid, SurfaceKind::bump, SurfaceKind::catenoid})
    for (const double u : {0.0, 0.5, 1.2})
      for (const double phi : {-3.1, 0.0, 3.1}) {
        const Snapshot s = body_on(kind, u, phi);
        ViewOptions view;
        view.kind = ViewKind::chart;
        aim_camera_at_body(view, s);
        EXPECT_TRUE(in_frame(pixel_of(build_scene(s, view), view, s.surface, s.bodies[0].X), view))
            << int(kind) << " " << u << " " << phi;
      }
}

}  // namespace
}  // namespace spinfold::render
