// The renderer through the process's GL backend (SPINFOLD_GL; auto here): pixels where the geometry says, the
// far side hidden, the HUD only when asked, identical bytes for identical input, and a golden PNG per view.
#include "render/renderer.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <set>
#include <sstream>
#include <string>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "engine/chart.h"
#include "engine/timeline.h"
#include "render/gl_context.h"
#include "render/gl_renderer.h"
#include "render/snapshot.h"
#include "render/view_table.h"
#include "render/views/view_model.h"
#include "tests/render/frame_compare.h"
#include "tests/render/views/view_test_support.h"

namespace spinfold::render {
namespace {

using testing::preset_snapshot;

Renderer& renderer() {
  static Renderer r;  // one context for the whole test binary (one thread)
  return r;
}

struct Rgb {
  int r, g, b;
};

Rgb pixel(const std::uint8_t* rgba, const ViewOptions& view, glm::dvec2 at) {
  const int x = static_cast<int>(at.x), y = static_cast<int>(at.y);
  const std::uint8_t* p = rgba + (static_cast<std::size_t>(y) * view.width + x) * 4;
  return {p[0], p[1], p[2]};
}

// The ellipse's fill over any background: clearly more red than blue (the surfaces are bluish or
// grey-green, the background near white).
bool orange(Rgb c) {
  return c.r > 150 && c.r - c.b > 60 && c.g < c.r;
}

// A point inside the ellipse away from the frame arrows (which start at the centre).
glm::dvec3 inside_ellipse(const Snapshot& s, ViewKind view, std::size_t body = 0, double scale = 0.25) {
  const BodySnapshot& b = s.bodies.at(body);
  const Vec3 P = b.X + 0.4 * scale * (-std::sqrt(0.5) * b.e[0] - std::sqrt(0.5) * b.e[1]);
  return world_position(s.surface, view, P * (s.surface.radius / P.norm()));
}

ViewOptions looking_at(const Snapshot& s, double yaw_offset) {
  ViewOptions view;
  const Vec3 n = s.bodies.front().X.normalized();
  view.yaw = std::atan2(n.y(), n.x()) + yaw_offset;
  view.pitch = std::asin(n.z());
  if (yaw_offset != 0.0) view.pitch = -view.pitch;
  return view;
}

TEST(Renderer, BodyColourAppearsAtItsProjectedPosition) {
  const Snapshot s = preset_snapshot("breathing_ellipse_sphere", 1.0, false);
  ViewOptions view = looking_at(s, 0.0);
  view.layers = kSurface | kBody;
  const FrameScene scene = build_scene(s, view);
  const auto at = pixel_position(scene, view, inside_ellipse(s, view.kind));
  ASSERT_TRUE(at);
  const std::uint8_t* rgba = renderer().render_rgba(scene, view.width, view.height);
  EXPECT_TRUE(orange(pixel(rgba, view, *at)));
  // Without the body layer the same pixel shows the surface.
  view.layers = kSurface;
  EXPECT_FALSE(
      orange(pixel(renderer().render_rgba(build_scene(s, view), view.width, view.height), view, *at)));
}

TEST(Renderer, ABodyBehindTheSphereIsHidden) {
  const Snapshot s = preset_snapshot("breathing_ellipse_sphere", 1.0, false);
  ViewOptions view = looking_at(s, std::numbers::pi);  // the camera on the far side
  view.layers = kSurface | kBody;
  const FrameScene scene = build_scene(s, view);
  const auto at = pixel_position(scene, view, inside_ellipse(s, view.kind));
  ASSERT_TRUE(at);
  ASSERT_TRUE(at->x >= 0 && at->x < view.width && at->y >= 0 && at->y < view.height);
  EXPECT_FALSE(orange(pixel(renderer().render_rgba(scene, view.width, view.height), view, *at)));
  // Without the sphere in the way the body shows through.
  view.layers = kBody;
  EXPECT_TRUE(
      orange(pixel(renderer().render_rgba(build_scene(s, view), view.width, view.height), view, *at)));
}

int dark_pixels_top_left(const std::uint8_t* rgba, const ViewOptions& view) {
  int dark = 0;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 200; ++x) {
      const std::uint8_t* p = rgba + (static_cast<std::size_t>(y) * view.width + x) * 4;
      dark += p[0] < 80 && p[1] < 80 && p[2] < 80;
    }
  return dark;
}

TEST(Renderer, HudTextAppearsOnlyWhenTheHudIsOn) {
  const Snapshot s = preset_snapshot("spinning_rigid_pseudosphere", 2.0, false);
  ViewOptions view;
  view.kind = ViewKind::disk;
  view.layers = kSurface | kGrid | kBody;
  const int without =
      dark_pixels_top_left(renderer().render_rgba(build_scene(s, view), view.width, view.height), view);
  view.layers |= kHud;
  const int with =
      dark_pixels_top_left(renderer().render_rgba(build_scene(s, view), view.width, view.height), view);
  EXPECT_EQ(without, 0);
  EXPECT_GT(with, 200);  // glyph pixels of six text lines
}

// A body's translucent fill over the background with nothing else drawn: 0.55·colour + 0.45·clear.
bool fill_of(Rgb c, const std::array<float, 3>& color) {
  const glm::vec4 clear = FrameScene{}.clear_color;
  const float want[3] = {0.55f * color[0] + 0.45f * clear.r, 0.55f * color[1] + 0.45f * clear.g,
                         0.55f * color[2] + 0.45f * clear.b};
  const int got[3] = {c.r, c.g, c.b};
  for (int i = 0; i < 3; ++i)
    if (std::abs(got[i] - 255.0f * want[i]) > 6.0f) return false;
  return true;
}

TEST(Renderer, EachCompanionsColourAppearsAtItsProjectedPosition) {
  for (const char* preset : {"spin_vs_geodesic_sphere", "spin_fan_sphere", "opposite_spins_sphere"}) {
    SCOPED_TRACE(preset);
    const Snapshot s = preset_snapshot(preset, 3.0, false);
    ASSERT_GE(s.bodies.size(), 2u);
    ViewOptions view;
    aim_camera_at_body(view, s);  // at the bodies' mean position
    view.scale = 0.1;             // small ellipses that do not overlap
    view.layers = kBody;
    const FrameScene scene = build_scene(s, view);
    const std::uint8_t* rgba = renderer().render_rgba(scene, view.width, view.height);
    for (std::size_t i = 0; i < s.bodies.size(); ++i) {
      SCOPED_TRACE(s.bodies[i].label);
      const auto at = pixel_position(scene, view, inside_ellipse(s, view.kind, i, view.scale));
      ASSERT_TRUE(at);
      ASSERT_TRUE(at->x >= 0 && at->x < view.width && at->y >= 0 && at->y < view.height);
      const Rgb got = pixel(rgba, view, *at);
      EXPECT_TRUE(fill_of(got, s.bodies[i].color)) << got.r << "," << got.g << "," << got.b;
      // Each body has its own colour (bodies overlap at t = 0 only).
      for (std::size_t j = 0; j < s.bodies.size(); ++j) {
        if (j != i) {
          EXPECT_NE(s.bodies[i].color, s.bodies[j].color);
        }
      }
    }
  }
}

TEST(Renderer, TheMainBodyKeepsItsColourAndCompanionsGiveTheirOwn) {
  const Snapshot s = preset_snapshot("spin_vs_geodesic_sphere", 1.0, false);
  ASSERT_EQ(s.bodies.size(), 2u);
  EXPECT_EQ(s.bodies[0].color, kMainBodyColor);
  EXPECT_EQ(s.bodies[0].label, "body 1");
  EXPECT_EQ(s.bodies[1].color, kCompanionPalette[0]);
  EXPECT_EQ(s.bodies[1].label, "geodesic (s = 0)");
  EXPECT_TRUE(s.bodies[1].geodesic);
  // The HUD: the main body's lines as before, then one compact line per companion.
  EXPECT_EQ(s.hud_lines.size(), preset_snapshot("spinning_rigid_sphere", 1.0, false).hud_lines.size() + 1);
  EXPECT_EQ(s.hud_lines.back().rfind("geodesic (s = 0): spin = 0.0000  energy error = ", 0), 0u)
      << s.hud_lines.back();
}

// The top-right corner, where the legend goes: 180 × 60 pixels, RGB.
std::vector<Rgb> top_right(const std::uint8_t* rgba, const ViewOptions& view) {
  std::vector<Rgb> corner;
  for (int y = 0; y < 60; ++y)
    for (int x = view.width - 180; x < view.width; ++x)
      corner.push_back(pixel(rgba, view, {x + 0.5, y + 0.5}));
  return corner;
}

int differing(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
  int n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += a[i].r != b[i].r || a[i].g != b[i].g || a[i].b != b[i].b;
  return n;
}

TEST(Renderer, TheLegendAppearsOnlyWithMoreThanOneBody) {
  for (const char* preset : {"spinning_rigid_sphere", "spin_vs_geodesic_sphere"}) {
    SCOPED_TRACE(preset);
    const Snapshot s = preset_snapshot(preset, 2.0, true);
    ViewOptions view;
    aim_camera_at_body(view, s);
    view.layers = kSurface;
    const std::vector<Rgb> bare =
        top_right(renderer().render_rgba(build_scene(s, view), view.width, view.height), view);
    view.layers = kSurface | kBody | kTrail;
    const std::vector<Rgb> drawn =
        top_right(renderer().render_rgba(build_scene(s, view), view.width, view.height), view);
    if (s.bodies.size() == 1) {
      EXPECT_EQ(differing(bare, drawn), 0);
      continue;
    }
    EXPECT_GT(differing(bare, drawn), 2000);  // the legend's box
    int dark = 0;                             // the labels' glyphs
    bool swatch = false;                      // the companion's colour, opaque
    const std::array<float, 3> c = s.bodies[1].color;
    for (const Rgb& p : drawn) {
      dark += p.r < 80 && p.g < 80 && p.b < 80;
      swatch |=
          std::abs(p.r - 255 * c[0]) < 8 && std::abs(p.g - 255 * c[1]) < 8 && std::abs(p.b - 255 * c[2]) < 8;
    }
    EXPECT_GT(dark, 100);
    EXPECT_TRUE(swatch);
  }
}

// A GL renderer with its own context, without the HUD: frames of a scene with these options.
struct BareGl {
  std::unique_ptr<GlContext> context = make_gl_context();
  std::unique_ptr<GlRenderer> gl;
  explicit BareGl(const GlRenderer::Options& options) {
    context->make_current(64, 64);
    gl = std::make_unique<GlRenderer>(options);
  }
  ~BareGl() {
    context->make_current(64, 64);
    gl.reset();
  }
  std::vector<std::uint8_t> frame(const FrameScene& scene, int width, int height) {
    context->make_current(width, height);
    gl->draw(scene, width, height);
    gl->finish();
    return {context->pixels(), context->pixels() + static_cast<std::size_t>(width) * height * 4};
  }
};

TEST(Renderer, CachedBackgroundsGiveTheBytesOfDrawnOnes) {
  const Snapshot a = preset_snapshot("spinning_rigid_sphere", 3.0, true);
  const Snapshot b = preset_snapshot("spinning_rigid_sphere", 3.2, true);  // the body moved
  for (const int samples : {1, 4})
    for (const ViewKind kind : {ViewKind::sphere, ViewKind::disk}) {
      SCOPED_TRACE(std::string(view_name(kind)) + ", " + std::to_string(samples) + " samples");
      GlRenderer::Options options;
      options.samples = samples;
      GlRenderer::Options uncached_options = options;
      uncached_options.cache_background = false;
      BareGl cached(options), uncached(uncached_options);
      ViewOptions view;
      view.kind = kind;  // an explicit (fixed) camera
      const FrameScene sa = build_scene(a, view), sb = build_scene(b, view);
      const auto want_a = uncached.frame(sa, view.width, view.height);
      const auto want_b = uncached.frame(sb, view.width, view.height);
      const GlRenderer::CacheStats before = cached.gl->cache_stats();
      EXPECT_EQ(cached.frame(sa, view.width, view.height), want_a);  // cold: drawn in place
      EXPECT_EQ(cached.frame(sb, view.width, view.height), want_b);  // seen again: filled, copied
      EXPECT_EQ(cached.frame(sa, view.width, view.height), want_a);  // warm: copied
      EXPECT_EQ(cached.frame(sb, view.width, view.height), want_b);
      const GlRenderer::CacheStats after = cached.gl->cache_stats();
      EXPECT_EQ(after.misses - before.misses, 1);
      EXPECT_EQ(after.fills - before.fills, 1);
      EXPECT_EQ(after.hits - before.hits, 2);
    }
}

TEST(Renderer, TheBackgroundCacheFollowsEveryChangeOfSurfaceViewCameraAndSize) {
  const Snapshot sphere = preset_snapshot("spinning_rigid_sphere", 3.0, true);
  const Snapshot pseudo = preset_snapshot("spinning_rigid_pseudosphere", 3.0, true);
  ViewOptions base;
  struct Case {
    const char* what;
    const Snapshot* snapshot;
    ViewOptions view;
  };
  std::vector<Case> cases;
  ViewOptions v = base;
  cases.push_back({"base", &sphere, v});
  v.kind = ViewKind::disk;  // stereographic
  cases.push_back({"view", &sphere, v});
  cases.push_back({"surface", &pseudo, v});  // Poincaré disk
  v = base;
  v.yaw += 0.3;
  cases.push_back({"camera", &sphere, v});
  v = base;
  v.width = 320;
  v.height = 240;
  cases.push_back({"size", &sphere, v});
  v = base;
  v.layers &= ~unsigned{kGrid};
  cases.push_back({"layers", &sphere, v});
  for (std::size_t i = 1; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].what);
    const FrameScene first = build_scene(*cases[0].snapshot, cases[0].view);
    const FrameScene then = build_scene(*cases[i].snapshot, cases[i].view);
    BareGl warm(GlRenderer::Options{});
    for (int k = 0; k < 3; ++k) warm.frame(first, cases[0].view.width, cases[0].view.height);  // cached
    const auto got = warm.frame(then, cases[i].view.width, cases[i].view.height);
    BareGl fresh(GlRenderer::Options{});
    EXPECT_EQ(got, fresh.frame(then, cases[i].view.width, cases[i].view.height));
    EXPECT_NE(got, fresh.frame(first, cases[0].view.width, cases[0].view.height));
  }
}

TEST(Renderer, ACameraThatMovesEveryFrameNeverFillsTheCache) {
  const Snapshot s = preset_snapshot("spinning_rigid_sphere", 3.0, true);
  BareGl r(GlRenderer::Options{});
  for (int k = 0; k < 6; ++k) {
    ViewOptions view;
    view.yaw += 0.01 * k;
    r.frame(build_scene(s, view), view.width, view.height);
  }
  EXPECT_EQ(r.gl->cache_stats().fills, 0);
  EXPECT_EQ(r.gl->cache_stats().misses, 6);
  EXPECT_EQ(r.gl->cache_stats().entries, 0);
}

TEST(Renderer, LineWidthsGrowWithTheFrameAndNeverFallBelowAPixel) {
  EXPECT_FLOAT_EQ(line_widths(640, 480).lines, 1.5f);
  EXPECT_FLOAT_EQ(line_widths(160, 120).lines, 1.0f);
  EXPECT_FLOAT_EQ(line_widths(160, 120).grid, 1.0f);
  EXPECT_GT(line_widths(1280, 720).lines, line_widths(640, 480).lines);
  EXPECT_GT(line_widths(1920, 1080).lines, line_widths(1280, 720).lines);
  EXPECT_FLOAT_EQ(line_widths(1920, 1080).lines, 1.5f * 1080 / 480);
  // In pixels: the trail's colour covers more of a frame twice the size than twice the pixels of
  // the smaller one would (lines twice as long and wider).
  const Snapshot s = preset_snapshot("spinning_rigid_pseudosphere", 3.0, true);
  const auto trail_pixels = [&](int w, int h) {
    ViewOptions view;
    view.kind = ViewKind::disk;
    view.width = w;
    view.height = h;
    view.layers = kTrail;
    const std::uint8_t* p = renderer().render_rgba(build_scene(s, view), w, h);
    const std::array<float, 3> c = s.bodies[0].trail_color;
    double ink = 0.0;  // coverage: how far each pixel went from the background to the trail colour
    const glm::vec4 clear = FrameScene{}.clear_color;
    for (int i = 0; i < w * h; ++i) {
      const double t = (clear.r * 255.0 - p[4 * i]) / (clear.r * 255.0 - 255.0 * c[0]);
      ink += std::clamp(t, 0.0, 1.0);
    }
    return ink;
  };
  const double small = trail_pixels(640, 480), large = trail_pixels(1280, 960);
  EXPECT_GT(small, 0.0);
  EXPECT_GT(large / small, 2.0 * 1.5);  // twice as long, at least 1.5× as wide (2× here)
}

// The sphere's automatic camera with companions, at the sizes the browser asks for: every body
// in the frame, in front of the sphere and out of the HUD's and legend's boxes (while the bodies
// are less than 120° apart: no camera shows both sides of a sphere; then the main body is).
TEST(Renderer, TheSpheresCameraShowsEveryBodyOutOfTheHud) {
  for (const std::string_view preset :
       {"spin_vs_geodesic_sphere", "spin_fan_sphere", "opposite_spins_sphere"})
    for (const double t : {1.0, 2.0, 4.0, 8.0})
      for (const auto& [w, h] : {std::pair{640, 480}, {960, 600}, {1280, 720}, {1920, 1080}}) {
        const Snapshot s = preset_snapshot(preset, t, true);
        ViewOptions view;
        view.width = w;
        view.height = h;
        aim_camera_at_body(view, s);
        const FrameScene scene = build_scene(s, view);
        const glm::dvec4 e = glm::inverse(glm::dmat4(scene.view_projection)) * glm::dvec4(0, 0, 1, 0);
        const glm::dvec3 eye = glm::dvec3(e) / e.w;
        double spread = 0.0;
        for (const BodySnapshot& a : s.bodies)
          for (const BodySnapshot& b : s.bodies)
            spread =
                std::max(spread, std::acos(std::clamp(a.X.normalized().dot(b.X.normalized()), -1.0, 1.0)));
        for (const BodySnapshot& b : s.bodies) {
          if (spread > 2.0 * std::numbers::pi / 3.0 && &b != &s.bodies.front()) continue;
          const glm::dvec3 world = world_position(s.surface, view.kind, b.X);
          const std::optional<glm::dvec2> p = pixel_position(scene, view, world);
          const std::string where = std::string(preset) + " t = " + std::to_string(t) + " " +
                                    std::to_string(w) + "x" + std::to_string(h) + " " + b.label;
          ASSERT_TRUE(p) << where;
          EXPECT_GT(glm::dot(world, eye), 1.0) << where;  // on the near side
          EXPECT_TRUE(p->x > 0 && p->x < w && p->y > 0 && p->y < h) << where;
          EXPECT_FALSE(scene.hud.hud.contains(*p)) << where;
          EXPECT_FALSE(scene.hud.legend.contains(*p)) << where;
        }
      }
}

// The HUD's box is drawn where hud_layout() says: its translucent grey inside, the background
// just outside, at every scale.
TEST(Renderer, TheHudBoxIsDrawnWhereTheLayoutSays) {
  const Snapshot s = preset_snapshot("spinning_rigid_plane", 1.0, false);
  for (const auto& [w, h] : {std::pair{640, 480}, {1280, 720}, {1920, 1080}}) {
    ViewOptions view;
    view.kind = ViewKind::plane;
    view.width = w;
    view.height = h;
    view.layers = kSurface | kHud;
    const FrameScene scene = build_scene(s, view);
    const std::vector<std::uint8_t> rgba = renderer().render_image(s, view).rgba;
    const PixelBox& box = scene.hud.hud;
    const Rgb plane = pixel(rgba.data(), view, {0.5 * w, 0.9 * h});
    const Rgb inside = pixel(rgba.data(), view, {box.x + box.w - 3, box.y + box.h - 3});
    const Rgb outside = pixel(rgba.data(), view, {box.x + box.w + 3, box.y + box.h + 3});
    EXPECT_NE(inside.r + inside.g + inside.b, plane.r + plane.g + plane.b) << w << "x" << h;
    EXPECT_EQ(outside.r + outside.g + outside.b, plane.r + plane.g + plane.b) << w << "x" << h;
    // The last line's glyphs reach into the box's last text line: dark pixels there.
    int dark = 0;
    for (double x = box.x; x < box.x + box.w; ++x)
      for (double y = box.y + box.h - scene.hud.padding - scene.hud.font_size; y < box.y + box.h; ++y) {
        const Rgb c = pixel(rgba.data(), view, {x, y});
        dark += c.r + c.g + c.b < 200;
      }
    EXPECT_GT(dark, 20 * scene.hud.scale * scene.hud.scale) << w << "x" << h;
  }
}

// A paced picture (drawn at a fraction of its shown size and scaled up by the page) keeps its HUD
// and legend, in fonts smaller than 1 in drawn pixels; at every scale such a picture asks for, the
// glyphs stay in their boxes: outside them (a strip right of the HUD, the legend's margin to the
// frame's edge) the frame is what it is with no overlay at all.
TEST(Renderer, PacedPicturesKeepTheirOverlayAndItsTextInItsBoxes) {
  std::set<double> scales;
  for (const char* preset : {"spin_vs_geodesic_sphere", "spin_vs_geodesic_torus"})
    for (const int shown : {700, 800, 900, 1066, 1280, 1600})
      for (const double pace : {1.0, 0.8, 0.64, 0.5}) {
        const Snapshot s = preset_snapshot(preset, 6.0, true);
        ViewOptions view = s.surface.kind == SurfaceKind::sphere ? looking_at(s, 0.0) : ViewOptions{};
        view.kind = default_view(s.surface.kind);
        view.width = static_cast<int>(std::lround(shown * pace));
        view.height = static_cast<int>(std::lround(0.75 * view.width));
        view.shown_width = shown;
        view.layers = kSurface | kBody | kTrail | kHud;
        const std::string at =
            std::string(preset) + " " + std::to_string(shown) + " at " + std::to_string(pace);
        const FrameScene scene = build_scene(s, view);
        ASSERT_FALSE(compact_overlay(view)) << at;
        ASSERT_FALSE(scene.legend.empty()) << at;
        scales.insert(scene.hud.scale);
        const std::vector<std::uint8_t> drawn = renderer().render_image(s, view).rgba;
        ViewOptions bare = view;
        bare.layers &= ~kHud;
        const std::vector<std::uint8_t> plain = renderer().render_image(s, bare).rgba;
        const auto same = [&](double x0, double x1, double y0, double y1) {
          int differ = 0;
          for (int y = static_cast<int>(y0); y < static_cast<int>(y1); ++y)
            for (int x = static_cast<int>(x0); x < static_cast<int>(x1); ++x) {
              const std::size_t i = 4 * (static_cast<std::size_t>(y) * view.width + x);
              differ += std::memcmp(&drawn[i], &plain[i], 3) != 0;
            }
          return differ;
        };
        const PixelBox &hud = scene.hud.hud, &legend = scene.hud.legend;
        EXPECT_EQ(same(hud.x + hud.w + 1, std::min(hud.x + hud.w + 8, legend.x - 1), hud.y, hud.y + hud.h), 0)
            << at << ": text right of the HUD's box";
        // No line is cut at the box's edge (ImGui clips to the box): the glyphs end a padding short.
        for (const bool of_hud : {true, false}) {
          const PixelBox& box = of_hud ? hud : legend;
          const PixelBox& other = of_hud ? legend : hud;  // (the legend overlaps the HUD's corner)
          int rightmost = -1;
          // Inside the box's border.
          for (int y = static_cast<int>(box.y) + 2; y < static_cast<int>(box.y + box.h) - 2; ++y)
            for (int x = static_cast<int>(box.x) + 2; x < static_cast<int>(box.x + box.w) - 1; ++x) {
              if (x >= other.x - 1 && x <= other.x + other.w + 1 && y >= other.y - 1 &&
                  y <= other.y + other.h + 1)
                continue;
              const Rgb c = pixel(drawn.data(), view, {static_cast<double>(x), static_cast<double>(y)});
              if (c.r + c.g + c.b < 350) rightmost = std::max(rightmost, x);
            }
          EXPECT_GE(rightmost, 0) << at;
          EXPECT_LE(rightmost, box.x + box.w - scene.hud.padding)
              << at << " (scale " << scene.hud.scale << "): a line cut at the box " << box.x << "+" << box.w;
        }
        EXPECT_EQ(same(legend.x + legend.w + 1, view.width, legend.y, legend.y + legend.h), 0)
            << at << ": text right of the legend's box";
        EXPECT_EQ(same(hud.x, hud.x + hud.w, hud.y + hud.h + 1, hud.y + hud.h + 4), 0)
            << at << ": below the HUD";
      }
  // Every font below 1 was tried (the paces of those four shown sizes reach each).
  for (const double scale : kHudScales)
    if (scale < 1.0) {
      EXPECT_EQ(scales.count(scale), 1u) << scale << " (" << scales.size() << " scales tried)";
    }
}

TEST(Renderer, SameSnapshotViewAndSizeGiveTheSameBytes) {
  const Snapshot s = preset_snapshot("spinning_rigid_sphere", 3.0, true);
  const ViewOptions view = looking_at(s, 0.0);
  EXPECT_EQ(renderer().render_png(s, view), renderer().render_png(s, view));
}

// Exact bytes within one machine (the golden frames allow other CPUs' jitter): a run advanced in
// many small steps through a parameter change and its replay from the timeline give the same PNG.
TEST(Renderer, AReplayedRunGivesTheLiveRunsBytes) {
  Scene scene = *parse_scene_text(find_preset("spin_vs_geodesic_sphere")->json).scene;
  scene.integrator.name = "dop853";  // adaptive steps, which the advance pattern could move
  Scene changed = scene;
  changed.body.inertia *= 1.5;
  const std::vector<ParameterChange> changes{{1.3, changed}};
  Simulation live = start_simulation(scene);
  Trail live_trail;
  live_trail.spacing = 3.0 / 64;
  for (double t = 0.05; t < 1.3; t += 0.05) advance_sampling_trail(live, live_trail, t);
  advance_sampling_trail(live, live_trail, 1.3);
  retune_carrying_trail(live, live_trail, changed);
  for (double t = 1.37; t < 3.0; t += 0.07) advance_sampling_trail(live, live_trail, t);
  advance_sampling_trail(live, live_trail, 3.0);
  Simulation rebuilt;
  Trail rebuilt_trail;
  rebuilt_trail.spacing = live_trail.spacing;
  ASSERT_TRUE(replay(scene, changes, 3.0, rebuilt, rebuilt_trail));
  ViewOptions view;
  const Snapshot a = make_snapshot(live, live_trail, -1.0), b = make_snapshot(rebuilt, rebuilt_trail, -1.0);
  aim_camera_at_body(view, a);
  const std::vector<std::uint8_t> png = renderer().render_png(a, view);
  EXPECT_EQ(png, renderer().render_png(b, view));
  EXPECT_EQ(png, renderer().render_png(a, view));  // and the same snapshot twice
}

// The preset's scene moved onto another surface (the same initial state), run to t with its trail.
Snapshot on_surface(std::string_view preset, const Surface& surface, double t) {
  Scene scene = *parse_scene_text(find_preset(preset)->json).scene;
  scene.surface = surface;
  Simulation run = start_simulation(scene);
  Trail trail;
  trail.spacing = t / 64;
  advance_sampling_trail(run, trail, t);
  return make_snapshot(run, trail, -1.0);
}

// The pixels in which two frames of one size differ.
int differing_pixels(const Image& a, const Image& b) {
  int n = 0;
  for (std::size_t i = 0; i < a.rgba.size(); i += 4) n += std::memcmp(&a.rgba[i], &b.rgba[i], 4) != 0;
  return n;
}

TEST(Renderer, TheConformalFrameIsContinuousInTheCurvatureAndChangesWithIt) {
  // The plane's preset on the plane, on a sphere and H² of radius 1e6 (K = ±1e-12) and of radius
  // 1 (K = ±1); no HUD, whose text names the surface. Measured: the three near K = 0 are
  // byte-identical; at K = ±1 over a third of the pixels differ from the plane's.
  const auto frame = [](const Surface& surface) {
    const Snapshot s = on_surface("spinning_rigid_plane", surface, 3.0);
    ViewOptions view;
    view.kind = ViewKind::conformal;
    view.layers = kDefaultLayers & ~unsigned{kHud};
    aim_camera_at_body(view, s);
    return renderer().render_image(s, view);
  };
  const Image flat = frame({SurfaceKind::plane, 1.0});
  const int pixels = flat.width * flat.height;
  EXPECT_LE(differing_pixels(flat, frame({SurfaceKind::sphere, 1e6})), 0);
  EXPECT_LE(differing_pixels(flat, frame({SurfaceKind::pseudosphere, 1e6})), 0);
  EXPECT_GT(differing_pixels(flat, frame({SurfaceKind::sphere, 1.0})), pixels / 10);
  EXPECT_GT(differing_pixels(flat, frame({SurfaceKind::pseudosphere, 1.0})), pixels / 10);
}

// The framing test (tests/render/views/camera_test.cpp) from the pixels: every preset in every view
// it offers at t = 5, at the picture of a 1366-wide page, rendered with and without the bodies
// (the same camera): round each body's centre that the framing test places in the frame, the
// picture changes — the body is painted there, over the surface, through it as a ghost, under
// nothing else.
TEST(Renderer, EveryPresetsBodiesArePaintedWhereTheCameraPutsThem) {
  int checked = 0;
  for (const PresetSource& preset : preset_sources()) {
    const Snapshot s = preset_snapshot(preset.name, 5.0, true);
    for (const ViewRow& row : view_table()) {
      if (!shows(row.info, s.surface.kind)) continue;
      const ViewOptions view = testing::aimed_view(row.info.kind, 795, 515, s);
      ViewOptions bare = view;
      bare.layers &= ~static_cast<unsigned>(kBody | kFrame);
      const FrameScene scene = build_scene(s, view);
      const std::vector<std::uint8_t> with = renderer().render_image(s, view).rgba;
      const std::vector<std::uint8_t> without = renderer().render_image(s, bare).rgba;
      const ViewModel& model = row.model();
      for (std::size_t b = 0; b < s.bodies.size(); ++b) {
        const Vec3& X = s.bodies[b].X;
        if (!model.draws(s.surface, X) ||
            (b > 0 && !(model.on_view(s.surface, X) && model.on_view(s.surface, s.bodies[0].X))))
          continue;  // as the framing test: beyond the drawn piece
        const std::optional<glm::dvec2> px = pixel_position(scene, view, model.world_position(s.surface, X));
        if (!px || px->x < 3 || px->y < 3 || px->x > view.width - 4 || px->y > view.height - 4) continue;
        int most = 0;  // the largest change of a channel round the centre [levels]
        for (int dy = -2; dy <= 2; ++dy)
          for (int dx = -2; dx <= 2; ++dx) {
            const std::size_t at =
                (static_cast<std::size_t>(px->y + dy) * view.width + static_cast<std::size_t>(px->x + dx)) *
                4;
            for (int c = 0; c < 3; ++c) most = std::max(most, std::abs(with[at + c] - without[at + c]));
          }
        ++checked;
        EXPECT_GT(most, 20) << preset.name << " " << row.info.name << " body " << b + 1;
      }
    }
  }
  EXPECT_GT(checked, 60);
}

struct Golden {
  const char* name;
  const char* preset;
  ViewKind view;
  double t = 3.0;    // [time]
  int width = 640;   // [pixels]
  int height = 480;  // [pixels]
  unsigned layers = kDefaultLayers;
};

class GoldenFrame : public ::testing::TestWithParam<Golden> {};

TEST_P(GoldenFrame, MatchesThePinnedPng) {
  const Golden g = GetParam();
  const Snapshot s = preset_snapshot(g.preset, g.t, true);
  ViewOptions view;
  view.kind = g.view;
  view.width = g.width;
  view.height = g.height;
  view.layers = g.layers;
  aim_camera_at_body(view, s);
  const std::vector<std::uint8_t> png = renderer().render_png(s, view);
  // Within llvmpipe's jitter across CPUs, not byte for byte: the bytes are pinned on one machine
  // (SameSnapshotViewAndSizeGiveTheSameBytes and the replay test check bytes within one).
  const std::string why =
      test::golden_mismatch(png, std::filesystem::path(SPINFOLD_GOLDEN_DIR) / (std::string(g.name) + ".png"),
                            std::filesystem::path(SPINFOLD_ACTUAL_DIR) / (std::string(g.name) + ".png"));
  EXPECT_TRUE(why.empty()) << why;
}

INSTANTIATE_TEST_SUITE_P(
    Views, GoldenFrame,
    ::testing::Values(Golden{"sphere", "spinning_rigid_sphere", ViewKind::sphere},
                      Golden{"hyperboloid", "spinning_rigid_pseudosphere", ViewKind::hyperboloid},
                      Golden{"disk", "spinning_rigid_pseudosphere", ViewKind::disk},
                      Golden{"stereographic", "breathing_ellipse_sphere", ViewKind::disk},
                      Golden{"plane", "spinning_rigid_plane", ViewKind::plane},
                      Golden{"spin_vs_geodesic_sphere", "spin_vs_geodesic_sphere", ViewKind::sphere, 2.0},
                      // A thumbnail (1 px lines) and a projector-sized frame (3.4 px lines).
                      Golden{"sphere_thumbnail", "spin_vs_geodesic_sphere", ViewKind::sphere, 2.0, 160, 120,
                             kDefaultLayers & ~unsigned{kHud}},
                      Golden{"sphere_1080p", "spin_vs_geodesic_sphere", ViewKind::sphere, 2.0, 1920, 1080},
                      // The other pictures of H².
                      Golden{"klein", "spin_vs_geodesic_pseudosphere", ViewKind::klein, 6.0},
                      Golden{"halfplane", "spin_vs_geodesic_pseudosphere", ViewKind::halfplane, 6.0},
                      Golden{"tractricoid", "spin_vs_geodesic_pseudosphere", ViewKind::tractricoid, 6.0},
                      // One flat map for every curvature.
                      Golden{"conformal_sphere", "spin_vs_geodesic_sphere", ViewKind::conformal, 2.0},
                      Golden{"conformal_pseudosphere", "spin_vs_geodesic_pseudosphere", ViewKind::conformal,
                             6.0},
                      // Where the curvature varies: the torus with the curvature layer, the bump without.
                      Golden{"revolution_torus", "spin_vs_geodesic_torus", ViewKind::revolution, 12.0, 640,
                             480, kDefaultLayers | kCurvature},
                      Golden{"revolution_bump", "trapped_spin_bump", ViewKind::revolution, 20.0},
                      Golden{"chart_torus", "spin_vs_geodesic_torus", ViewKind::chart, 16.0}),
    [](const auto& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace spinfold::render
