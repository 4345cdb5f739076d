// The renderer through OSMesa: pixels where the geometry says, the far side hidden, the HUD only
// when asked, identical bytes for identical input, and a golden PNG per view.
#include "render/renderer.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "engine/chart.h"
#include "render/snapshot.h"

namespace spinfold::render {
namespace {

Renderer& renderer() {
  static Renderer r;  // one context for the whole test binary (one thread)
  return r;
}

Snapshot preset_snapshot(std::string_view name, double t, bool with_trail) {
  const Scene scene = *parse_scene_text(find_preset(name)->json).scene;
  Simulation run = start_simulation(scene);
  std::vector<Vec3> trail;
  for (int k = 0; k <= 64; ++k) {
    advance_to(run, t * k / 64);
    if (with_trail) trail.push_back(global_embedding(scene, run.state).X);
  }
  return make_snapshot(run, std::move(trail));
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
glm::dvec3 inside_ellipse(const Snapshot& s, ViewKind view) {
  const Vec3 P = s.X + 0.4 * 0.25 * (-std::sqrt(0.5) * s.e[0] - std::sqrt(0.5) * s.e[1]);
  return world_position(s.surface, view, P * (s.surface.radius / P.norm()));
}

ViewOptions looking_at(const Snapshot& s, double yaw_offset) {
  ViewOptions view;
  const Vec3 n = s.X.normalized();
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

TEST(Renderer, SameSnapshotViewAndSizeGiveTheSameBytes) {
  const Snapshot s = preset_snapshot("spinning_rigid_sphere", 3.0, true);
  const ViewOptions view = looking_at(s, 0.0);
  EXPECT_EQ(renderer().render_png(s, view), renderer().render_png(s, view));
}

// FNV-1a, 64 bit.
std::uint64_t hash_of(const std::vector<std::uint8_t>& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint8_t b : bytes) h = (h ^ b) * 1099511628211ull;
  return h;
}

std::vector<std::uint8_t> read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Golden {
  const char* name;
  const char* preset;
  ViewKind view;
};

class GoldenFrame : public ::testing::TestWithParam<Golden> {};

TEST_P(GoldenFrame, MatchesThePinnedPng) {
  const Golden g = GetParam();
  const Snapshot s = preset_snapshot(g.preset, 3.0, true);
  ViewOptions view;
  view.kind = g.view;
  aim_camera_at_body(view, s);
  const std::vector<std::uint8_t> png = renderer().render_png(s, view);
  const std::filesystem::path golden =
      std::filesystem::path(SPINFOLD_GOLDEN_DIR) / (std::string(g.name) + ".png");
  const std::filesystem::path actual =
      std::filesystem::path(SPINFOLD_ACTUAL_DIR) / (std::string(g.name) + ".png");
  std::filesystem::create_directories(actual.parent_path());
  std::ofstream(actual, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), png.size());
  ASSERT_TRUE(std::filesystem::exists(golden)) << "no golden frame; look at " << actual << " and pin it";
  EXPECT_EQ(hash_of(png), hash_of(read_file(golden)))
      << "frame differs from " << golden << "; see " << actual;
}

INSTANTIATE_TEST_SUITE_P(
    Views, GoldenFrame,
    ::testing::Values(Golden{"sphere", "spinning_rigid_sphere", ViewKind::sphere},
                      Golden{"hyperboloid", "spinning_rigid_pseudosphere", ViewKind::hyperboloid},
                      Golden{"disk", "spinning_rigid_pseudosphere", ViewKind::disk},
                      Golden{"stereographic", "breathing_ellipse_sphere", ViewKind::disk},
                      Golden{"plane", "spinning_rigid_plane", ViewKind::plane}),
    [](const auto& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace spinfold::render
