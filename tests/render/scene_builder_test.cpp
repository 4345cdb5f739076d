// build_scene without GL: the geometry of the drawing.
#include "render/scene_builder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <tuple>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "engine/chart.h"
#include "engine/path_bending.h"
#include "engine/readout.h"
#include "engine/scene_fields.h"
#include "render/views/camera.h"
#include "tests/render/views/view_test_support.h"

namespace spinfold::render {
namespace {

// A body at chart point (r, φ) with L = diag(λ, μ) in the paper's frame.
Snapshot body_at(SurfaceKind kind, double R, double r, double phi, double lambda, double mu) {
  Snapshot s;
  s.surface = {kind, R};
  s.model = surface_model_of(s.surface);
  const ChartPoint p = chart_point(s.surface, r, phi);
  testing::add_body(s, p.X, p.E1, p.E2, lambda, mu);
  return s;
}

double geodesic_distance(const Surface& surface, const Vec3& a, const Vec3& b) {
  const double R = surface.radius, c = dot(surface, a, b) / (R * R);
  return offers(surface, Offer::positive_curvature) ? R * std::acos(std::clamp(c, -1.0, 1.0))
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

// A frame far larger than the surface (issue 35: λ ≈ 26, det L < 0 on the unit sphere painted the
// sphere orange and tore the outline) is drawn smaller, as an ellipse: its semi-axes in proportion,
// the larger one kMaxDrawnExtent·R, and the HUD says at what scale. Ordinary bodies and the plane
// keep the picture's scale.
TEST(SceneBuilder, AFrameTooLargeForTheSurfaceIsDrawnSmallerAsAnEllipseAndTheHudSaysSo) {
  const Snapshot s = body_at(SurfaceKind::sphere, 1.0, 1.3, 0.4, 24.0, -5.0);
  ViewOptions view;
  view.scale = 0.15;
  const double drawn = drawn_scale(s.surface, s.bodies[0], view.scale);
  EXPECT_NEAR(drawn * 24.0, kMaxDrawnExtent, 1e-12);
  const Vec3& X = s.bodies[0].X;
  const std::vector<Vec3> points = ellipse_points(s.surface, s.bodies[0], drawn, 64);
  EXPECT_NEAR(geodesic_distance(s.surface, X, points[0]), kMaxDrawnExtent, 1e-12);
  EXPECT_NEAR(geodesic_distance(s.surface, X, points[16]), kMaxDrawnExtent * 5.0 / 24.0, 1e-12);
  for (const Vec3& P : points) EXPECT_LE(geodesic_distance(s.surface, X, P), kMaxDrawnExtent + 1e-12);
  // Every filled vertex near the body (a chord of at most 2 sin(kMaxDrawnExtent/2), the lift aside).
  const FrameScene scene = build_scene(s, view);
  ASSERT_FALSE(scene.fills.empty());
  const glm::dvec3 at = world_position(s.surface, view.kind, X);
  for (const auto& v : scene.fills) EXPECT_LT(glm::length(glm::dvec3(v.position) - at), 0.52);
  EXPECT_NE(std::find(scene.hud_lines.begin(), scene.hud_lines.end(), "body 1 drawn at 0.14 x its size"),
            scene.hud_lines.end())
      << scene.hud_lines.back();
  // A body of ordinary size, and any body on the plane: the picture's scale, and nothing said.
  const Snapshot ordinary = body_at(SurfaceKind::sphere, 1.0, 1.3, 0.4, 1.5, 0.5);
  EXPECT_EQ(drawn_scale(ordinary.surface, ordinary.bodies[0], view.scale), view.scale);
  EXPECT_TRUE(build_scene(ordinary, view).hud_lines.empty() ||
              build_scene(ordinary, view).hud_lines.back().find("drawn at") == std::string::npos);
  const Snapshot plane = body_at(SurfaceKind::plane, 1.0, 1.3, 0.4, 24.0, -5.0);
  EXPECT_EQ(drawn_scale(plane.surface, plane.bodies[0], view.scale), view.scale);
}

TEST(SceneBuilder, ASnapshotHoldsItsRunsSurfaceModel) {
  Scene scene;
  scene.surface.kind = SurfaceKind::torus;
  const Simulation run = start_simulation(scene);
  const Snapshot s = make_snapshot(run, Trail{}, -1.0);
  EXPECT_EQ(s.model, run.surface);  // one object: the frame asks the run's model, not a second copy
  EXPECT_EQ(&surface_model(s), run.surface.get());
  Snapshot changed = s;  // its surface changed and not its model: refused, not drawn wrongly
  changed.surface.tube_radius = 0.5;
  EXPECT_THROW((void)surface_model(changed), std::logic_error);
  changed.model = nullptr;
  EXPECT_THROW((void)surface_model(changed), std::logic_error);
}

// The torus's claim drawn (issue 50): the main trail orange where it bends left and blue where it
// bends right, which is where K s > 0 and K s < 0 (κ_g = K s/(m v)); the legend says which is which
// and the HUD says it at the body in words; with the layer off the trail is its own colour.
TEST(SceneBuilder, TheBendingLayerColoursTheTorusTrailWhereKsSaysItBends) {
  const Scene scene = *parse_scene_text(find_preset("spin_vs_geodesic_torus")->json).scene;
  Simulation run = start_simulation(scene);
  const double spin = readout(run).spin;
  Trail trail;
  trail.spacing = 0.02;
  ASSERT_TRUE(advance_sampling_trail(run, trail, 12.0));
  const Snapshot s = make_snapshot(run, trail, -1.0);
  ViewOptions view;
  view.kind = ViewKind::revolution;
  ASSERT_TRUE(view.layers & kBending);  // on by default: the lesson is the default picture
  const std::vector<double> bending = main_trail_bending(s, view);
  ASSERT_EQ(bending.size(), s.bodies[0].trail.size());
  const auto nearer_left = [](const glm::vec4& c) {
    return glm::distance(c, kBendsLeftColor) < glm::distance(c, kBendsRightColor);
  };
  int left = 0, right = 0;
  for (std::size_t i = 1; i + 1 < bending.size(); ++i) {
    const double Ks = curvature_at(*s.model, s.bodies[0].trail[i]) * spin;
    if (std::abs(Ks) < 0.1) continue;  // near the K = 0 circles: grey, either way
    const glm::vec4 c = bending_color(bending[i]);
    EXPECT_EQ(nearer_left(c), Ks > 0.0) << "K s = " << Ks << " at point " << i;
    EXPECT_NE(c, kStraightColor);
    (Ks > 0.0 ? left : right)++;
  }
  EXPECT_GT(left, 50);
  EXPECT_GT(right, 50);

  aim_camera_at_body(view, s);
  const FrameScene frame = build_scene(s, view);
  int drawn_left = 0, drawn_right = 0;
  for (std::size_t i = frame.trails_begin; i < frame.trails_end; ++i) {
    const glm::vec4& c = frame.lines[i].color;
    if (glm::distance(c, kBendsLeftColor) < 0.25f) ++drawn_left;
    if (glm::distance(c, kBendsRightColor) < 0.25f) ++drawn_right;
  }
  EXPECT_GT(drawn_left, 20);
  EXPECT_GT(drawn_right, 20);
  // One row keys both colours, left half orange, right half green.
  const auto key = std::find_if(frame.legend.begin(), frame.legend.end(),
                                [](const LegendEntry& e) { return e.label == "path bends left / right"; });
  ASSERT_NE(key, frame.legend.end());
  EXPECT_EQ(key->trail_color, kBendsLeftColor);
  ASSERT_TRUE(key->right_half);
  EXPECT_EQ(*key->right_half, kBendsRightColor);
  // The surface's line gives K at the body and, now, which way the path turns there.
  ASSERT_GT(frame.hud_lines.size(), kSurfaceReadoutLine);
  const std::string& surface_line = frame.hud_lines[kSurfaceReadoutLine];
  EXPECT_EQ(surface_line.rfind("torus  K = ", 0), 0u) << surface_line;
  EXPECT_TRUE(surface_line.ends_with(": the path bends left") ||
              surface_line.ends_with(": the path bends right") ||
              surface_line.ends_with(": the path runs straight"))
      << surface_line;

  view.layers &= ~kBending;
  const FrameScene plain = build_scene(s, view);
  const glm::vec4 own(kMainTrailColor[0], kMainTrailColor[1], kMainTrailColor[2], 1.0f);
  ASSERT_EQ(s.bodies.size(), 2u);
  const auto& g = s.bodies[1].trail_color;
  const glm::vec4 geodesic(g[0], g[1], g[2], 1.0f);
  for (std::size_t i = plain.trails_begin; i < plain.trails_end; ++i) {
    const glm::vec4& c = plain.lines[i].color;  // the main trail's own colour, or the companion's
    EXPECT_TRUE(c == own || c == geodesic) << c.r << " " << c.g << " " << c.b;
  }
  for (const LegendEntry& e : plain.legend) EXPECT_EQ(e.label.find("bends"), std::string::npos);
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
  view.width = kFullOverlayWidth;
  EXPECT_FALSE(build_scene(s, view).legend.empty());
  view.width = kFullOverlayWidth - 1;  // a phone's picture: the legend would cover it
  EXPECT_TRUE(build_scene(s, view).legend.empty());
  view.width = 640, view.height = kFullOverlayHeight - 1;
  EXPECT_TRUE(build_scene(s, view).legend.empty());
}

// A compact overlay (a phone's picture, a thumbnail): the HUD says the time and the notes about the
// picture, not the whole read-out, which at 320×240 covered its top half.
TEST(SceneBuilder, ASmallFrameHasACompactHud) {
  const Snapshot s = testing::preset_snapshot("spin_vs_geodesic_sphere", 2.0, true);
  ViewOptions view;
  view.layers = kDefaultLayers;
  const FrameScene full = build_scene(s, view);
  ASSERT_GT(full.hud_lines.size(), 3u);
  EXPECT_EQ(full.hud_lines, readout_lines(s, view));
  view.width = 320, view.height = 240;
  const FrameScene small = build_scene(s, view);
  ASSERT_EQ(small.hud_lines.size(), 1u);
  EXPECT_EQ(small.hud_lines[0], full.hud_lines[0]);
  EXPECT_EQ(small.hud_lines[0].rfind("t = ", 0), 0u);
  EXPECT_LT(small.hud.hud.h, full.hud.hud.h / 3);
  // A figure's caption says all of it, however small the picture.
  EXPECT_EQ(readout_lines(s, view), full.hud_lines);
}

// No HUD text runs into the legend (the bump's companions' lines ran under it, 640 px wide) nor
// past the frame: over every preset at the full overlay's sizes, each line beside the legend's box
// ends left of it, and every line within the frame.
TEST(SceneBuilder, NoHudLineRunsIntoTheLegendOrPastTheFrame) {
  const auto glyphs = [](const std::string& text) {
    return static_cast<double>(
        std::count_if(text.begin(), text.end(), [](char c) { return (c & 0xC0) != 0x80; }));
  };
  int beside = 0;
  std::vector<std::pair<std::string, Snapshot>> cases;
  for (const PresetSource& preset : preset_sources())
    cases.emplace_back(preset.name, testing::preset_snapshot(preset.name, 20.0, true));
  // A companion with a long label: a wide legend beside the HUD's longest lines.
  Scene wide = *parse_scene_text(find_preset("trapped_spin_bump")->json).scene;
  wide.companions.at(0).label = "s = 2.5, a little below the critical spin of this bump";
  Simulation run;
  cases.emplace_back("long label", snapshot_at(wide, 20.0, true, std::nullopt, run));
  for (const auto& [name, s] : cases) {
    for (const auto& [w, h] : {std::pair{640, 480}, {800, 520}, {1280, 720}}) {
      const FrameScene scene = build_scene(s, testing::aimed_view(default_view(s.surface.kind), w, h, s));
      const HudLayout& l = scene.hud;
      for (std::size_t k = 0; k < scene.hud_lines.size(); ++k) {
        const double top = l.hud.y + l.padding + k * l.line,
                     right = l.hud.x + l.padding + glyphs(scene.hud_lines[k]) * l.advance;
        EXPECT_LE(right, w) << name << " " << w << ": " << scene.hud_lines[k];
        if (l.legend.w > 0.0 && top < l.legend.y + l.legend.h) {
          ++beside;
          EXPECT_LE(right, l.legend.x) << name << " " << w << ": " << scene.hud_lines[k];
        }
      }
    }
  }
  EXPECT_GT(beside, 50);
}

// A paced live picture (drawn at a fraction of its shown size, the page scales it up) has the full
// picture's overlay on the screen: its text the same size there, or the compact overlay where no
// font is that small; never the text scaled up with the picture (the HUD over the top half).
// Every preset, the pictures of 1280-, 1366- and 1920-wide pages, every pace the page uses.
TEST(SceneBuilder, APacedPictureShowsItsOverlayAsTheFullPictureDoes) {
  int same = 0, compact = 0;
  double worst = 0.0;  // the paced HUD's share of the picture beyond the full one's
  for (const PresetSource& preset : preset_sources()) {
    const Snapshot s = testing::preset_snapshot(preset.name, 10.0, true);
    for (const auto& [w, h] : {std::pair{756, 475}, {799, 520}, {1280, 727}}) {
      const ViewOptions full = testing::aimed_view(default_view(s.surface.kind), w, h, s);
      const FrameScene unpaced = build_scene(s, full);
      for (const double pace : {0.8, 0.64, 0.5}) {
        SCOPED_TRACE(std::string(preset.name) + " " + std::to_string(w) + " pace " + std::to_string(pace));
        ViewOptions view = full;
        view.width = static_cast<int>(std::lround(w * pace)),
        view.height = static_cast<int>(std::lround(h * pace));
        view.shown_width = w;
        const FrameScene paced = build_scene(s, view);
        const double up = static_cast<double>(w) / view.width;  // shown pixels per drawn pixel
        if (!compact_overlay(view)) {
          ++same;
          // The text's size on the screen is the full picture's, to the font's steps (kHudScales).
          EXPECT_NEAR(paced.hud.font_size * up, unpaced.hud.font_size, 0.15 * unpaced.hud.font_size);
          EXPECT_EQ(paced.hud_lines.size(), unpaced.hud_lines.size());
        } else {
          ++compact;
          EXPECT_LE(paced.hud_lines.size(), unpaced.hud_lines.size());
          EXPECT_EQ(paced.hud.legend.w, 0.0);
        }
        // Either way the boxes cover no more of the picture than the full one's (up to a glyph's
        // rounding), and no line runs past the frame.
        const auto share = [](const PixelBox& b, int width, int height) {
          return b.w * b.h / (width * height);
        };
        const double paced_share = share(paced.hud.hud, view.width, view.height),
                     full_share = share(unpaced.hud.hud, w, h);
        worst = std::max(worst, paced_share - full_share);
        EXPECT_LE(paced_share, full_share + 0.04);  // sized for the drawn size: up to +0.32
        EXPECT_LE(paced.hud.hud.x + paced.hud.hud.w, view.width);
      }
    }
  }
  // Both cases are met: 1920's picture keeps its text at every pace down to 0.64, 1280's goes compact.
  EXPECT_GT(same, 20);
  EXPECT_GT(compact, 20);
  std::printf(
      "paced pictures: %d with the full overlay, %d compact; the HUD's share at most %.3f above the full "
      "one's\n",
      same, compact, worst);
}

// The plain layer (simple mode) says the time, the surface and the spin in words a class has met, on
// every preset; the main body is "the body" in the legend. The full overlay keeps every line.
TEST(SceneBuilder, ThePlainLayerSaysTheTimeTheSurfaceAndTheSpinOnly) {
  int with_companions = 0;
  for (const PresetSource& preset : preset_sources()) {
    SCOPED_TRACE(std::string(preset.name));
    const Snapshot s = testing::preset_snapshot(preset.name, 5.0, true);
    ViewOptions view;
    view.kind = default_view(s.surface.kind);
    view.width = 1280, view.height = 720;
    const std::vector<std::string> full = hud_lines(s, view);
    view.layers |= kPlain;
    const std::vector<std::string> plain = hud_lines(s, view);
    std::string text;
    for (const std::string& line : plain) text += line + "\n";
    for (const char* jargon : {"energy", "integrator", "det L", "J =", "rigid", "affine"})
      EXPECT_EQ(text.find(jargon), std::string::npos) << jargon << " in\n" << text;
    EXPECT_EQ(plain.front().rfind("t = ", 0), 0u) << text;
    EXPECT_NE(text.find("spin = "), std::string::npos) << text;
    EXPECT_NE(text.find(std::string(enum_name(s.surface.kind))), std::string::npos) << text;
    EXPECT_LT(plain.size(), full.size());
    const std::vector<LegendEntry> legend = legend_entries(s, view);
    if (s.bodies.size() > 1) {  // the bodies' rows (a lone body has none)
      ++with_companions;
      EXPECT_NE(legend.at(0).label, "body 1");  // "the body", or the name the scene gives it
    }
  }
  EXPECT_GE(with_companions, 5);
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
  for (const ViewKind h2 : {ViewKind::klein, ViewKind::halfplane, ViewKind::tractricoid}) {
    EXPECT_FALSE(view_unsupported_reason(h2, SurfaceKind::pseudosphere));
    EXPECT_TRUE(view_unsupported_reason(h2, SurfaceKind::sphere));
    EXPECT_TRUE(view_unsupported_reason(h2, SurfaceKind::plane));
    EXPECT_EQ(parse_view(view_name(h2)), h2);
  }
  EXPECT_EQ(*view_unsupported_reason(ViewKind::sphere, SurfaceKind::pseudosphere),
            "the pseudosphere is shown in these views: disk, hyperboloid, klein, halfplane, tractricoid, "
            "conformal");
  for (const SurfaceKind kind : {SurfaceKind::sphere, SurfaceKind::plane, SurfaceKind::pseudosphere})
    EXPECT_FALSE(view_unsupported_reason(ViewKind::conformal, kind));
  EXPECT_EQ(parse_view("conformal"), ViewKind::conformal);
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
  // The 2-D views: only the mesh's boundary (the Poincaré disk's rim, kRimSlices segments).
  const Snapshot h = body_at(SurfaceKind::pseudosphere, 1.0, 1.0, 0.0, 1.0, 1.0);
  view.kind = ViewKind::disk;
  const FrameScene disk = build_scene(h, view);
  const std::vector<Vertex> rim = silhouette(*disk.statics, disk);
  EXPECT_EQ(rim.size(), 2u * kRimSlices);
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
  EXPECT_EQ(hud_layout(lines, {}, 1920, 460).font_size, 13.0);  // the shorter side counts
  // The picture of a 1366×900 page (795×515) and anything larger: at least 16 px, for a projector.
  EXPECT_GE(hud_layout(lines, {}, 795, 515).font_size, 16.0);
  EXPECT_GE(hud_layout(lines, {}, 1920, 600).font_size, 16.0);
  EXPECT_EQ(hud_layout(lines, {}, 700, 490).font_size, 13.0);
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
      const ViewOptions view = testing::aimed_view(ViewKind::hyperboloid, w, h, s);
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
      // Seen from inside the bowl: the camera above the sheet, the body's face (its Minkowski normal
      // (−x₁, −x₂, x₃), into the bowl) turned to it. Near the vertex a camera drawn back at the
      // preferred pitch was under the sheet: a frame of dark underside and no body.
      const glm::dvec4 e = glm::inverse(glm::dmat4(scene.view_projection)) * glm::dvec4(0, 0, 1, 0);
      const glm::dvec3 eye = glm::dvec3(e) / e.w;
      EXPECT_GT(eye.z + 1.0, std::sqrt(1.0 + eye.x * eye.x + eye.y * eye.y))
          << "r = " << r << ", " << w << "x" << h;
      const Vec3& X = s.bodies[0].X;
      const glm::dvec3 normal(-X.x(), -X.y(), X.z());
      EXPECT_GT(glm::dot(normal, eye - world_position(s.surface, view.kind, X)), 0.0) << "r = " << r;
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

// The teacher's dial at K = −1: the body at r ≈ 4.3–5 was a speck on the rim of a fixed disk.
// The flat maps of H² now close up on the bodies where the map shrinks them, by a power of two
// that the HUD states, and leave a body near the pole in the whole disk.
TEST(SceneBuilder, TheFlatMapsOfH2CloseUpOnABodyFarOutAndSaySo) {
  for (const ViewKind kind : {ViewKind::disk, ViewKind::klein, ViewKind::conformal})
    for (const double r : {1.3, 3.0, 4.5, 6.0, 9.0})
      for (const auto& [w, h] : {std::pair{640, 480}, {795, 515}, {1280, 757}}) {
        // Its recent trail: the last 0.8 R of a radial run (a circle far out is as local).
        Snapshot s = body_at(SurfaceKind::pseudosphere, 1.0, r, 0.8, 1.0, 1.0);
        for (int k = 0; k <= 64; ++k)
          s.bodies[0].trail.push_back(chart_point(s.surface, r - 0.8 + 0.8 * k / 64, 0.8).X);
        s.hud_lines = hud_of_a_run();
        ViewOptions view;
        view.kind = kind;
        view.width = w;
        view.height = h;
        view.scale = 0.25 * (kind == ViewKind::conformal ? 1.0 : s.surface.radius);
        aim_camera_at_body(view, s);
        const FrameScene scene = build_scene(s, view);
        const std::string where = std::string(view_name(kind)) + " r = " + std::to_string(r) + " " +
                                  std::to_string(w) + "x" + std::to_string(h);
        const auto at = [&](const Vec3& X) {
          return *pixel_position(scene, view, world_position(s.surface, view.kind, X));
        };
        // The body's outline across [pixels], and what it is at the pole in the view's own window.
        const auto across = [&](const Snapshot& snap, const FrameScene& sc, const ViewOptions& v) {
          double most = 0.0;
          const std::vector<Vec3> outline = ellipse_points(snap.surface, snap.bodies[0], v.scale, 16);
          for (const Vec3& a : outline)
            for (const Vec3& b : outline)
              most =
                  std::max(most, glm::length(*pixel_position(sc, v, world_position(snap.surface, kind, a)) -
                                             *pixel_position(sc, v, world_position(snap.surface, kind, b))));
          return most;
        };
        const Snapshot home = out_on_h2(0.0);
        ViewOptions home_view = view;
        aim_camera_at_body(home_view, home);
        const double size = across(s, scene, view),
                     size_at_pole = across(home, build_scene(home, home_view), home_view);
        if (r <= 1.3) {
          EXPECT_EQ(view.zoom, 1.0) << where;  // near the pole: the whole disk
          continue;
        }
        if (r <= 6.0)  // within the largest close-up's reach: a quarter of its size at the pole at least
          EXPECT_GE(size, size_at_pole / 4.0) << where << ": zoom " << view.zoom;
        else
          EXPECT_EQ(view.zoom, kMaxCloseUp) << where;
        EXPECT_GT(view.zoom, 1.0) << where;
        const bool said = std::ranges::any_of(scene.hud_lines, [&](const std::string& line) {
          return line.starts_with("close-up ") && std::stod(line.substr(9)) == view.zoom;
        });
        EXPECT_TRUE(said) << where;
        // The body and the trail's last stretch in the frame and clear of the HUD.
        const glm::dvec2 body = at(s.bodies[0].X);
        EXPECT_FALSE(scene.hud.hud.contains(body)) << where;
        for (int k = 0; k <= 64; ++k) {
          const glm::dvec2 p = at(s.bodies[0].trail[k]);
          EXPECT_TRUE(p.x >= 0 && p.x <= w && p.y >= 0 && p.y <= h) << where;
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

// ---- The pictures of H²: Klein, the upper half-plane, the tractricoid.

// Points of the H² geodesic through the chart point (r, φ) in the direction of E₁ cos a + E₂ sin a,
// at arc lengths from −reach to reach [radii].
std::vector<Vec3> h2_geodesic(const Surface& h2, double r, double phi, double a, double reach, int count) {
  const ChartPoint p = chart_point(h2, r, phi);
  const Vec3 u = std::cos(a) * p.E1 + std::sin(a) * p.E2;  // a unit tangent
  std::vector<Vec3> points;
  for (int i = 0; i <= count; ++i) {
    const double s = h2.radius * reach * (2.0 * i / count - 1.0);
    points.push_back(exponential_map(h2, p.X, s * u, std::abs(s)));
  }
  return points;
}

// The H² point at half-plane coordinates (x, y): the inverse of half_plane_point.
Vec3 from_half_plane(const Surface& h2, double x, double y) {
  const double R = h2.radius, minus = R / y, plus = R * (x * x + y * y) / y;  // X₃ − X₁, X₃ + X₁
  return {0.5 * (plus - minus), -x * R / y, 0.5 * (plus + minus)};
}

TEST(HyperbolicPictures, KleinGeodesicsAreStraightChords) {
  const Surface h2{SurfaceKind::pseudosphere, 1.5};
  for (const auto& [r, phi, a] :
       {std::tuple{0.0, 0.0, 0.3}, {0.7, 0.3, 1.1}, {2.5, -2.0, 2.9}, {4.0, 1.0, -0.4}}) {
    const std::vector<Vec3> points = h2_geodesic(h2, r, phi, a, 5.0, 200);
    const glm::dvec2 p0(world_position(h2, ViewKind::klein, points.front()));
    const glm::dvec2 chord = glm::dvec2(world_position(h2, ViewKind::klein, points.back())) - p0;
    for (const Vec3& P : points) {
      const glm::dvec2 q = glm::dvec2(world_position(h2, ViewKind::klein, P)) - p0;
      EXPECT_LT(std::abs(chord.x * q.y - chord.y * q.x) / glm::length(chord), 1e-12)
          << r << " " << phi << " " << a;
      EXPECT_LT(glm::length(glm::dvec2(world_position(h2, ViewKind::klein, P))), 1.0);
    }
  }
  // Not a map of the disk: the Poincaré picture of the same geodesic bends.
  const std::vector<Vec3> points = h2_geodesic(h2, 0.7, 0.3, 1.1, 3.0, 2);
  const glm::dvec2 a(world_position(h2, ViewKind::disk, points[0])),
      b(world_position(h2, ViewKind::disk, points[1])), c(world_position(h2, ViewKind::disk, points[2]));
  EXPECT_GT(std::abs((c - a).x * (b - a).y - (c - a).y * (b - a).x), 1e-3);
}

TEST(HyperbolicPictures, HalfPlaneGeodesicsAreSemicirclesOnTheBoundaryOrVerticalLines) {
  const Surface h2{SurfaceKind::pseudosphere, 0.8};
  EXPECT_NEAR(half_plane_point(h2, chart_point(h2, 0.0, 0.0).X).x, 0.0, 1e-15);
  EXPECT_NEAR(half_plane_point(h2, chart_point(h2, 0.0, 0.0).X).y, 1.0, 1e-15);
  for (const auto& [r, phi, a] :
       {std::tuple{0.7, 0.3, 1.1}, {2.5, -2.0, 2.9}, {1.0, 2.0, 0.2}, {3.0, 0.5, 1.9}}) {
    std::vector<glm::dvec2> q;
    for (const Vec3& P : h2_geodesic(h2, r, phi, a, 4.0, 100)) q.push_back(half_plane_point(h2, P));
    // The centre on y = 0 equidistant from the two ends; every point at that distance.
    const glm::dvec2 p = q.front(), e = q.back();
    const double c = (glm::dot(e, e) - glm::dot(p, p)) / (2.0 * (e.x - p.x));
    const double radius = glm::length(p - glm::dvec2(c, 0.0));
    for (const glm::dvec2& x : q) {
      EXPECT_GT(x.y, 0.0);
      EXPECT_NEAR(glm::length(x - glm::dvec2(c, 0.0)), radius, 1e-11 * std::max(1.0, radius))
          << r << " " << phi;
    }
  }
  // The geodesic through the centre along X₁ is the vertical line x = 0, from 0 up to infinity.
  const Surface unit{SurfaceKind::pseudosphere, 1.0};
  double last = 0.0;
  for (const Vec3& P : h2_geodesic(unit, 0.0, 0.0, 0.0, 6.0, 60)) {
    const glm::dvec2 x = half_plane_point(unit, P);
    EXPECT_NEAR(x.x, 0.0, 1e-12);
    EXPECT_GT(x.y, last);
    last = x.y;
  }
  // Conformal: the picture of a small circle round a point is a circle (its widths agree).
  const Vec3 X = chart_point(h2, 1.7, 0.9).X;
  const ChartPoint p = chart_point(h2, 1.7, 0.9);
  std::vector<double> widths;
  for (const double a : {0.0, 0.5, 1.0, 1.5}) {
    const Vec3 u = std::cos(a) * p.E1 + std::sin(a) * p.E2;
    widths.push_back(glm::length(half_plane_point(h2, exponential_map(h2, X, 1e-4 * u, 1e-4)) -
                                 half_plane_point(h2, exponential_map(h2, X, -1e-4 * u, 1e-4))));
  }
  for (const double w : widths) EXPECT_NEAR(w / widths[0], 1.0, 1e-6);
}

TEST(HyperbolicPictures, TheTractricoidIsTheSurfaceAndItsDistancesAreThoseOfH2) {
  const Surface h2{SurfaceKind::pseudosphere, 1.3};
  // On the surface ρ = sech u, z = u − tanh u (world units of R) for points of the strip.
  for (double x = -3.0; x <= 3.0; x += 0.37)
    for (double y = 0.55; y < 40.0; y *= 1.7) {
      const Vec3 P = from_half_plane(h2, x, y);
      const glm::dvec2 back = half_plane_point(h2, P);
      EXPECT_NEAR(back.x, x, 1e-12 * std::max(1.0, y));
      EXPECT_NEAR(back.y, y, 1e-12 * y);
      ASSERT_TRUE(on_view(h2, ViewKind::tractricoid, P));
      const glm::dvec3 w = world_position(h2, ViewKind::tractricoid, P);
      const double rho = glm::length(glm::dvec2(w)), u = std::acosh(1.0 / rho);
      EXPECT_NEAR(w.z, u - std::tanh(u), 1e-12);
      EXPECT_NEAR(std::atan2(w.y, w.x), std::remainder(kTractricoidDilation * x, 2 * std::numbers::pi),
                  1e-12);
    }
  // Lengths along the surface are H² lengths: a geodesic arc of 1.5 radii inside the strip,
  // measured as a fine polygon in space (the chord error falls as 1/n²).
  for (const auto& [r, phi, a] : {std::tuple{0.3, 0.0, 0.4}, {0.8, 1.0, 2.0}, {0.5, -0.5, -1.2}}) {
    const std::vector<Vec3> points = h2_geodesic(h2, r, phi, a, 0.75, 4000);
    double length = 0.0;
    for (std::size_t i = 1; i < points.size(); ++i) {
      ASSERT_TRUE(on_view(h2, ViewKind::tractricoid, points[i]));
      length += h2.radius * glm::length(world_position(h2, ViewKind::tractricoid, points[i]) -
                                        world_position(h2, ViewKind::tractricoid, points[i - 1]));
    }
    EXPECT_NEAR(length / (1.5 * h2.radius), 1.0, 1e-6) << r << " " << phi << " " << a;
  }
}

TEST(HyperbolicPictures, TheCoveringMapWrapsTheStripRoundTheSeamAndEndsAtTheRim) {
  const Surface h2{SurfaceKind::pseudosphere, 2.0};
  const double period = 2.0 * std::numbers::pi / kTractricoidDilation;  // in x
  for (const double x : {-1.0, 0.2, 1.5})
    for (const double y : {0.6, 2.0, 9.0}) {
      const glm::dvec3 a = world_position(h2, ViewKind::tractricoid, from_half_plane(h2, x, y));
      const glm::dvec3 b = world_position(h2, ViewKind::tractricoid, from_half_plane(h2, x + period, y));
      EXPECT_LT(glm::length(a - b), 1e-12) << x << " " << y;  // one point of the surface, two of H²
      const glm::dvec3 c =
          world_position(h2, ViewKind::tractricoid, from_half_plane(h2, x + 0.5 * period, y));
      EXPECT_GT(glm::length(a - c), 0.1);  // half a turn away: another point
    }
  // Across the seam (x = ±period/2) the picture is continuous.
  const glm::dvec3 left =
      world_position(h2, ViewKind::tractricoid, from_half_plane(h2, 0.5 * period - 1e-9, 1.0));
  const glm::dvec3 right =
      world_position(h2, ViewKind::tractricoid, from_half_plane(h2, 0.5 * period + 1e-9, 1.0));
  EXPECT_LT(glm::length(left - right), 1e-8);
  // The rim: y = 1/k is u = 0 (ρ = R, z = 0); below it the point is off the surface.
  const Vec3 rim = from_half_plane(h2, 0.3, 1.0 / kTractricoidDilation);
  EXPECT_NEAR(glm::length(glm::dvec2(world_position(h2, ViewKind::tractricoid, rim))), 1.0, 1e-12);
  EXPECT_FALSE(on_view(h2, ViewKind::tractricoid, from_half_plane(h2, 0.3, 0.99 / kTractricoidDilation)));
  EXPECT_TRUE(on_view(h2, ViewKind::disk, from_half_plane(h2, 0.3, 0.01)));
}

TEST(HyperbolicPictures, ABodyBeyondTheRimIsNotDrawnAndTheHudSaysSo) {
  Snapshot s = body_at(SurfaceKind::pseudosphere, 1.0, 0.0, 0.0, 1.0, 1.0);
  ViewOptions view;
  view.kind = ViewKind::tractricoid;
  const FrameScene on = build_scene(s, view);
  EXPECT_FALSE(on.fills.empty());
  // Far out along −X₁ the half-plane's y falls below 1/k: off the strip.
  s = body_at(SurfaceKind::pseudosphere, 1.0, 2.0, std::numbers::pi, 1.0, 1.0);
  s.hud_lines = {"t = 0"};
  ASSERT_FALSE(on_view(s.surface, ViewKind::tractricoid, s.bodies[0].X));
  aim_camera_at_body(view, s);  // no sight of it: the default camera
  const FrameScene off = build_scene(s, view);
  EXPECT_TRUE(off.fills.empty());
  ASSERT_EQ(off.hud_lines.size(), 2u);
  EXPECT_NE(off.hud_lines[1].find("beyond the rim"), std::string::npos);
  view.kind = ViewKind::disk;
  EXPECT_EQ(build_scene(s, view).hud_lines.size(), 1u);
}

TEST(SceneBuilder, TheActionsLayerAddsTheActionLinesToTheHudAndIsOffByDefault) {
  Snapshot s = body_at(SurfaceKind::sphere, 1.0, 1.0, 0.0, 1.0, 1.0);
  s.hud_lines = {"t = 1.000"};
  s.action_lines = {"J_r = 0.5  J_phi = 1  J_alpha = 2", "nu_r = 0.3"};
  ViewOptions view;
  EXPECT_EQ(build_scene(s, view).hud_lines, s.hud_lines);
  view.layers = kDefaultLayers | kActions;
  const FrameScene with = build_scene(s, view);
  ASSERT_EQ(with.hud_lines.size(), 3u);
  EXPECT_EQ(with.hud_lines[1], s.action_lines[0]);
  EXPECT_GT(with.hud.hud.h, build_scene(s, ViewOptions{}).hud.hud.h);  // the box grows to hold them
  view.layers = kActions;                                              // without the HUD there is no text
  EXPECT_TRUE(build_scene(s, view).hud_lines.empty());
  EXPECT_EQ(parse_layers("hud,actions"), kHud | kActions);
  EXPECT_NE(std::find(layer_names().begin(), layer_names().end(), "actions"), layer_names().end());
}

TEST(HyperbolicPictures, TheHalfPlaneFollowsTheBodyAtEveryHeight) {
  for (const auto& [r, phi] :
       {std::pair{0.0, 0.0}, {3.0, 0.0}, {3.0, std::numbers::pi}, {5.0, 2.0}, {6.0, -1.0}}) {
    const Snapshot s = body_at(SurfaceKind::pseudosphere, 1.0, r, phi, 1.0, 1.0);
    ViewOptions view;
    view.kind = ViewKind::halfplane;
    aim_camera_at_body(view, s);
    const FrameScene scene = build_scene(s, view);
    for (const Vec3& P : ellipse_points(s.surface, s.bodies[0], view.scale, 16)) {
      const std::optional<glm::dvec2> p =
          pixel_position(scene, view, world_position(s.surface, view.kind, P));
      ASSERT_TRUE(p);
      EXPECT_TRUE(p->x > 0.1 * view.width && p->x < 0.9 * view.width && p->y > 0.1 * view.height &&
                  p->y < 0.9 * view.height)
          << r << " " << phi << ": " << p->x << ", " << p->y;
    }
    // The boundary y = 0 stays in the picture, just above its lower edge.
    const std::optional<glm::dvec2> ground = pixel_position(scene, view, {(*view.target)[0], 0.0, 0.0});
    ASSERT_TRUE(ground);
    EXPECT_GT(ground->y, 0.9 * view.height);
    EXPECT_LT(ground->y, view.height);
  }
}

// ---- The conformal view: one flat map for every curvature, continuous in K.

TEST(ConformalView, TheMapIsContinuousInKThroughZero) {
  for (const double K : {1e-12, -1e-12, 1e-300, -1e-300})
    for (double r = 0.0; r <= 10.0; r += 0.25) {
      const double T = conformal_radius(K, r);
      // T_K(r) = r(1 + Kr²/12 + …): within 1e-12 of r relative where |K|r²/12 is below it, and
      // within that first term (≤ 8.4e-12 at r = 10) everywhere.
      EXPECT_LE(std::abs(T - r), (std::abs(K) * r * r / 12.0 * 1.001 + 1e-15) * r) << K << " " << r;
      if (r <= 3.0) {
        EXPECT_LE(std::abs(T - r), 1e-12 * r);
      }
      EXPECT_NEAR(conformal_distance(K, T), r, 1e-14 * std::max(1.0, r));
    }
  EXPECT_EQ(conformal_radius(0.0, 7.25), 7.25);
  // And the points of surfaces of radius 1e6 land where the plane's do.
  const Surface plane{SurfaceKind::plane, 1.0};
  for (const Surface& surface : {Surface{SurfaceKind::sphere, 1e6}, Surface{SurfaceKind::pseudosphere, 1e6}})
    for (const auto& [r, phi] : {std::pair{0.0, 0.0}, {0.7, 2.0}, {3.0, -1.0}, {10.0, 3.1}}) {
      const glm::dvec2 w = conformal_point(surface, chart_point(surface, r, phi).X);
      const glm::dvec2 flat = conformal_point(plane, chart_point(plane, r, phi).X);
      EXPECT_LE(glm::length(w - flat), 1e-10 * std::max(1.0, r));
    }
}

TEST(ConformalView, AVectorIsDrawnLongerByTheConformalFactorAtItsOwnAngle) {
  // Central differences of w along geodesics from a few points in a few directions: |dw|/ds is
  // 1 + K|w|²/4, and dw makes the angle with the radial direction that the tangent makes with E₁.
  for (const double K : {1.0, -1.0, 0.25, -0.25}) {
    const Surface surface{K > 0 ? SurfaceKind::sphere : SurfaceKind::pseudosphere,
                          1.0 / std::sqrt(std::abs(K))};
    for (const auto& [r, phi] : {std::pair{0.3, 0.4}, {1.2, -2.0}, {2.5, 2.8}})
      for (const double a : {0.0, 0.9, 2.0, -1.3}) {
        const ChartPoint p = chart_point(surface, r, phi);
        const Vec3 u = std::cos(a) * p.E1 + std::sin(a) * p.E2;
        const double h = 1e-5;
        const glm::dvec2 w = conformal_point(surface, p.X);
        const glm::dvec2 dw = (conformal_point(surface, exponential_map(surface, p.X, h * u, h)) -
                               conformal_point(surface, exponential_map(surface, p.X, -h * u, h))) /
                              (2.0 * h);
        EXPECT_NEAR(glm::length(dw), conformal_factor(K, w), 1e-8 * conformal_factor(K, w)) << K << " " << r;
        EXPECT_NEAR(std::remainder(std::atan2(dw.y, dw.x) - phi - a, 2 * std::numbers::pi), 0.0, 1e-8);
      }
  }
}

TEST(ConformalView, TheSpheresAntipodeGoesToInfinityAndH2StaysInsideItsDisk) {
  const Surface sphere{SurfaceKind::sphere, 2.0}, h2{SurfaceKind::pseudosphere, 2.0};
  double last = 0.0;
  for (const double gap : {1.0, 1e-1, 1e-2, 1e-3, 1e-4, 1e-6}) {  // distance to the antipode [length]
    const double w =
        glm::length(conformal_point(sphere, chart_point(sphere, std::numbers::pi * 2.0 - gap, 0.5).X));
    EXPECT_GT(w, last);
    EXPECT_NEAR(w * gap, 4.0 * 2.0 * 2.0, 0.1 * 16.0);  // |w| ≈ 4R²/gap
    last = w;
  }
  EXPECT_GT(last, 1e7);
  for (const double r : {0.5, 5.0, 20.0, 60.0, 400.0}) {
    const glm::dvec2 w = conformal_point(h2, chart_point(h2, r, 1.0).X);
    EXPECT_TRUE(std::isfinite(w.x) && std::isfinite(w.y));
    EXPECT_LE(glm::length(w), 4.0);  // 2R, reached in double from r ≈ 37R on
    if (r <= 20.0) {
      EXPECT_LT(glm::length(w), 4.0);
    }
  }
}

TEST(ConformalView, TheBodyIsTheFirstOrderImageOfItsFrame) {
  // L = diag(λ, μ) in the paper's frame: the ellipse's outline is w + f·scale·(λ cos θ ŵ + μ sin θ ŵ⊥)
  // with f = 1 + K|w|²/4, and the arrow e₁ ends at w + 1.3 f·scale·λ ŵ.
  for (const auto& [kind, R] : {std::pair{SurfaceKind::sphere, 1.0},
                                {SurfaceKind::pseudosphere, 1.0},
                                {SurfaceKind::plane, 1.0},
                                {SurfaceKind::pseudosphere, 0.5}}) {
    const double r = 1.1, phi = 0.6, lambda = 1.4, mu = 0.7;
    const Snapshot s = body_at(kind, R, r, phi, lambda, mu);
    ViewOptions view;
    view.kind = ViewKind::conformal;
    view.layers = kBody | kFrame;
    const FrameScene scene = build_scene(s, view);
    const double K = curvature(s.surface);
    const glm::dvec2 w = conformal_radius(K, r) * glm::dvec2(std::cos(phi), std::sin(phi));
    const glm::dvec2 radial = glm::normalize(w), angular(-radial.y, radial.x);
    const double f = conformal_factor(K, w) * view.scale;
    EXPECT_NEAR(glm::length(glm::dvec2(world_position(s.surface, view.kind, s.bodies[0].X)) - w), 0.0, 1e-12);
    // The outline: 64 segments, the first from θ = 0.
    ASSERT_GE(scene.lines.size(), 128u);
    for (int i = 0; i < 64; ++i) {
      const double theta = 2 * std::numbers::pi * i / 64;
      const glm::dvec2 expected =
          w + f * (lambda * std::cos(theta) * radial + mu * std::sin(theta) * angular);
      EXPECT_NEAR(glm::length(glm::dvec2(scene.lines[2 * i].position) - expected), 0.0, 1e-5);
    }
    const glm::dvec2 tip(scene.lines[129].position);  // the e₁ shaft's far end
    EXPECT_NEAR(glm::length(tip - (w + 1.3 * f * lambda * radial)), 0.0, 1e-5);
  }
}

TEST(ConformalView, AtZeroCurvatureTheGridIsThePlanesAndH2AddsItsBoundaryWhereTheFrameShowsIt) {
  Snapshot s = body_at(SurfaceKind::plane, 1.0, 1.3, 0.4, 1.0, 1.0);
  ViewOptions view;
  view.kind = ViewKind::conformal;
  aim_camera_at_body(view, s);
  const FrameScene flat = build_scene(s, view);
  ASSERT_FALSE(flat.grid_lines.empty());
  EXPECT_EQ(flat.clear_color, flat.surface_color);
  EXPECT_TRUE(flat.backdrop.empty());
  for (std::size_t i = 0; i + 1 < flat.grid_lines.size(); i += 2) {  // on the plane's lines
    const glm::dvec3 a(flat.grid_lines[i].position), b(flat.grid_lines[i + 1].position);
    const double c = a.x == b.x ? a.x : a.y;
    ASSERT_TRUE(a.x == b.x || a.y == b.y);
    EXPECT_NEAR(c / kPlaneGridSpacing, std::round(c / kPlaneGridSpacing), 1e-5);
  }
  const auto boundary_segments = [](const FrameScene& scene) {
    int n = 0;
    for (const Vertex& v : scene.grid_lines) n += v.color != scene.grid_lines.front().color;
    return n;
  };
  EXPECT_EQ(boundary_segments(flat), 0);
  // H² of radius 1: the disk |w| < 2 lies in the frame: drawn on the background, with its rim.
  s = body_at(SurfaceKind::pseudosphere, 1.0, 1.3, 0.4, 1.0, 1.0);
  aim_camera_at_body(view, s);
  const FrameScene h2 = build_scene(s, view);
  EXPECT_NE(h2.clear_color, h2.surface_color);
  EXPECT_FALSE(h2.backdrop.empty());
  EXPECT_GT(boundary_segments(h2), 100);
  for (const Vertex& v : h2.backdrop) EXPECT_LE(glm::length(v.position), 2.0 + 1e-6);
  // H² of radius 100: the frame lies inside the disk.
  s = body_at(SurfaceKind::pseudosphere, 100.0, 1.3, 0.4, 1.0, 1.0);
  aim_camera_at_body(view, s);
  const FrameScene big = build_scene(s, view);
  EXPECT_EQ(big.clear_color, big.surface_color);
  EXPECT_TRUE(big.backdrop.empty());
  EXPECT_EQ(boundary_segments(big), 0);
}

TEST(ConformalView, NearTheSpheresAntipodeAndFarOutOnH2TheFrameStaysFiniteAndSmall) {
  // The window follows the body wherever its image goes: out towards infinity by the antipode, up
  // to the disk's boundary on H². Nothing drawn is NaN, and the grid stays a few thousand segments.
  const double pi = std::numbers::pi;
  for (const auto& [kind, r] : {std::pair{SurfaceKind::sphere, pi - 1e-3},
                                {SurfaceKind::sphere, pi - 1e-9},
                                {SurfaceKind::sphere, pi},
                                {SurfaceKind::pseudosphere, 20.0},
                                {SurfaceKind::pseudosphere, 200.0}}) {
    Snapshot s = body_at(kind, 1.0, r, 0.8, 1.0, 1.0);
    for (int i = 0; i <= 16; ++i)
      s.bodies[0].trail.push_back(chart_point(s.surface, r - 0.5 + i / 32.0, 0.8 - 0.2 + i / 40.0).X);
    ViewOptions view;
    view.kind = ViewKind::conformal;
    aim_camera_at_body(view, s);
    const FrameScene scene = build_scene(s, view);
    EXPECT_LT(scene.grid_lines.size(), 20000u) << r;
    for (const std::vector<Vertex>* list : {&scene.lines, &scene.fills, &scene.grid_lines, &scene.backdrop})
      for (const Vertex& v : *list)
        ASSERT_TRUE(std::isfinite(v.position.x) && std::isfinite(v.position.y)) << r;
  }
}

}  // namespace
}  // namespace spinfold::render
