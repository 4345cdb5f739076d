#include "bench/record_bench.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "record/clip.h"
#include "record/recorder.h"
#include "server/api.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::bench {

namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

constexpr const char* kPreset = "spin_vs_geodesic_sphere";  // the spinning sphere, geodesic companion

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// One viewer asking for new 640×480 JPEG frames (each a cache miss: the scale changes by 1e-9), as
// a live view of a playing session does: back to back (fps = 0: as many as the server gives), or
// at most `fps` a second; frames a second over `seconds`, or until `stop`.
double live_rate(int port, const std::string& session, double seconds, double fps = 0.0,
                 const std::atomic<bool>* stop = nullptr) {
  httplib::Client c("127.0.0.1", port);
  c.set_tcp_nodelay(true);
  const auto start = Clock::now();
  long frames = 0;
  while (seconds_since(start) < seconds && !(stop && *stop)) {
    if (fps > 0)
      std::this_thread::sleep_until(start +
                                    std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(static_cast<double>(frames) / fps)));
    char path[160];
    std::snprintf(path, sizeof path, "/api/v1/sessions/%s/frame.jpg?width=640&height=480&scale=%.12f",
                  session.c_str(), 0.25 + 1e-9 * static_cast<double>(frames));
    auto res = c.Get(path);
    if (res && res->status == 200) ++frames;
  }
  return static_cast<double>(frames) / seconds_since(start);
}

}  // namespace

int run_record_bench(const RecordBenchOptions& o) {
  std::filesystem::create_directories(o.out_dir);
  const Scene scene = *parse_scene_text(find_preset(kPreset)->json).scene;
  const record::Clip clip{0.0, o.seconds, o.fps, 1.0};
  record::ClipFrames frames{.scene = scene};
  frames.view.width = o.width;
  frames.view.height = o.height;
  frames.view.scale = 0.25 * scene.surface.radius;

  // 1. Each format as `spinfold record` makes it: one renderer on this thread, then the encoder.
  render::Renderer renderer;
  for (const record::Format format :
       {record::Format::webm, record::Format::mp4, record::Format::gif, record::Format::png_zip}) {
    const std::string path = o.out_dir + "/clip." + std::string(record::file_extension(format));
    auto recorder = record::open_clip_writer(format, path, {o.width, o.height, o.fps});
    double render_s = 0.0;
    const auto start = Clock::now();
    record::record_clip(clip, frames, *recorder, [&](render::Snapshot s, const render::ViewOptions& v) {
      const auto t0 = Clock::now();
      render::Image image = renderer.render_image(s, v);
      render_s += seconds_since(t0);
      return image;
    });
    const double wall = seconds_since(start);
    std::printf(
        "{\"format\": \"%s\", \"frames\": %lld, \"wall_s\": %.2f, \"render_s\": %.2f, \"bytes\": %llu}\n",
        std::string(record::format_name(format)).c_str(), record::frame_count(clip), wall, render_s,
        static_cast<unsigned long long>(std::filesystem::file_size(path)));
    std::fflush(stdout);
  }

  // 2. The live view's frame rate without and during a WebM recording, in one server.
  server::ServerOptions options;
  options.port = 0;
  options.threads = 16;
  options.limits.requests_per_second_per_client = 0.0;
  server::ApiServer api(options);
  const int port = api.bind();
  std::thread listener([&] { api.listen(); });
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // render threads compile their shaders
  httplib::Client c("127.0.0.1", port);
  const std::string live = json::parse(
      c.Post("/api/v1/sessions", json{{"preset", kPreset}}.dump(), "application/json")->body)["id"];
  const std::string source = json::parse(
      c.Post("/api/v1/sessions", json{{"preset", kPreset}}.dump(), "application/json")->body)["id"];
  live_rate(port, live, 0.5);  // warm up
  // A viewer taking every frame it can, then one at the live view's 60 frames/s: each without a
  // recording, then during a WebM recording of the same clip (of another session).
  for (const double fps : {0.0, 60.0}) {
    const double without = live_rate(port, live, o.live_seconds, fps);
    const json body{
        {"t_end", o.seconds}, {"fps", o.fps}, {"width", o.width}, {"height", o.height}, {"format", "webm"}};
    const auto start = Clock::now();
    const std::string url = json::parse(
        c.Post("/api/v1/sessions/" + source + "/recordings", body.dump(), "application/json")->body)["url"];
    std::atomic<bool> finished{false};
    double recording_s = 0.0;
    std::thread poller([&] {
      httplib::Client p("127.0.0.1", port);
      for (;;) {
        const json r = json::parse(p.Get(url)->body);
        if (r["status"] != "queued" && r["status"] != "running") break;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
      recording_s = seconds_since(start);
      finished = true;
    });
    const double during = live_rate(port, live, 1e9, fps, &finished);
    poller.join();
    std::printf(
        "{\"viewer\": \"%s\", \"live_frames_per_s\": {\"without_recording\": %.1f, \"during_recording\": "
        "%.1f, "
        "\"ratio\": %.2f}, \"server_webm_wall_s\": %.2f}\n",
        fps > 0 ? "60 frames/s" : "back to back", without, during, during / without, recording_s);
    std::fflush(stdout);
  }
  api.stop();
  listener.join();
  return 0;
}

}  // namespace spinfold::bench
