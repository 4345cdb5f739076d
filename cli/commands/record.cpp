// `spinfold record`: a time window as a GIF, WebM, MP4 or a zip of PNGs, each frame drawn as
// `render` draws it.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands/command.h"
#include "cli/commands/gl_option.h"
#include "cli/commands/render.h"
#include "codec/provenance.h"
#include "record/clip.h"
#include "record/recorder.h"
#include "render/renderer.h"
#include "render/snapshot.h"

namespace spinfold::cli {

namespace {

struct RecordOptions {
  RenderOptions render;  // the scene, view, size, layers, camera, scale, trail and --out
  record::Clip clip;
  std::string format;
  bool quiet = false;
  std::string gl;
};

// "[#######.............]  120/300 frames  45.2 frames/s  4 s left", redrawn in place on stderr.
void draw_progress(long long done, long long total, double seconds) {
  constexpr int kBar = 30;
  const int filled = static_cast<int>(kBar * done / std::max(1LL, total));
  const double rate = seconds > 0 ? static_cast<double>(done) / seconds : 0.0;
  const double left = rate > 0 ? static_cast<double>(total - done) / rate : 0.0;
  std::fprintf(stderr, "\r[%s%s] %lld/%lld frames  %.1f frames/s  %.0f s left ",
               std::string(filled, '#').c_str(), std::string(kBar - filled, '.').c_str(), done, total, rate,
               left);
  if (done == total) std::fputc('\n', stderr);
}

// Frames at t_start + k·speed/fps drawn like `render` (its own renderer, this thread), encoded.
int record_window(const RecordOptions& opt) {
  const auto flag = [](const std::string& field) {
    std::string name = "--" + field;
    std::replace(name.begin(), name.end(), '_', '-');
    return name;
  };
  for (const FieldError& e : record::clip_errors(opt.clip))
    throw BadInput{flag(e.field) + ": " + e.reason + " (got " + e.value + ")"};
  const auto format = record::parse_format(opt.format);
  if (!format)
    throw BadInput{"--format: must be " + record::joined_format_names(", ", " or ") + " (got '" + opt.format +
                   "')"};
  if (opt.render.out.empty()) throw BadInput{"--out: the file to write is required"};
  const render::ViewRequest request = view_request(opt.render);
  const Scene scene = load_scene(opt.render.scene);
  record::ClipFrames frames{.scene = scene,
                            .view = view_options(request, scene),
                            .yaw = request.yaw,
                            .pitch = request.pitch,
                            .distance = request.distance,
                            .motion = request.motion,
                            .trail_span = request.trail};
  if (const auto why = record::size_unsupported_reason(*format, frames.view.width, frames.view.height))
    throw BadInput{"--width/--height: " + *why};
  nlohmann::ordered_json provenance = provenance_json(scene, opt.render.scene.command);
  provenance["t_start"] = opt.clip.t_start;
  provenance["t_end"] = opt.clip.t_end;
  provenance["view"] = std::string(render::view_name(frames.view.kind));
  const record::ClipWriterSpec spec{frames.view.width, frames.view.height, opt.clip.fps, provenance.dump()};
  std::unique_ptr<record::ClipWriter> recorder;
  try {
    recorder = record::open_clip_writer(*format, opt.render.out, spec);
  } catch (const record::RecordError& e) {
    throw BadInput{std::string("--out: ") + e.what()};
  }
  render::Renderer renderer;
  const bool show = !opt.quiet && isatty(fileno(stderr));
  const auto start = std::chrono::steady_clock::now();
  auto last_drawn = start - std::chrono::seconds(1);
  record::record_clip(
      opt.clip, frames, *recorder,
      [&](render::Snapshot snapshot, const render::ViewOptions& view) {
        return renderer.render_image(snapshot, view);
      },
      [&](long long done, long long total) {
        const auto now = std::chrono::steady_clock::now();
        if (show && (now - last_drawn > std::chrono::milliseconds(100) || done == total)) {
          draw_progress(done, total, std::chrono::duration<double>(now - start).count());
          last_drawn = now;
        }
        return true;
      });
  return 0;
}

}  // namespace

Command register_record(CLI::App& app) {
  auto options = std::make_shared<RecordOptions>();
  CLI::App* record_cmd =
      app.add_subcommand("record", "Record a time window as a GIF, WebM, MP4 or a zip of PNGs");
  record_cmd->add_option("scene_file", options->render.scene.scene_file,
                         "A scene file, or a preset's name if no file has it (default: the default preset)");
  record_cmd->add_option("--scene", options->render.scene.preset, "Record an embedded preset by name");
  record_cmd->add_option("--t-start", options->clip.t_start, "Simulated time of the first frame")
      ->capture_default_str();
  record_cmd->add_option("--t-end", options->clip.t_end, "End of the window (excluded) [time]")->required();
  record_cmd->add_option("--fps", options->clip.fps, "Frames per second of the file")->capture_default_str();
  record_cmd->add_option("--speed", options->clip.speed, "Simulated time per second of the file")
      ->capture_default_str();
  record_cmd->add_option("--format", options->format, record::joined_format_names(" | ", " | "))->required();
  record_cmd->add_option("--out", options->render.out, "File to write")->required();
  add_view_options(*record_cmd, options->render.view);
  record_cmd->add_option("--integrator", options->render.scene.integrator,
                         "Override the scene's integrator name");
  add_gl_option(record_cmd, options->gl);
  record_cmd->add_flag("--quiet", options->quiet,
                       "No progress bar (there is none when stderr is not a terminal)");
  return {record_cmd, [options](int argc, char** argv) {
            apply_gl_choice(options->gl);
            options->render.scene.command = provenance_command(argc, argv);
            return record_window(*options);
          }};
}

}  // namespace spinfold::cli
