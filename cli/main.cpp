// spinfold: the command line. `simulate` prints JSON Lines samples of a run; `render` draws one
// frame; `record` a time window as a GIF, WebM, MP4 or zip of PNGs; `scenes` lists the presets;
// `integrators` prints the catalog; `work-precision` measures run time against error on a scene;
// `plot` draws quantities of a run as an SVG or PDF figure (render writes those too).
// Bad input: a message on stderr and exit code 2.
#include <pthread.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <thread>

#include "cli/run_loop.h"
#include "cli/sweep.h"
#ifndef SPINFOLD_COMPUTE_ONLY
#include "cli/figure_command.h"
#include "cli/work_precision_command.h"
#endif
#include "codec/presets.h"
#include "codec/provenance.h"
#include "codec/sample_json.h"
#include "codec/sample_table.h"
#include "codec/scene_json.h"
#include "engine/chart.h"
#include "engine/integrator.h"
#include "engine/run_limits.h"
#include "engine/simulation.h"
#ifndef SPINFOLD_COMPUTE_ONLY  // the compute-only build: simulate and sweep, no GL, FFmpeg or HTTP
#include "cli/view_options.h"
#include "record/clip.h"
#include "record/recorder.h"
#include "render/renderer.h"
#include "render/snapshot.h"
#include "render/view.h"
#include "server/api.h"
#include "server/session_db.h"
#endif

namespace {

using namespace spinfold;

constexpr int kExitBadInput = 2;
constexpr int kExitRunStopped = 3;

struct BadInput {
  std::string message;
};

struct SimulateOptions {
  std::string scene_file;
  std::string preset;
  double t_end = 10.0;
  double every = 0.5;
  std::optional<std::string> integrator;
  std::optional<double> dt;
  std::optional<double> tolerance;
  // simulate's output (codec/sample_table.h) and its budgets
  std::string format;  // jsonl | csv; "": by --out's extension, else jsonl
  std::string fields;  // table columns; "": all (CSV), the whole sample (JSON Lines)
  std::string out;     // "" or "-": stdout
  std::optional<std::string> max_steps_text;  // read by run_limit_value (engine/run_limits.h)
  std::optional<std::uint64_t> max_steps;
  std::optional<double> max_seconds;
  bool quiet = false;
  std::string command;  // the command line, for the provenance
};

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BadInput{"cannot read scene file '" + path + "'"};
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string preset_names() {
  std::string names;
  for (const PresetSource& p : preset_sources()) names += (names.empty() ? "" : ", ") + std::string(p.name);
  return names;
}

Scene load_scene(const SimulateOptions& opt) {
  if (!opt.scene_file.empty() && !opt.preset.empty())
    throw BadInput{"give either a scene file or --scene, not both"};
  std::string text;
  if (!opt.scene_file.empty()) {
    text = read_file(opt.scene_file);
  } else {
    const std::string name = opt.preset.empty() ? std::string(kDefaultPreset) : opt.preset;
    const PresetSource* preset = find_preset(name);
    if (!preset) throw BadInput{"--scene: no preset named '" + name + "' (presets: " + preset_names() + ")"};
    text = preset->json;
  }
  SceneParse parsed = parse_scene_text(text);
  if (!parsed.errors.empty()) throw BadInput{describe_errors(parsed.errors)};
  // Command-line overrides go through the same validation as the scene file.
  nlohmann::json document = scene_to_json(*parsed.scene);
  if (opt.integrator) document["integrator"]["name"] = *opt.integrator;
  if (opt.dt) document["integrator"]["dt"] = *opt.dt;
  if (opt.tolerance) document["integrator"]["tolerance"] = *opt.tolerance;
  parsed = parse_scene(document);
  if (!parsed.errors.empty()) throw BadInput{describe_errors(parsed.errors)};
  return *parsed.scene;
}

// "t = 41.5 / 100 (41%)  123456 steps  2.1 s", redrawn in place on stderr.
void draw_run_progress(const Simulation& run, double t_end, double seconds) {
  std::fprintf(stderr, "\rt = %.6g / %.6g (%.0f%%)  %llu steps  %.1f s ", run.state.t, t_end,
               t_end > 0 ? 100.0 * run.state.t / t_end : 100.0, static_cast<unsigned long long>(run.steps),
               seconds);
}

// Why a run ended before t_end without trouble of its own: a budget the user set.
enum class Budget { left, steps, seconds };

// A run limit as given (engine/run_limits.h): the row's rule and words, exit 2 naming the option.
void check_run_limit(std::string_view name, double value) {
  const RunLimit& limit = run_limit(name);
  if (!allows(limit.rule, value))
    throw BadInput{refused(run_limit_option(name), must_be(limit.rule), "'" + shortest(value) + "'")};
}

// A run limit given as text, read by the one number reader (engine/number_rule.h).
double run_limit_value(std::string_view name, const std::string& text) {
  const RunLimit& limit = run_limit(name);
  const std::optional<double> x = number_from_text(text);
  if (!x || !allows(limit.rule, *x))
    throw BadInput{refused(run_limit_option(name), must_be(limit.rule), "'" + text + "'")};
  return *x;
}

int simulate(SimulateOptions opt) {
  if (opt.max_steps_text)
    opt.max_steps = static_cast<std::uint64_t>(run_limit_value("max_steps", *opt.max_steps_text));
  check_run_limit("t_end", opt.t_end);
  check_run_limit("every", opt.every);
  if (const auto why = samples_refusal(opt.t_end, opt.every)) throw BadInput{"--every: " + *why};
  if (opt.max_seconds) check_run_limit("max_seconds", *opt.max_seconds);
  const bool to_stdout = opt.out.empty() || opt.out == "-";
  std::string format = opt.format;
  if (format.empty()) format = !to_stdout && opt.out.ends_with(".csv") ? "csv" : "jsonl";
  if (format != "jsonl" && format != "csv")
    throw BadInput{"--format: must be jsonl or csv (got '" + format + "')"};
  const bool csv = format == "csv";
  const Scene scene = load_scene(opt);

  Simulation run = start_simulation(scene);
  SampleTable table;
  try {
    table = make_sample_table(opt.fields, sample_to_json(run, -1.0));
  } catch (const std::invalid_argument& e) {
    throw BadInput{std::string("--fields: ") + e.what()};
  }
  FILE* out = stdout;
  if (!to_stdout) {
    out = std::fopen(opt.out.c_str(), "w");
    if (!out) throw BadInput{"--out: cannot write '" + opt.out + "'"};
  }
  // Line by line: a run killed at a cluster's time limit leaves whole lines only.
  std::setvbuf(out, nullptr, _IOLBF, 1 << 16);
  const auto write = [&](const std::string& line) { std::fputs(line.c_str(), out); };

  const nlohmann::ordered_json provenance = provenance_json(scene, opt.command);
  if (csv) {
    write("# spinfold simulate " + version_line() + "\n# provenance: " + provenance.dump() + "\n");
    write(table.csv_header());
  } else {
    write(nlohmann::ordered_json{{"provenance", provenance}}.dump() + "\n");
  }
  double reported_until = -1.0;  // events up to this time were printed
  const auto emit = [&] {
    const nlohmann::ordered_json sample = sample_to_json(run, reported_until);
    if (csv)
      write(table.csv_row(sample));
    else
      write((opt.fields.empty() ? sample : table.json_row(sample)).dump() + "\n");
    reported_until = run.state.t;
  };

  // Advanced in slices of step attempts so that the clock, the progress line and --max-steps are
  // looked at between them; a run's numbers do not depend on where it was stopped (advance_to).
  constexpr std::uint64_t kSlice = 4096;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const bool show = !opt.quiet && isatty(fileno(stderr));
  double drawn_at = 0.0;
  std::uint64_t steps_left = opt.max_steps.value_or(kNoStepLimit);
  Budget budget = Budget::left;
  const auto advance = [&](double t) {
    while (true) {
      if (opt.max_seconds && elapsed() > *opt.max_seconds) {
        budget = Budget::seconds;
        return false;
      }
      std::uint64_t slice = std::min(kSlice, steps_left);
      const std::uint64_t before = slice;
      const bool reached = advance_within(run, t, slice);
      steps_left -= before - slice;
      if (show && elapsed() - drawn_at > 0.25) draw_run_progress(run, opt.t_end, drawn_at = elapsed());
      if (reached) return true;
      if (steps_left == 0) {
        budget = Budget::steps;
        return false;
      }
    }
  };
  cli::sample_run(run, opt.t_end, opt.every, advance, emit);
  if (show && drawn_at > 0.0) {
    draw_run_progress(run, opt.t_end, elapsed());
    std::fputc('\n', stderr);
  }
  int code = 0;
  std::string stopped;
  if (budget != Budget::left) {
    stopped = budget == Budget::steps ? "max_steps (the step budget --max-steps ran out)"
                                      : "max_seconds (the time budget --max-seconds ran out)";
    code = kExitRunStopped;
  } else if (run.state.status != Status::ok) {
    stopped = std::string(status_name(run.state.status));
    code = kExitRunStopped;
  }
  if (budget != Budget::left) {  // the last sample is not at the run's end: say where it got to
    const nlohmann::ordered_json end = {{"stopped", budget == Budget::steps ? "max_steps" : "max_seconds"},
                                        {"t", run.state.t},
                                        {"steps", run.steps}};
    write(csv ? "# stopped: " + end.dump() + "\n" : end.dump() + "\n");
  }
  if (!to_stdout)
    std::fclose(out);
  else
    std::fflush(out);
  if (code != 0) std::cerr << "spinfold: run stopped at t = " << run.state.t << ": " << stopped << "\n";
  return code;
}

#ifndef SPINFOLD_COMPUTE_ONLY
struct RenderOptions {
  SimulateOptions scene;
  double t = 0.0;
  cli::ViewArgs view;  // --width … --trail, --camera (cli/view_options.h)
  std::string out;
};

// The view options as the table reads them; the view checked against the scene's surface.
render::ViewRequest view_request(const RenderOptions& opt) {
  try {
    return cli::view_request(opt.view);
  } catch (const cli::BadViewOption& e) {
    throw BadInput{e.what()};
  }
}

// The view of the request on the scene's surface (render::view_options: the one resolver).
render::ViewOptions view_options(const render::ViewRequest& request, const Scene& scene) {
  try {
    return render::view_options(request, scene.surface);
  } catch (const render::ViewRefused& e) {
    throw BadInput{"--" + e.parameter + ": " + e.what()};
  }
}

int render_frame(const RenderOptions& opt, const std::string& format_option) {
  check_run_limit("t", opt.t);
  if (opt.out.empty()) throw BadInput{"--out: the PNG file to write is required"};
  const render::FigureFormat format = cli::render_format(format_option, opt.out);  // before any work
  const render::ViewRequest request = view_request(opt);
  const Scene scene = load_scene(opt.scene);
  render::ViewOptions view = view_options(request, scene);

  Simulation run;
  const render::Snapshot snapshot =
      render::snapshot_at(scene, opt.t, view.layers & render::kTrail, request.trail, run);
  // The camera aimed at the body, the parts given replacing the aimed ones (as every front door).
  render::place_camera(view, request, snapshot,
                       format == render::FigureFormat::png ? render::Picture::frame : render::Picture::figure);
  if (format != render::FigureFormat::png) {  // a vector figure (cli/figure_command.h)
    cli::write_frame_figure(scene, snapshot, view, false, format, opt.out, opt.scene.command, opt.t);
  } else {
    render::Renderer renderer;
    const std::vector<render::PngText> texts =
        picture_texts(scene, opt.scene.command, opt.t, render::view_name(view.kind));
    const std::vector<std::uint8_t> png = renderer.render_png(snapshot, view, texts);
    std::ofstream file(opt.out, std::ios::binary);
    if (!file) throw BadInput{"--out: cannot write '" + opt.out + "'"};
    file.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  }
  if (run.state.status != Status::ok) {
    std::cerr << "spinfold: run stopped at t = " << run.state.t << ": " << status_name(run.state.status)
              << "\n";
    return kExitRunStopped;
  }
  return 0;
}

struct RecordOptions {
  RenderOptions render;  // the scene, view, size, layers, camera, scale, trail and --out
  record::Clip clip;
  std::string format;
  bool quiet = false;
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

// Serves until SIGTERM or SIGINT: a thread waits for them (sigwait; blocked in every thread, so
// no handler runs in the middle of anything) and stops the server, which ends the event streams and
// stores the time of playing sessions.
int serve(const server::ServerOptions& options) {
  if (options.port < 0 || options.port > 65535) throw BadInput{"--port: must be 0..65535"};
  if (options.threads < 2 || options.threads > 256) throw BadInput{"--threads: must be 2..256"};
  if (options.frame_ancestors.empty() || options.frame_ancestors.find_first_of(";,\r\n") != std::string::npos)
    throw BadInput{"--frame-ancestors: 'none' or space-separated origins (no ';', ',' or line breaks)"};
  if (options.render_threads < 0 || options.render_threads > 64)
    throw BadInput{"--render-threads: must be 0..64"};
  const double rate = options.limits.requests_per_second_per_client;
  if (!std::isfinite(rate) || rate < 0.0)
    throw BadInput{"--requests-per-second: must be a finite number >= 0 (0: unlimited)"};
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);  // before any thread starts: they inherit it
  std::unique_ptr<server::ApiServer> api;
  try {
    api = std::make_unique<server::ApiServer>(options);
  } catch (const server::StoreError& e) {
    throw BadInput{std::string("the session store: ") + e.what()};
  }
  const int port = api->bind();
  if (port < 0) {
    std::cerr << "spinfold: cannot listen on " << options.host << ":" << options.port << "\n";
    return 1;
  }
  const std::string id = api->create_session(*parse_scene_text(find_preset(kDefaultPreset)->json).scene);
  const std::string base = "http://" + options.host + ":" + std::to_string(port);
  std::cout << "Spinfold " << version_line() << " serving on " << base << "/\n"
            << "  default scene '" << kDefaultPreset << "': " << base << "/api/v1/sessions/" << id << "\n"
            << "  its frame:  " << base << "/api/v1/sessions/" << id << "/frame.png\n"
            << "  sessions: "
            << (!options.store.empty()      ? "stored in " + server::store_url_for_messages(options.store)
                : options.data_dir.empty() ? "in memory only"
                                           : "stored in " + options.data_dir + "/sessions.db")
            << std::endl;
  std::atomic<bool> signalled{false};
  std::thread waiter([&] {
    int signal = 0;
    sigwait(&signals, &signal);
    signalled = true;
    api->stop();
  });
  const bool served = api->listen();
  if (!signalled) pthread_kill(waiter.native_handle(), SIGTERM);  // listen failed: end the waiter
  waiter.join();
  api.reset();  // joins the player and the render thread before the exit code is returned
  return served || signalled ? 0 : 1;
}
#endif  // SPINFOLD_COMPUTE_ONLY

int list_scenes() {
  for (const PresetSource& p : preset_sources()) {
    const SceneParse parsed = parse_scene_text(p.json);
    const std::string description = parsed.scene ? parsed.scene->description : "(invalid preset)";
    std::printf("%-32s %s\n", std::string(p.name).c_str(), description.c_str());
  }
  return 0;
}

#ifndef SPINFOLD_COMPUTE_ONLY
// --gl auto|egl|osmesa (default: SPINFOLD_GL, else auto); CLI11 refuses other values (exit 2).
void add_gl_option(CLI::App* command, std::string& choice) {
  command
      ->add_option("--gl", choice,
                   "GL backend: auto (an EGL GPU device, else EGL surfaceless, else OSMesa) | egl | osmesa "
                   "(default: SPINFOLD_GL, else auto)")
      ->check(CLI::IsMember({"auto", "egl", "osmesa"}));
}

// The process's backend from --gl, else SPINFOLD_GL (a bad value is bad input, exit 2).
void apply_gl_choice(const std::string& choice) {
  if (!choice.empty()) {
    render::set_gl_backend(*render::parse_gl_backend(choice));
    return;
  }
  try {
    render::set_gl_backend(render::gl_backend_setting());
  } catch (const std::invalid_argument& e) {
    throw BadInput{e.what()};
  }
}

// For --version: the backends built in and the context SPINFOLD_GL (else auto) gives here.
std::string gl_version_lines() {
  std::string lines = "GL backends built in: " + render::compiled_gl_backends() + "\n";
  try {
    const std::unique_ptr<render::GlContext> context = render::make_gl_context();
    lines += "GL in use: " + context->name() + " (" + context->renderer() + ")";
  } catch (const std::exception& e) {
    lines += std::string("GL in use: none (") + e.what() + ")";
  }
  return lines;
}
#endif

int list_integrators() {
  std::printf("%-18s %5s %10s %8s %5s  %s\n", "name", "order", "symplectic", "adaptive", "exact", "summary");
  for (const CatalogEntry& e : integrator_catalog()) {
    const IntegratorInfo& i = e.info;
    std::printf("%-18s %5d %10s %8s %5s  %s\n", std::string(i.name).c_str(), i.order,
                i.symplectic ? "yes" : "no", i.adaptive ? "yes" : "no", i.exact ? "yes" : "no",
                std::string(i.summary).c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Spinfold: affinely-rigid bodies moving on the sphere and the pseudosphere"};
#ifdef SPINFOLD_COMPUTE_ONLY
  app.set_version_flag("--version", "spinfold " + version_line());
#else
  app.set_version_flag("--version", [] { return "spinfold " + version_line() + "\n" + gl_version_lines(); });
#endif
  app.require_subcommand(1);

  SimulateOptions sim;
  CLI::App* simulate_cmd = app.add_subcommand("simulate", "Simulate a scene and print JSON Lines samples");
  simulate_cmd->add_option("scene_file", sim.scene_file, "Scene JSON file (default: the default preset)");
  simulate_cmd->add_option("--scene", sim.preset,
                           "Simulate an embedded preset by name (see `spinfold scenes`)");
  simulate_cmd->add_option("--t-end", sim.t_end, "Simulated time to reach")->capture_default_str();
  simulate_cmd->add_option("--every", sim.every, "Sample interval")->capture_default_str();
  simulate_cmd->add_option("--integrator", sim.integrator, "Override the scene's integrator name");
  simulate_cmd->add_option("--dt", sim.dt, "Override the step (fixed-step) or first trial step");
  simulate_cmd->add_option("--tolerance", sim.tolerance, "Override the error tolerance per step");
  simulate_cmd->add_option("--format", sim.format, "jsonl | csv (default: by --out's extension, else jsonl)");
  simulate_cmd->add_option("--fields", sim.fields,
                           "Comma-separated columns (see `spinfold simulate --list-fields`; default: all)");
  simulate_cmd->add_option("--out", sim.out, "File to write (default: stdout)");
  simulate_cmd->add_option("--max-steps", sim.max_steps_text, "Stop after this many step attempts (exit 3)");
  simulate_cmd->add_option("--max-seconds", sim.max_seconds, "Stop after this much wall time (exit 3)");
  simulate_cmd->add_flag("--quiet", sim.quiet,
                         "No progress line (there is none when stderr is not a terminal)");
  bool list_fields = false;
  simulate_cmd->add_flag("--list-fields", list_fields, "Print the column names --fields takes, and exit");
  cli::SweepOptions sweep_opt;
  CLI::App* sweep_cmd = cli::add_sweep_command(app, sweep_opt);
#ifndef SPINFOLD_COMPUTE_ONLY
  RenderOptions ren;
  CLI::App* render_cmd =
      app.add_subcommand("render", "Render the state at time T as a PNG, or an SVG or PDF figure");
  render_cmd->add_option("scene_file", ren.scene.scene_file, "Scene JSON file (default: the default preset)");
  render_cmd->add_option("--scene", ren.scene.preset, "Render an embedded preset by name");
  render_cmd->add_option("--t", ren.t, "Time of the frame")->capture_default_str();
  cli::add_view_options(*render_cmd, ren.view);
  render_cmd->add_option("--out", ren.out, "File to write (.png, .svg or .pdf)");
  std::string render_format;  // png | svg | pdf (cli/figure_command.h)
  render_cmd->add_option("--format", render_format,
                         "png | svg | pdf: the GL frame, or a vector figure for a paper (default: by --out's "
                         "extension, else png)");
  render_cmd->add_option("--integrator", ren.scene.integrator, "Override the scene's integrator name");
  std::string gl_choice;  // --gl of render, record or serve (one subcommand runs)
  add_gl_option(render_cmd, gl_choice);
  RecordOptions rec;
  CLI::App* record_cmd =
      app.add_subcommand("record", "Record a time window as a GIF, WebM, MP4 or a zip of PNGs");
  record_cmd->add_option("scene_file", rec.render.scene.scene_file,
                         "Scene JSON file (default: the default preset)");
  record_cmd->add_option("--scene", rec.render.scene.preset, "Record an embedded preset by name");
  record_cmd->add_option("--t-start", rec.clip.t_start, "Simulated time of the first frame")
      ->capture_default_str();
  record_cmd->add_option("--t-end", rec.clip.t_end, "End of the window (excluded) [time]")->required();
  record_cmd->add_option("--fps", rec.clip.fps, "Frames per second of the file")->capture_default_str();
  record_cmd->add_option("--speed", rec.clip.speed, "Simulated time per second of the file")
      ->capture_default_str();
  record_cmd->add_option("--format", rec.format, record::joined_format_names(" | ", " | "))->required();
  record_cmd->add_option("--out", rec.render.out, "File to write")->required();
  cli::add_view_options(*record_cmd, rec.render.view);
  record_cmd->add_option("--integrator", rec.render.scene.integrator, "Override the scene's integrator name");
  add_gl_option(record_cmd, gl_choice);
  record_cmd->add_flag("--quiet", rec.quiet, "No progress bar (there is none when stderr is not a terminal)");
  cli::WorkPrecisionOptions wp_opt;
  CLI::App* wp_cmd = cli::add_work_precision_command(app, wp_opt);
  cli::PlotOptions plot_opt;
  CLI::App* plot_cmd = cli::add_plot_command(app, plot_opt);
  server::ServerOptions serve_opt;
  CLI::App* serve_cmd = app.add_subcommand("serve", "Serve the HTTP API with a session on the default scene");
  serve_cmd->add_option("--host", serve_opt.host, "Address to bind")->capture_default_str();
  serve_cmd->add_option("--port", serve_opt.port, "Port (0: any free port)")->capture_default_str();
  add_gl_option(serve_cmd, gl_choice);
  serve_cmd->add_option("--threads", serve_opt.threads, "HTTP worker threads (one per open connection)")
      ->capture_default_str();
  serve_cmd
      ->add_option("--render-threads", serve_opt.render_threads,
                   "Render threads, each with its own GL context (0: one per core)")
      ->capture_default_str();
  serve_cmd
      ->add_option("--frame-ancestors", serve_opt.frame_ancestors,
                   "Origins that may show the UI in an iframe (?embed=1), space-separated; 'none': nobody")
      ->capture_default_str();
  serve_cmd
      ->add_option("--trusted-proxy", serve_opt.trusted_proxy,
                   "Address (or IPv4 network a.b.c.d/n) of the reverse proxy whose X-Forwarded-For names the client ('' never trusts it)")
      ->capture_default_str();
  serve_cmd
      ->add_option("--requests-per-second", serve_opt.limits.requests_per_second_per_client,
                   "Requests a second per client address (token bucket; 0: unlimited)")
      ->capture_default_str();
  serve_opt.data_dir = server::default_data_dir();
  serve_cmd
      ->add_option("--data-dir", serve_opt.data_dir,
                   "Directory of the session store (sessions.db, SQLite); '' keeps sessions in memory only")
      ->capture_default_str();
  serve_cmd
      ->add_option("--store", serve_opt.store,
                   "PostgreSQL URL of a session store shared by replicas on several hosts "
                   "(postgresql://user:password@host:port/db); instead of --data-dir")
      ->envname("SPINFOLD_STORE");
  bool no_store = false;
  serve_cmd->add_flag("--no-store", no_store, "Keep sessions in memory only (as --data-dir '')");
#endif
  CLI::App* scenes_cmd = app.add_subcommand("scenes", "List the embedded preset scenes");
  CLI::App* integrators_cmd = app.add_subcommand("integrators", "Print the integrator catalog");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "spinfold: " << e.what() << "\n(run `spinfold --help` for usage)\n";
    return kExitBadInput;
  }

  try {
    if (simulate_cmd->parsed() && list_fields) {
      for (const std::string& name : sample_column_names()) std::printf("%s\n", name.c_str());
      return 0;
    }
    if (simulate_cmd->parsed()) {
      sim.command = command_line(argc, argv);
      return simulate(sim);
    }
    if (sweep_cmd->parsed()) return cli::run_sweep_command(sweep_opt, argc, argv);
#ifndef SPINFOLD_COMPUTE_ONLY
    if (render_cmd->parsed() || record_cmd->parsed() || serve_cmd->parsed()) apply_gl_choice(gl_choice);
    if (render_cmd->parsed()) {
      ren.scene.command = command_line(argc, argv);
      return render_frame(ren, render_format);
    }
    if (record_cmd->parsed()) {
      rec.render.scene.command = command_line(argc, argv);
      return record_window(rec);
    }
    if (wp_cmd->parsed()) return cli::run_work_precision_command(wp_opt, argc, argv);
    if (plot_cmd->parsed()) return cli::run_plot_command(plot_opt, argc, argv);
    if (serve_cmd->parsed()) {
      if (no_store) serve_opt.data_dir.clear(), serve_opt.store.clear();
      return serve(serve_opt);
    }
#endif
    if (scenes_cmd->parsed()) return list_scenes();
    if (integrators_cmd->parsed()) return list_integrators();
  } catch (const BadInput& e) {
    std::cerr << "spinfold: " << e.message << (e.message.ends_with('\n') ? "" : "\n");
    return kExitBadInput;
#ifndef SPINFOLD_COMPUTE_ONLY
  } catch (const cli::FigureInputError& e) {
    std::cerr << "spinfold: " << e.what() << "\n";
    return kExitBadInput;
#endif
  } catch (const std::runtime_error& e) {  // record::RecordError among them
    std::cerr << "spinfold: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
