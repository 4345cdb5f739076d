// Each GL backend this build has (EGL, OSMesa): it makes a context, names itself and its
// GL_RENDERER, and draws the frames the other one draws, within the golden frames' tolerance.
#include <gtest/gtest.h>

#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "render/gl_context.h"
#include "render/renderer.h"
#include "render/snapshot.h"
#include "tests/render/frame_compare.h"

namespace spinfold::render {
namespace {

std::vector<GlBackend> compiled_backends() {
  std::vector<GlBackend> backends;
#ifdef SPINFOLD_HAVE_EGL
  backends.push_back(GlBackend::egl);
#endif
#ifdef SPINFOLD_HAVE_OSMESA
  backends.push_back(GlBackend::osmesa);
#endif
  return backends;
}

struct Drawn {
  std::string name, renderer, error;
  std::vector<std::vector<std::uint8_t>> pngs;  // one per view below
};

struct ViewCase {
  const char* preset;
  ViewKind view;
  double t;
  int width, height;
};
// A lit 3-D view with the HUD, an H² view with wide lines, and a thumbnail of 1 px lines.
const ViewCase kViews[] = {{"spin_vs_geodesic_sphere", ViewKind::sphere, 2.0, 640, 480},
                           {"spin_vs_geodesic_pseudosphere", ViewKind::klein, 6.0, 800, 600},
                           {"spinning_rigid_plane", ViewKind::plane, 3.0, 160, 120}};

// On a thread of its own, as a render thread: one context per thread.
Drawn draw_with(GlBackend backend) {
  Drawn drawn;
  std::thread worker([&] {
    try {
      Renderer renderer(backend);
      drawn.name = renderer.context().name();
      drawn.renderer = renderer.context().renderer();
      for (const ViewCase& c : kViews) {
        Simulation run;
        const Snapshot s =
            snapshot_at(*parse_scene_text(find_preset(c.preset)->json).scene, c.t, true, std::nullopt, run);
        ViewOptions view;
        view.kind = c.view;
        view.width = c.width;
        view.height = c.height;
        aim_camera_at_body(view, s);
        drawn.pngs.push_back(renderer.render_png(s, view));
      }
    } catch (const std::exception& e) {
      drawn.error = e.what();
    }
  });
  worker.join();
  return drawn;
}

TEST(GlBackends, EachMakesAContextAndNamesItsRenderer) {
  for (const GlBackend backend : compiled_backends()) {
    const Drawn d = draw_with(backend);
    ASSERT_TRUE(d.error.empty()) << gl_backend_name(backend) << ": " << d.error;
    EXPECT_TRUE(d.name.starts_with(gl_backend_name(backend))) << d.name;
    EXPECT_FALSE(d.renderer.empty());
    std::printf("%s: %s\n", d.name.c_str(), d.renderer.c_str());
  }
}

TEST(GlBackends, DrawTheSameFramesWithinTheGoldenTolerance) {
  const std::vector<GlBackend> backends = compiled_backends();
  if (backends.size() < 2) GTEST_SKIP() << "one backend in this build: " << compiled_gl_backends();
  const Drawn egl = draw_with(backends[0]), osmesa = draw_with(backends[1]);
  ASSERT_TRUE(egl.error.empty()) << egl.error;
  ASSERT_TRUE(osmesa.error.empty()) << osmesa.error;
  const test::FrameTolerance tolerance;
  for (std::size_t i = 0; i < std::size(kViews); ++i) {
    const auto a = test::decode_png(egl.pngs[i]), b = test::decode_png(osmesa.pngs[i]);
    ASSERT_TRUE(a && b);
    const test::FrameDifference d = test::compare_frames(*b, *a, tolerance);
    // Printed: the measured difference (docs/performance.md, "GL backends").
    std::printf("%s %s vs %s: %s\n", kViews[i].preset, egl.name.c_str(), osmesa.name.c_str(),
                test::describe(d, tolerance).c_str());
    EXPECT_TRUE(test::within(d, tolerance)) << kViews[i].preset << ": " << test::describe(d, tolerance);
  }
}

TEST(GlBackends, SettingNamesParseAndOthersDoNot) {
  EXPECT_EQ(parse_gl_backend("auto"), GlBackend::automatic);
  EXPECT_EQ(parse_gl_backend("egl"), GlBackend::egl);
  EXPECT_EQ(parse_gl_backend("osmesa"), GlBackend::osmesa);
  EXPECT_FALSE(parse_gl_backend("nonsense"));
  EXPECT_FALSE(parse_gl_backend("EGL"));
  EXPECT_FALSE(compiled_gl_backends().empty());
}

}  // namespace
}  // namespace spinfold::render
