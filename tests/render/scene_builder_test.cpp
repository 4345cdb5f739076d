// build_scene without GL: the geometry of the drawing.
#include "render/scene_builder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <tuple>

#include "engine/chart.h"

namespace spinfold::render {
namespace {

// A body at chart point (r, φ) with L = diag(λ, μ) in the paper's frame.
Snapshot body_at(SurfaceKind kind, double R, double r, double phi, double lambda, double mu) {
  Snapshot s;
  s.surface = {kind, R};
  const ChartPoint p = chart_point(s.surface, r, phi);
  BodySnapshot& b = s.bodies.emplace_back();
  b.X = p.X;
  b.e[0] = lambda * p.E1;
  b.e[1] = mu * p.E2;
  b.gram << lambda * lambda, 0.0, 0.0, mu * mu;
  return s;
}

double geodesic_distance(const Surface& surface, const Vec3& a, const Vec3& b) {
  const double R = surface.radius, c = dot(surface, a, b) / (R * R);
  return surface.kind == SurfaceKind::sphere ? R * std::acos(std::clamp(c, -1.0, 1.0))
                                             : R * std::acosh(std::max(1.0, -c));
}

TEST(SceneBuilder, EllipseLiesOnTheSurfaceCentredOnTheBodyWithTheAxesOfL) {
  for (SurfaceKind kind : {SurfaceKind::sphere, SurfaceKind::pseudosphere}) {
    const Snapshot s = body_at(kind, 2.0, 1.3, 0.4, 1.5, 0.5);
    const double scale = 0.2;
    const Vec3& X = s.bodies[0].X;
    const std::vector<Vec3> points = ellipse_points(s.surface, s.bodies[0], scale, 64);
    for (const Vec3& P : points) EXPECT_NEAR(curvature(s.surface) * dot(s.surface, P, P), 1.0, 1e-12);
    // Opposite points are geodesically symmetric about the body: equal distances, and their sum
    // is parallel to X.
    for (int i = 0; i < 32; ++i) {
      const Vec3 sum = points[i] + points[i + 32];
      EXPECT_LT(sum.cross(X).norm(), 1e-12 * sum.norm() * X.norm());
      EXPECT_NEAR(geodesic_distance(s.surface, X, points[i]), geodesic_distance(s.surface, X, points[i + 32]),
                  1e-12);
    }
    // Semi-axes: scale·λ along e₁ (θ = 0), scale·μ along e₂ (θ = π/2).
    EXPECT_NEAR(geodesic_distance(s.surface, X, points[0]), scale * 1.5, 1e-12);
    EXPECT_NEAR(geodesic_distance(s.surface, X, points[16]), scale * 0.5, 1e-12);
  }
}

TEST(SceneBuilder, UnselectedLayersCostNothing) {
  const Snapshot s = body_at(SurfaceKind::sphere, 1.0, 1.0, 0.0, 1.0, 1.0);
  ViewOptions view;
  view.layers = 0;
  const FrameScene none = build_scene(s, view);
  EXPECT_EQ(none.statics, nullptr);
  EXPECT_TRUE(none.fills.empty());
  EXPECT_TRUE(none.lines.empty());
  EXPECT_TRUE(none.hud_lines.empty());
  view.layers = kBody;
  EXPECT_FALSE(build_scene(s, view).fills.empty());
  EXPECT_TRUE(build_scene(s, view).hud_lines.empty());
}

TEST(SceneBuilder, StaticGeometryIsBuiltOncePerSurfaceAndView) {
  const StaticGeometry& a = static_geometry(SurfaceKind::sphere, ViewKind::sphere);
  const StaticGeometry& b = static_geometry(SurfaceKind::sphere, ViewKind::sphere);
  EXPECT_EQ(&a, &b);
  EXPECT_FALSE(a.surface.empty());
  EXPECT_FALSE(a.grid.empty());
  EXPECT_NE(&a, &static_geometry(SurfaceKind::sphere, ViewKind::disk));
}

TEST(SceneBuilder, FarOutOnH2TheDiskViewDrawsNearTheRimWithoutOverflow) {
  const Snapshot s = body_at(SurfaceKind::pseudosphere, 1.0, 50.0, 0.3, 1.0, 1.0);
  ViewOptions view;
  view.kind = ViewKind::disk;
  const glm::dvec3 w = world_position(s.surface, view.kind, s.bodies[0].X);
  EXPECT_TRUE(std::isfinite(w.x) && std::isfinite(w.y));
  EXPECT_LE(glm::length(w), 1.0);  // 1 − |p| = 2e^{−50}: the rim, to double precision
  EXPECT_GT(glm::length(w), 1.0 - 1e-9);
  EXPECT_NEAR(std::atan2(w.y, w.x), 0.3, 1e-12);
  const FrameScene scene = build_scene(s, view);
  ASSERT_FALSE(scene.fills.empty());
  for (const auto* list : {&scene.fills, &scene.lines})
    for (const Vertex& v : *list) EXPECT_TRUE(std::isfinite(v.position.x) && std::isfinite(v.position.y));
}

TEST(SceneBuilder, EachBodyIsDrawnAndALegendListsThemOnlyWhenThereAreSeveral) {
  Snapshot s = body_at(SurfaceKind::sphere, 1.0, 1.0, 0.0, 1.0, 1.0);
  ViewOptions view;
  view.layers = kBody | kTrail;
  const FrameScene one = build_scene(s, view);
  EXPECT_TRUE(one.legend.empty());
  BodySnapshot companion = body_at(SurfaceKind::sphere, 1.0, 1.2, 0.5, 1.0, 1.0).bodies[0];
  companion.color = companion.trail_color = kCompanionPalette[0];
  companion.label = "geodesic";
  s.bodies.push_back(companion);
  const FrameScene two = build_scene(s, view);
  EXPECT_EQ(two.fills.size(), 2 * one.fills.size());
  ASSERT_EQ(two.legend.size(), 2u);
  EXPECT_EQ(two.legend[1].label, "geodesic");
  EXPECT_EQ(two.legend[1].color, glm::vec4(0.00f, 0.42f, 0.75f, 1.0f));
  view.layers = kGrid;  // nothing of the bodies drawn: nothing to tell apart
  EXPECT_TRUE(build_scene(s, view).legend.empty());
  view.layers = kBody | kTrail;
  view.width = kLegendMinWidth - 1;  // a thumbnail: the legend would cover the picture
  EXPECT_TRUE(build_scene(s, view).legend.empty());
}

// The total length of the segments of `color` [world units].
double drawn_length(const FrameScene& scene, const glm::vec4& color) {
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < scene.lines.size(); i += 2)
    if (scene.lines[i].color == color)
      length += glm::length(glm::dvec3(scene.lines[i + 1].position - scene.lines[i].position));
  return length;
}

TEST(SceneBuilder, TheGeodesicCompanionsTrailIsDashed) {
  Snapshot s;
  s.surface = {SurfaceKind::sphere, 1.0};
  for (bool geodesic : {false, true}) {
    BodySnapshot& b = s.bodies.emplace_back(body_at(SurfaceKind::sphere, 1.0, 1.0, 1.0, 1.0, 1.0).bodies[0]);
    for (int k = 0; k <= 100; ++k) b.trail.push_back(chart_point(s.surface, 1.0, 0.01 * k).X);
    b.color = b.trail_color = kCompanionPalette[geodesic ? 1 : 0];
    b.geodesic = geodesic;
  }
  ViewOptions view;
  view.layers = kTrail;
  const FrameScene scene = build_scene(s, view);
  const double solid = drawn_length(scene, glm::vec4(0.00f, 0.42f, 0.75f, 1.0f));
  const double dashed = drawn_length(scene, glm::vec4(0.80f, 0.10f, 0.55f, 1.0f));
  EXPECT_NEAR(solid, std::sin(1.0), 0.01);                    // the parallel at r = 1 over φ ∈ [0, 1]
  EXPECT_NEAR(dashed / solid, 0.045 / (0.045 + 0.03), 0.05);  // dash / (dash + gap)
}

TEST(SceneBuilder, ViewsMatchSurfaces) {
  EXPECT_FALSE(view_unsupported_reason(ViewKind::sphere, SurfaceKind::sphere));
  EXPECT_FALSE(view_unsupported_reason(ViewKind::disk, SurfaceKind::pseudosphere));
  EXPECT_TRUE(view_unsupported_reason(ViewKind::hyperboloid, SurfaceKind::sphere));
  EXPECT_TRUE(view_unsupported_reason(ViewKind::sphere, SurfaceKind::plane));
  std::string unknown;
  EXPECT_EQ(parse_layers("body,trail", &unknown), kBody | kTrail);
  EXPECT_FALSE(parse_layers("body,sparkles", &unknown));
  EXPECT_EQ(unknown, "sparkles");
}

TEST(SceneBuilder, TheSilhouetteIsTheSpheresLimbAndTheDisksRim) {
  const Snapshot s = body_at(SurfaceKind::sphere, 1.0, 1.0, 0.0, 1.0, 1.0);
  ViewOptions view;  // camera at distance 3.4 from the centre
  const FrameScene scene = build_scene(s, view);
  const std::vector<Vertex> limb = silhouette(*scene.statics, scene);
  ASSERT_GT(limb.size(), 100u);
  // Seen from distance d, the limb is the circle where the sight line is tangent: x·ê = 1/d.
  const glm::dvec3 eye_dir(std::cos(view.pitch) * std::cos(view.yaw),
                           std::cos(view.pitch) * std::sin(view.yaw), std::sin(view.pitch));
  for (const Vertex& v : limb)
    EXPECT_NEAR(glm::dot(glm::normalize(glm::dvec3(v.position)), eye_dir), 1.0 / view.distance,
                0.1);  // within a face (~0.1 rad) of it
  // The 2-D views: only the mesh's boundary (the Poincaré disk's rim, 128 segments).
  const Snapshot h = body_at(SurfaceKind::pseudosphere, 1.0, 1.0, 0.0, 1.0, 1.0);
  view.kind = ViewKind::disk;
  const FrameScene disk = build_scene(h, view);
  const std::vector<Vertex> rim = silhouette(*disk.statics, disk);
  EXPECT_EQ(rim.size(), 2u * 128u);
  for (const Vertex& v : rim) EXPECT_NEAR(glm::length(v.position), 1.0f, 1e-6f);
}

// The HUD of a run (as make_snapshot writes it): six lines, the longest 37 characters.
std::vector<std::string> hud_of_a_run() {
  return {"t = 12.000",          "energy error = 1.23e-12", "integrator: exact",
          "pseudosphere  R = 1", "m = 1  J = 0.5  rigid",   "spin = 1.0000  det L = 1.0000 (x)"};
}

TEST(SceneBuilder, HudTextGrowsWithTheFrameAndKeepsItsSizeInSmallOnes) {
  const std::vector<std::string> lines = hud_of_a_run();
  const HudLayout small = hud_layout(lines, {}, 640, 480), thumb = hud_layout(lines, {}, 160, 120);
  const HudLayout hd = hud_layout(lines, {}, 1280, 720), full = hud_layout(lines, {}, 1920, 1080);
  EXPECT_EQ(small.font_size, 13.0);  // unchanged at 480 px high
  EXPECT_EQ(thumb.font_size, 13.0);
  EXPECT_EQ(hd.font_size, 19.5);
  EXPECT_EQ(full.font_size, 26.0);                              // 2× at 1080
  EXPECT_EQ(hud_layout(lines, {}, 1920, 600).font_size, 13.0);  // the shorter side counts
  EXPECT_NEAR(full.hud.h / small.hud.h, 2.0, 1e-9);
  EXPECT_NEAR(full.hud.w / small.hud.w, 2.0, 1e-9);
  // Compact: the box of six lines keeps to the same share of the frame at every size.
  for (const auto& [l, w, h] : {std::tuple{small, 640, 480}, {hd, 1280, 720}, {full, 1920, 1080}}) {
    EXPECT_LT(l.hud.h, 0.22 * h);
    EXPECT_LT(l.hud.w, 0.4 * w);
  }
  const HudLayout with_legend = hud_layout(lines, {"body 1", "geodesic (s = 0)"}, 1920, 1080);
  EXPECT_NEAR(with_legend.legend.x + with_legend.legend.w, 1920 - 12.0, 1e-9);  // top-right corner
  EXPECT_FALSE(hud_layout({}, {}, 640, 480).hud.w > 0.0);
}

// A body r out from the vertex along φ with its trail from the vertex, the HUD of a run on.
Snapshot out_on_h2(double r) {
  Snapshot s = body_at(SurfaceKind::pseudosphere, 1.0, r, 0.8, 1.0, 1.0);
  for (int k = 0; k <= 64; ++k) s.bodies[0].trail.push_back(chart_point(s.surface, r * k / 64, 0.8).X);
  s.hud_lines = hud_of_a_run();
  return s;
}

TEST(SceneBuilder, TheHyperboloidsCameraKeepsTheBodyInTheFrameAndOutOfTheHudFarOut) {
  for (const double r : {0.0, 1.0, 3.0, 6.0})
    for (const auto& [w, h] : {std::pair{640, 480}, {960, 600}, {1920, 1080}}) {
      const Snapshot s = out_on_h2(r);
      ViewOptions view;
      view.kind = ViewKind::hyperboloid;
      view.width = w;
      view.height = h;
      aim_camera_at_body(view, s);
      const FrameScene scene = build_scene(s, view);
      const auto at = [&](const Vec3& X) {
        return pixel_position(scene, view, world_position(s.surface, view.kind, X));
      };
      const std::optional<glm::dvec2> body = at(s.bodies[0].X);
      ASSERT_TRUE(body) << "r = " << r;
      EXPECT_GT(body->x, 0.05 * w) << "r = " << r << ", " << w << "x" << h;
      EXPECT_LT(body->x, 0.95 * w) << "r = " << r << ", " << w << "x" << h;
      EXPECT_GT(body->y, 0.05 * h) << "r = " << r << ", " << w << "x" << h;
      EXPECT_LT(body->y, 0.95 * h) << "r = " << r << ", " << w << "x" << h;
      EXPECT_FALSE(scene.hud.hud.contains(*body)) << "r = " << r << ", " << w << "x" << h;
      // The whole ellipse and the trail's last stretch (up to 3 radii back) are in the frame.
      std::vector<Vec3> points = ellipse_points(s.surface, s.bodies[0], view.scale, 16);
      for (int k = 0; k <= 64; ++k)
        if (r * (64 - k) / 64 <= 3.0) points.push_back(s.bodies[0].trail[k]);
      for (const Vec3& P : points) {
        const std::optional<glm::dvec2> p = at(P);
        ASSERT_TRUE(p);
        EXPECT_TRUE(p->x >= 0 && p->x <= w && p->y >= 0 && p->y <= h) << "r = " << r << ", " << w << "x" << h;
      }
    }
}

TEST(SceneBuilder, ThePlanesGridIsCentredOnTheBodyFillsTheFrameAndStaysPutInTheWorld) {
  Snapshot s = body_at(SurfaceKind::plane, 1.0, 5.3, -2.2, 1.0, 1.0);
  s.hud_lines = hud_of_a_run();
  for (const auto& [w, h] : {std::pair{640, 480}, {1366, 600}, {400, 700}}) {
    ViewOptions view;
    view.kind = ViewKind::plane;
    view.width = w;
    view.height = h;
    aim_camera_at_body(view, s);
    const FrameScene scene = build_scene(s, view);
    const glm::dvec3 world = world_position(s.surface, view.kind, s.bodies[0].X);
    const std::optional<glm::dvec2> body = pixel_position(scene, view, world);
    ASSERT_TRUE(body);
    EXPECT_NEAR(body->x, 0.5 * w, 1e-3);
    EXPECT_NEAR(body->y, 0.5 * h, 1e-3);
    ASSERT_FALSE(scene.grid_lines.empty());
    EXPECT_EQ(scene.clear_color, scene.surface_color);  // the plane fills the frame
    glm::dvec2 lo(1e300), hi(-1e300);
    for (std::size_t i = 0; i + 1 < scene.grid_lines.size(); i += 2) {
      const glm::dvec3 a(scene.grid_lines[i].position), b(scene.grid_lines[i + 1].position);
      const bool vertical = a.x == b.x;
      const double c = vertical ? a.x : a.y;  // a whole multiple of the spacing, wherever the body is
      EXPECT_NEAR(c / kPlaneGridSpacing, std::round(c / kPlaneGridSpacing), 1e-5);
      for (const glm::dvec3& p : {a, b}) {
        const glm::dvec2 px = *pixel_position(scene, view, p);
        lo = glm::min(lo, px), hi = glm::max(hi, px);
      }
    }
    EXPECT_LE(lo.x, 0.0);
    EXPECT_LE(lo.y, 0.0);
    EXPECT_GE(hi.x, w);
    EXPECT_GE(hi.y, h);
  }
}

}  // namespace
}  // namespace spinfold::render
