#include "bench/gl_bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <thread>
#include <vector>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "engine/simulation.h"
#include "engine/trail.h"
#include "render/renderer.h"
#include "render/snapshot.h"
#include "render/view.h"

namespace spinfold::bench {

namespace {

double ms_between(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Row {
  int width = 0, height = 0;
  double frame_ms = 0.0;
};

struct BackendResult {
  std::string name, renderer, error;
  double start_ms = 0.0;  // context + shader warm-up
  std::vector<Row> rows;
};

// The live view's work: a fixed camera on a moving body (trail, HUD, legend; the background
// cached), the frames' scenes built beforehand so that only GL is timed (draw, HUD, read-back).
BackendResult measure(render::GlBackend backend, int frames) {
  BackendResult result;
  const auto start = std::chrono::steady_clock::now();
  render::Renderer renderer(backend);
  result.start_ms = ms_between(start, std::chrono::steady_clock::now());
  result.name = renderer.context().name();
  result.renderer = renderer.context().renderer();
  Simulation run = start_simulation(*parse_scene_text(find_preset("spin_vs_geodesic_sphere")->json).scene);
  Trail trail;
  trail.spacing = 2.0 / 64;
  std::vector<render::Snapshot> snapshots;
  for (int i = 0; i < frames + 2; ++i) {
    advance_sampling_trail(run, trail, 2.0 + 0.02 * i);
    snapshots.push_back(render::make_snapshot(run, trail, -1.0));
  }
  for (const auto& [w, h] : {std::pair{640, 480}, std::pair{1920, 1080}}) {
    render::ViewOptions view;
    view.kind = render::ViewKind::sphere;
    view.width = w;
    view.height = h;
    render::aim_camera_at_body(view, snapshots.front());
    std::vector<render::FrameScene> scenes;
    for (const render::Snapshot& s : snapshots) scenes.push_back(render::build_scene(s, view));
    std::vector<double> times;
    for (std::size_t i = 0; i < scenes.size(); ++i) {
      const auto t = std::chrono::steady_clock::now();
      renderer.render_rgba(scenes[i], w, h);
      if (i >= 2) times.push_back(ms_between(t, std::chrono::steady_clock::now()));  // 2 warm-up frames
    }
    result.rows.push_back({w, h, median(times)});
  }
  return result;
}

}  // namespace

int run_gl_bench(const GlBenchOptions& options) {
  std::vector<render::GlBackend> backends;
  if (options.backend == "all") {
#ifdef SPINFOLD_HAVE_EGL
    backends.push_back(render::GlBackend::egl);
#endif
#ifdef SPINFOLD_HAVE_OSMESA
    backends.push_back(render::GlBackend::osmesa);
#endif
  } else if (const auto one = render::parse_gl_backend(options.backend)) {
    backends.push_back(*one);
  } else {
    std::fprintf(stderr, "spinfold-bench gl: --backend: must be all, auto, egl or osmesa (not '%s')\n",
                 options.backend.c_str());
    return 2;
  }
  if (options.frames < 1) {
    std::fprintf(stderr, "spinfold-bench gl: --frames: must be >= 1\n");
    return 2;
  }
  std::printf(
      "spin_vs_geodesic_sphere, sphere view, fixed camera, moving body; %d frames per size (median)\n\n",
      options.frames);
  std::printf("| backend | GL_RENDERER | size | frame ms | frames/s | context + warm-up ms |\n");
  std::printf("| --- | --- | --- | --- | --- | --- |\n");
  int failures = 0;
  for (const render::GlBackend backend : backends) {
    // A thread of its own per backend: one context per thread, as the server's render threads.
    BackendResult result;
    std::thread worker([&] {
      try {
        result = measure(backend, options.frames);
      } catch (const std::exception& e) {
        result.error = e.what();
      }
    });
    worker.join();
    if (!result.error.empty()) {
      std::printf("| %s | (none: %s) | | | | |\n", std::string(render::gl_backend_name(backend)).c_str(),
                  result.error.c_str());
      ++failures;
      continue;
    }
    for (const Row& row : result.rows)
      std::printf("| %s | %s | %dx%d | %.2f | %.1f | %.0f |\n", result.name.c_str(), result.renderer.c_str(),
                  row.width, row.height, row.frame_ms, 1000.0 / row.frame_ms, result.start_ms);
    std::fflush(stdout);
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace spinfold::bench
