#include "bench/render_bench.h"

#include <turbojpeg.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "bench/bare_render_loop.h"
#include "codec/presets.h"
#include "codec/scene_json.h"
#include "engine/chart.h"
#include "engine/formula_examples.h"
#include "engine/simulation.h"
#include "engine/surface_model.h"
#include "render/gl_context.h"
#include "render/gl_renderer.h"
#include "render/implicit_mesh.h"
#include "render/jpeg_encoder.h"
#include "render/overlay.h"
#include "render/png_encoder.h"
#include "render/renderer.h"

namespace spinfold::bench {

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

// A deforming, spinning body on the sphere with a trail of `trail_points` positions over 20 time
// units per 512 points (513 points: the CLI's default; 10,001: a session played for minutes).
render::Snapshot bench_snapshot(int trail_points = 513) {
  Scene scene;
  scene.surface = {SurfaceKind::sphere, 1.0};
  scene.body = {1.0, 0.2, BodyModel::affine};
  scene.potential.deformation = AbcPotential{0.0, 0.0, 0.5};
  scene.initial = {1.2, 0.0, 0.2, 0.0, 1.3, 0.7, 0.0, 0.3, 0.8, 0.0, 0.0, 0.0};
  Simulation run = start_simulation(scene);
  Trail trail;
  trail.spacing = 20.0 / 512;
  trail.max_points = static_cast<std::size_t>(trail_points);
  advance_sampling_trail(run, trail, 20.0 * (trail_points - 1) / 512);
  return render::make_snapshot(run, trail, -1.0);
}

// The spin fan of spin_fan_sphere with `companions` companions (spins 0.25, 0.5, …), run to t = 20
// with every body's trail sampled 512 times.
struct FanRun {
  Simulation run;
  Trail trail;
};
FanRun fan_run(int companions) {
  std::string values;
  for (int i = 1; i <= companions; ++i) {
    if (i > 1) values += ',';
    values += std::to_string(0.25 * i);
  }
  std::string text = R"({"surface": {"kind": "sphere", "radius": 1.0},
    "body": {"mass": 1.0, "inertia": 0.5, "model": "rigid"},
    "initial": {"r": 1.0, "lambda": 1.0, "mu": 1.0, "speed": 0.5, "heading": 1.5707963267948966, "spin": 0.0})";
  if (companions > 0) {
    text += R"(, "vary": {"field": "initial.spin", "values": [)";
    text += values;
    text += "]}";
  }
  text += '}';
  FanRun fan{start_simulation(*parse_scene_text(text).scene), Trail{}};
  fan.trail.spacing = 20.0 / 512;
  advance_sampling_trail(fan.run, fan.trail, 20.0);
  return fan;
}

// The decoded JPEG against the RGBA frame it was made from (RGB channels).
struct JpegError {
  double psnr_db = 0.0;
  double mean_abs = 0.0;  // [0, 255]
};

JpegError jpeg_error(const std::vector<std::uint8_t>& jpeg, const std::vector<std::uint8_t>& rgba, int width,
                     int height) {
  tjhandle handle = tjInitDecompress();
  std::vector<std::uint8_t> decoded(static_cast<std::size_t>(width) * height * 4);
  tjDecompress2(handle, jpeg.data(), jpeg.size(), decoded.data(), width, 0, height, TJPF_RGBX,
                TJFLAG_ACCURATEDCT);
  tjDestroy(handle);
  double squared = 0.0, absolute = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < decoded.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = static_cast<double>(decoded[i]) - static_cast<double>(rgba[i]);
    squared += d * d;
    absolute += std::abs(d);
    ++n;
  }
  const double mse = squared / static_cast<double>(n);
  return {10.0 * std::log10(255.0 * 255.0 / std::max(mse, 1e-12)), absolute / static_cast<double>(n)};
}

// Snapshots of a preset's run at t0, t0 + dt, …: the body moves from one to the next (trail kept).
std::vector<render::Snapshot> moving_snapshots(std::string_view preset, double t0, double dt, int count) {
  Simulation run = start_simulation(*parse_scene_text(find_preset(preset)->json).scene);
  Trail trail;
  trail.spacing = t0 / 64;
  std::vector<render::Snapshot> out;
  for (int i = 0; i < count; ++i) {
    advance_sampling_trail(run, trail, t0 + dt * i);
    out.push_back(render::make_snapshot(run, trail, -1.0));
  }
  return out;
}

// One GL renderer with its options in a shared context, drawing what render::Renderer draws
// (scene, HUD, glFinish) without encoding.
struct GlUnderTest {
  render::GlRenderer gl;
  render::HudOverlay& hud;
  double render_ms(render::GlContext& context, const render::FrameScene& scene, int w, int h) {
    const auto t = std::chrono::steady_clock::now();
    context.make_current(w, h);
    gl.draw(scene, w, h);
    if (!scene.hud_lines.empty() || !scene.legend.empty())
      hud.draw(scene.hud_lines, scene.legend, scene.hud, w, h);
    gl.finish();
    return ms_since(t);
  }
};

// Anti-aliasing and the cached background (gl_renderer.h): each pair of variants measured
// interleaved, frame by frame, in one context, so that the machine's drift falls on both.
void anti_aliasing_and_cache_tables(int frames) {
  const std::unique_ptr<render::GlContext> owned_context = render::make_gl_context();
  render::GlContext& context = *owned_context;
  render::HudOverlay hud;
  using Options = render::GlRenderer::Options;
  Options aliased;  // the previous renderer: one sample, 1 px lines, nothing cached
  aliased.samples = 1;
  aliased.smooth_lines = false;
  aliased.wide_lines = false;
  aliased.cache_background = false;
  Options smooth;  // the default without the cache: coverage-blended lines and outline
  smooth.cache_background = false;
  Options msaa = smooth;  // 4 samples, resolved
  msaa.samples = 4;
  Options cached;  // the default
  GlUnderTest a{render::GlRenderer(aliased), hud};
  GlUnderTest b{render::GlRenderer(smooth), hud};
  GlUnderTest m{render::GlRenderer(msaa), hud};
  GlUnderTest c{render::GlRenderer(cached), hud};
  const int n = frames + 2;
  const std::vector<render::Snapshot> sphere = moving_snapshots("spinning_rigid_sphere", 3.0, 0.02, n);
  const std::vector<render::Snapshot> disk = moving_snapshots("spinning_rigid_pseudosphere", 3.0, 0.02, n);
  struct Row {
    const char* name;
    const std::vector<render::Snapshot>* snapshots;
    render::ViewKind kind;
    bool aim;  // the camera follows the body: a new view_projection every frame
  };
  // Two variants measured interleaved over frames that differ in the body's position only (and
  // the camera, when it follows the body): medians [ms].
  const auto pair = [&](const Row& row, int w, int h, GlUnderTest& x, GlUnderTest& y) {
    std::vector<double> tx, ty;
    for (int f = 0; f < n; ++f) {
      const render::Snapshot& s = (*row.snapshots)[f];
      render::ViewOptions view;
      view.kind = row.kind;
      view.width = w;
      view.height = h;
      if (row.aim) render::aim_camera_at_body(view, s);
      const render::FrameScene scene = render::build_scene(s, view);
      const double mx = x.render_ms(context, scene, w, h), my = y.render_ms(context, scene, w, h);
      if (f >= 2) tx.push_back(mx), ty.push_back(my);
    }
    return std::pair{median(tx), median(ty)};
  };
  const Row sphere_aimed{"sphere, camera on the body", &sphere, render::ViewKind::sphere, true};
  const Row sphere_fixed{"sphere, explicit camera", &sphere, render::ViewKind::sphere, false};
  const Row disk_fixed{"disk (Poincaré)", &disk, render::ViewKind::disk, false};
  // Each ratio against the aliased frames measured interleaved with it.
  std::printf(
      "| size | view | aliased ms (1 px) | smooth ms (cache off) | smooth / aliased | default ms (smooth, "
      "cache on) | default / aliased | 4x MSAA ms (cache off) | MSAA / aliased |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (const auto& [w, h] : {std::pair{640, 480}, std::pair{1280, 720}, std::pair{1920, 1080}})
    for (const Row* row : {&sphere_aimed, &disk_fixed}) {
      const auto [a1, sm] = pair(*row, w, h, a, b);
      const auto [a2, df] = pair(*row, w, h, a, c);
      const auto [a3, ms] = pair(*row, w, h, a, m);
      std::printf("| %dx%d | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", w, h, row->name, a1,
                  sm, sm / a1, df, df / a2, ms, ms / a3);
    }
  std::printf(
      "\n| size | view | full frame ms (cache off) | body-only frame ms (cached background) | cached / full "
      "| "
      "cache hits, fills, misses |\n| --- | --- | --- | --- | --- | --- |\n");
  for (const auto& [w, h] : {std::pair{640, 480}, std::pair{1280, 720}})
    for (const Row* row : {&sphere_fixed, &disk_fixed, &sphere_aimed}) {
      const render::GlRenderer::CacheStats before = c.gl.cache_stats();
      const auto [mb, mc] = pair(*row, w, h, b, c);
      const render::GlRenderer::CacheStats after = c.gl.cache_stats();
      std::printf("| %dx%d | %s | %.2f | %.2f | %.2f | %d, %d, %d |\n", w, h, row->name, mb, mc, mc / mb,
                  after.hits - before.hits, after.fills - before.fills, after.misses - before.misses);
    }
  // Where the curvature varies: the torus's revolution view against the sphere view, each frame
  // aimed, built (the ellipse through the implicit surface's exponential map) and drawn with the
  // default renderer, interleaved frame by frame. Issue 33's target: torus / sphere ≤ 1.5.
  const std::vector<render::Snapshot> torus = moving_snapshots("spin_vs_geodesic_torus", 3.0, 0.02, n);
  std::printf(
      "\n| size | sphere frame ms (aim + build + draw) | torus frame ms (revolution view) | torus / sphere "
      "|\n"
      "| --- | --- | --- | --- |\n");
  // A frame as the server makes it: aimed, built and drawn [ms: aim, build, draw, all], and its
  // surface's triangles.
  const auto aimed_frame = [&](const render::Snapshot& s, render::ViewKind kind, int w, int h,
                               std::size_t* triangles = nullptr) {
    const auto t = std::chrono::steady_clock::now();
    render::ViewOptions view;
    view.kind = kind;
    view.width = w;
    view.height = h;
    view.scale *= render::body_scale_length(kind, s.surface);
    render::aim_camera_at_body(view, s);
    const double aimed = ms_since(t);
    const render::FrameScene scene = render::build_scene(s, view);
    const double built = ms_since(t);
    c.render_ms(context, scene, w, h);
    const double all = ms_since(t);
    if (triangles) *triangles = scene.statics ? scene.statics->surface.size() / 3 : 0;
    return std::array<double, 4>{aimed, built - aimed, all - built, all};
  };
  for (const auto& [w, h] : {std::pair{640, 480}, std::pair{1280, 720}}) {
    std::vector<double> ts, tt;
    for (int f = 0; f < n; ++f) {
      const double ms = aimed_frame(sphere[f], render::ViewKind::sphere, w, h)[3];
      const double mt = aimed_frame(torus[f], render::ViewKind::revolution, w, h)[3];
      if (f >= 2) ts.push_back(ms), tt.push_back(mt);
    }
    std::printf("| %dx%d | %.2f | %.2f | %.2f |\n", w, h, median(ts), median(tt), median(tt) / median(ts));
  }
  // A surface given by a formula: the same torus written as F = 0 (the same bodies at the same
  // places) in the formula view against the built-in torus in the revolution view, each frame aimed,
  // built and drawn, interleaved. Issue 49's target: formula / built-in ≤ 1.5. The mesh is cached
  // (its first build is timed below).
  std::vector<render::Snapshot> formula_torus = torus;
  for (render::Snapshot& s : formula_torus) {
    s.surface.kind = SurfaceKind::implicit;
    s.surface.F = "(x^2 + y^2 + z^2 + c^2 - a^2)^2 - 4*c^2*(x^2 + y^2)";
    s.surface.parameters = {{"a", 1.0}, {"c", 2.5}};
    s.model = surface_model_of(s.surface);
  }
  std::printf(
      "| size | torus frame ms (revolution view: aim, build, draw) | formula torus frame ms (formula view: "
      "aim, "
      "build, draw) | formula / built-in | triangles, built-in and formula |\n"
      "| --- | --- | --- | --- | --- |\n");
  for (const auto& [w, h] : {std::pair{640, 480}, std::pair{1280, 720}}) {
    struct Parts {
      std::vector<double> aim, build, draw, all;
      std::size_t triangles = 0;
    } pb, pf;
    for (int f = 0; f < n; ++f) {
      const auto mb = aimed_frame(torus[f], render::ViewKind::revolution, w, h, &pb.triangles);
      const auto mf = aimed_frame(formula_torus[f], render::ViewKind::formula, w, h, &pf.triangles);
      if (f < 2) continue;
      for (auto [parts, ms] : {std::pair{&pb, mb}, std::pair{&pf, mf}})
        parts->aim.push_back(ms[0]), parts->build.push_back(ms[1]), parts->draw.push_back(ms[2]),
            parts->all.push_back(ms[3]);
    }
    std::printf("| %dx%d | %.2f (%.2f, %.2f, %.2f) | %.2f (%.2f, %.2f, %.2f) | %.2f | %zu, %zu |\n", w, h,
                median(pb.all), median(pb.aim), median(pb.build), median(pb.draw), median(pf.all),
                median(pf.aim), median(pf.build), median(pf.draw), median(pf.all) / median(pb.all),
                pb.triangles, pf.triangles);
  }
  // Meshing each example surface at the default resolution (render/implicit_mesh.h), and the whole
  // static geometry (mesh, grid, K = 0 curves, edges) of its view: the first frame's extra cost.
  // Issue 49's target: ≤ 300 ms.
  std::printf(
      "\n| example | mesh ms (72 cubes a side) | triangles | a new shape ms (box search, then the view's "
      "mesh, "
      "grid, edges) |\n| --- | --- | --- | --- |\n");
  for (const FormulaExample& example : formula_examples()) {
    const Surface surface = example_surface(example);
    const std::shared_ptr<const SurfaceModel> shape = surface_model_of(surface);
    std::size_t triangles = 0;
    std::vector<double> mesh_ms;
    for (int k = 0; k < 3; ++k) {
      const auto t = std::chrono::steady_clock::now();
      triangles = render::mesh_implicit_surface(*shape, shape->box).triangles.size();
      mesh_ms.push_back(ms_since(t));
    }
    // A new parameter value each time, so that the cache misses.
    std::vector<double> static_ms;
    for (int k = 0; k < 3; ++k) {
      Surface fresh = surface;
      fresh.bounds = SurfaceBounds{};
      for (int i = 0; i < 3; ++i) (*fresh.bounds)[i] = {shape->box[i][0] - 1e-6 * (k + 1), shape->box[i][1]};
      const auto t = std::chrono::steady_clock::now();
      (void)render::static_geometry(fresh, render::ViewKind::formula);
      static_ms.push_back(ms_since(t));
    }
    std::printf("| %s | %.1f | %zu | %.1f |\n", std::string(example.title).c_str(), median(mesh_ms),
                triangles, median(static_ms));
  }
  std::printf("\n");
}

}  // namespace

int run_render_bench(int frames) {
  anti_aliasing_and_cache_tables(frames);
  const render::Snapshot snapshot = bench_snapshot();
  render::Renderer renderer;
  struct Size {
    int w, h;
  };
  struct LayerSet {
    const char* name;
    unsigned layers;
  };
  const Size sizes[] = {{640, 480}, {1024, 768}, {1920, 1080}};
  const LayerSet sets[] = {
      {"all layers", render::kDefaultLayers},
      {"no trail, no HUD", render::kSurface | render::kGrid | render::kBody | render::kFrame},
      {"body only", render::kBody},
      {"surface only", render::kSurface},
      {"no layers (clear + encode)", 0u}};
  std::printf(
      "| size | layers | triangles | segments | build ms | render ms | encode ms | frame ms | bare render ms "
      "| "
      "bare encode ms | frame / bare |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- "
      "|\n");
  for (const Size& size : sizes) {
    for (const LayerSet& set : sets) {
      render::ViewOptions view;
      view.width = size.w;
      view.height = size.h;
      view.layers = set.layers;
      render::aim_camera_at_body(view, snapshot);
      std::vector<double> build, draw, encode;
      render::FrameScene scene;
      for (int f = 0; f < frames + 2; ++f) {
        auto t = std::chrono::steady_clock::now();
        scene = render::build_scene(snapshot, view);
        const double b = ms_since(t);
        t = std::chrono::steady_clock::now();
        const std::uint8_t* rgba = renderer.render_rgba(scene, view.width, view.height);
        const double d = ms_since(t);
        t = std::chrono::steady_clock::now();
        const std::vector<std::uint8_t> png = render::encode_png(rgba, view.width, view.height);
        const double e = ms_since(t);
        if (f >= 2) build.push_back(b), draw.push_back(d), encode.push_back(e);
      }
      const int triangles =
          static_cast<int>(((scene.statics && scene.draw_surface) ? scene.statics->surface.size() : 0) / 3 +
                           scene.fills.size() / 3);
      const int segments = static_cast<int>(
          ((scene.statics && scene.draw_grid) ? scene.statics->grid.size() : 0) / 2 + scene.lines.size() / 2);
      // The same pixels for the bare loop: vertices with their final colours (the surface's
      // per-vertex lighting computed here once, as lit.vert does).
      std::vector<float> opaque, translucent, lines;
      const auto put = [](std::vector<float>& out, const glm::vec3& p, const glm::vec4& c) {
        out.insert(out.end(), {p.x, p.y, p.z, c.r, c.g, c.b, c.a});
      };
      if (scene.statics && scene.draw_surface) {
        const glm::vec3 light =
            glm::normalize(glm::vec3(glm::inverse(scene.view_projection) * glm::vec4(0, 0, -1, 0)));
        for (const auto& v : scene.statics->surface) {
          const float shade = 0.35f + 0.65f * std::abs(glm::dot(v.normal, light));
          put(opaque, v.position, glm::vec4(glm::vec3(scene.surface_color) * shade, 1.0f));
        }
      }
      for (const auto& v : scene.fills) put(translucent, v.position, v.color);
      if (scene.statics && scene.draw_grid)
        for (const auto& v : scene.statics->grid) put(lines, v.position, v.color);
      for (const auto& v : scene.lines) put(lines, v.position, v.color);
#ifdef SPINFOLD_HAVE_OSMESA
      const BareTimings bare =
          bare_render_loop(size.w, size.h, opaque, translucent, lines, &scene.view_projection[0][0], frames);
#else  // the bare loop is OSMesa's: no baseline in a build without it
      const BareTimings bare{std::nan(""), std::nan("")};
#endif
      const double frame = median(build) + median(draw) + median(encode);
      std::printf("| %dx%d | %s | %d | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", size.w,
                  size.h, set.name, triangles, segments, median(build), median(draw), median(encode), frame,
                  bare.render_ms, bare.encode_ms, frame / (bare.render_ms + bare.encode_ms));
    }
  }
  // The default frame's RGBA pixels at a size (all layers, the camera aimed at the body).
  const auto rgba_frame = [&](const Size& size) {
    render::ViewOptions view;
    view.width = size.w;
    view.height = size.h;
    render::aim_camera_at_body(view, snapshot);
    const std::uint8_t* rgba =
        renderer.render_rgba(render::build_scene(snapshot, view), view.width, view.height);
    return std::vector<std::uint8_t>(rgba, rgba + static_cast<std::size_t>(size.w) * size.h * 4);
  };
  // The PNG encoder against libpng + zlib at the same level on the same frames, interleaved.
  std::printf(
      "\n| size | encode ms (libdeflate) | libpng ms | ratio | bytes | libpng bytes | ratio |\n"
      "| --- | --- | --- | --- | --- | --- | --- |\n");
  for (const Size& size : sizes) {
    const std::vector<std::uint8_t> frame = rgba_frame(size);
    std::vector<double> ours, theirs;
    std::size_t ours_bytes = 0, theirs_bytes = 0;
    for (int f = 0; f < frames + 2; ++f) {
      auto t = std::chrono::steady_clock::now();
      ours_bytes = render::encode_png(frame.data(), size.w, size.h).size();
      const double a = ms_since(t);
      t = std::chrono::steady_clock::now();
      theirs_bytes = bare_encode_png(frame.data(), size.w, size.h).size();
      const double b = ms_since(t);
      if (f >= 2) ours.push_back(a), theirs.push_back(b);
    }
    std::printf("| %dx%d | %.2f | %.2f | %.2f | %zu | %zu | %.2f |\n", size.w, size.h, median(ours),
                median(theirs), median(ours) / median(theirs), ours_bytes, theirs_bytes,
                static_cast<double>(ours_bytes) / static_cast<double>(theirs_bytes));
  }
  // JPEG for motion frames: bytes against the (lossless) PNG of the same frame and the error of
  // the decoded picture, per quality: the table render::kDefaultJpegQuality is chosen from.
  std::printf(
      "\n| size | quality | JPEG bytes | PNG bytes | JPEG / PNG | PSNR dB | mean abs error | encode ms |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (const Size& size : {sizes[0], sizes[1]}) {
    const std::vector<std::uint8_t> frame = rgba_frame(size);
    const std::size_t png_bytes = render::encode_png(frame.data(), size.w, size.h).size();
    for (const int quality : {50, 60, 70, 75, 80, 90}) {
      std::vector<double> times;
      std::vector<std::uint8_t> jpeg;
      for (int f = 0; f < frames + 2; ++f) {
        const auto t = std::chrono::steady_clock::now();
        jpeg = render::encode_jpeg(frame.data(), size.w, size.h, quality);
        if (f >= 2) times.push_back(ms_since(t));
      }
      const JpegError e = jpeg_error(jpeg, frame, size.w, size.h);
      std::printf("| %dx%d | %d | %zu | %zu | %.2f | %.1f | %.2f | %.2f |\n", size.w, size.h, quality,
                  jpeg.size(), png_bytes, static_cast<double>(jpeg.size()) / static_cast<double>(png_bytes),
                  e.psnr_db, e.mean_abs, median(times));
    }
  }
  // What the trail and the HUD cost, measured interleaved (one frame of each layer set in turn) so
  // that the machine's drift falls on all of them alike; also with a long trail, as a played
  // server session accumulates.
  std::printf(
      "\n| size | trail points | all layers ms | no trail ms | no HUD ms | no trail, no HUD ms | trail ms | "
      "HUD ms "
      "| all / no trail, no HUD |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  const render::Snapshot long_trail = bench_snapshot(10001);
  const unsigned without_trail = render::kDefaultLayers & ~unsigned{render::kTrail};
  const unsigned without_hud = render::kDefaultLayers & ~unsigned{render::kHud};
  const unsigned without_both = without_trail & without_hud;
  const unsigned interleaved[] = {unsigned{render::kDefaultLayers}, without_trail, without_hud, without_both};
  for (const auto& [size, trail_snapshot] :
       {std::pair{sizes[0], &snapshot}, std::pair{sizes[1], &snapshot}, std::pair{sizes[2], &snapshot},
        std::pair{sizes[0], &long_trail}}) {
    std::vector<double> total[4];
    for (int f = 0; f < frames + 2; ++f)
      for (int k = 0; k < 4; ++k) {
        render::ViewOptions view;
        view.width = size.w;
        view.height = size.h;
        view.layers = interleaved[k];
        render::aim_camera_at_body(view, *trail_snapshot);
        const auto t = std::chrono::steady_clock::now();
        const render::FrameScene scene = render::build_scene(*trail_snapshot, view);
        const std::uint8_t* rgba = renderer.render_rgba(scene, view.width, view.height);
        render::encode_png(rgba, view.width, view.height);
        if (f >= 2) total[k].push_back(ms_since(t));
      }
    const double all = median(total[0]), no_trail = median(total[1]), no_hud = median(total[2]),
                 neither = median(total[3]);
    std::printf("| %dx%d | %zu | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f× |\n", size.w, size.h,
                trail_snapshot->bodies.front().trail.size(), all, no_trail, no_hud, neither, all - no_trail,
                all - no_hud, all / neither);
  }
  // What companions cost: one body against 8 companions (the most a scene may have), all layers,
  // interleaved as above. Building the snapshot is part of a frame (readouts, trails copied).
  std::printf(
      "\n| size | bodies | snapshot ms | build ms | render ms | encode ms | frame ms |\n| --- | --- | --- | "
      "--- | "
      "--- | --- | --- |\n");
  for (const Size& size : {sizes[0], sizes[1]}) {
    std::vector<double> snap[2], build[2], draw[2], encode[2];
    const FanRun fans[2] = {fan_run(0), fan_run(8)};
    render::Snapshot snapshots[2];
    for (int f = 0; f < frames + 2; ++f)
      for (int k = 0; k < 2; ++k) {
        render::ViewOptions view;
        view.width = size.w;
        view.height = size.h;
        auto t = std::chrono::steady_clock::now();
        snapshots[k] = render::make_snapshot(fans[k].run, fans[k].trail, -1.0);
        const double sn = ms_since(t);
        render::aim_camera_at_body(view, snapshots[k]);
        t = std::chrono::steady_clock::now();
        const render::FrameScene scene = render::build_scene(snapshots[k], view);
        const double b = ms_since(t);
        t = std::chrono::steady_clock::now();
        const std::uint8_t* rgba = renderer.render_rgba(scene, view.width, view.height);
        const double d = ms_since(t);
        t = std::chrono::steady_clock::now();
        render::encode_png(rgba, view.width, view.height);
        const double e = ms_since(t);
        if (f >= 2)
          snap[k].push_back(sn), build[k].push_back(b), draw[k].push_back(d), encode[k].push_back(e);
      }
    for (int k = 0; k < 2; ++k)
      std::printf("| %dx%d | %zu | %.2f | %.2f | %.2f | %.2f | %.2f |\n", size.w, size.h,
                  snapshots[k].bodies.size(), median(snap[k]), median(build[k]), median(draw[k]),
                  median(encode[k]),
                  median(snap[k]) + median(build[k]) + median(draw[k]) + median(encode[k]));
  }
  return 0;
}

}  // namespace spinfold::bench
