// spinfold-bench: benchmarks with their own command, never part of the test suite.
#include <CLI/CLI.hpp>

#include "bench/companions_bench.h"
#include "bench/cross_cpu.h"
#include "bench/gl_bench.h"
#include "bench/oracle_sweep.h"
#include "bench/record_bench.h"
#include "bench/render_bench.h"
#include "bench/share_link_bench.h"
#include "bench/soak.h"
#include "bench/stress.h"
#include "bench/surfaces_bench.h"
#include "bench/work_precision.h"

int main(int argc, char** argv) {
  CLI::App app{"Spinfold benchmarks"};
  app.require_subcommand(1);
  spinfold::bench::WorkPrecisionOptions wp;
  CLI::App* wp_cmd =
      app.add_subcommand("work-precision", "Run time against error for every integrator and Boost.Odeint");
  wp_cmd->add_option("--scenes", wp.scenes, "Scene names (default: all)");
  wp_cmd->add_option("--out", wp.out_dir, "Output folder")->capture_default_str();
  wp_cmd->add_option("--periods", wp.periods, "T in characteristic periods")->capture_default_str();
  wp_cmd->add_option("--target", wp.target_error, "Error at which methods are compared")
      ->capture_default_str();
  std::vector<std::string> stress_names;
  double stress_size = 1.0;
  CLI::App* stress_cmd = app.add_subcommand("stress", "Numerical stability stress suite (long versions)");
  stress_cmd->add_option("--cases", stress_names, "Case names (default: all)");
  stress_cmd->add_option("--size", stress_size, "1 = the documented long runs")->capture_default_str();
  int render_frames = 30;
  CLI::App* render_cmd = app.add_subcommand("render", "Frame cost against the bare OSMesa + libpng loop");
  render_cmd->add_option("--frames", render_frames, "Frames per measurement (median)")->capture_default_str();
  spinfold::bench::GlBenchOptions gl;
  CLI::App* gl_cmd = app.add_subcommand(
      "gl", "Frame time and frames/s of each GL backend (EGL, OSMesa) at 640x480 and 1920x1080");
  gl_cmd->add_option("--backend", gl.backend, "all | auto | egl | osmesa")->capture_default_str();
  gl_cmd->add_option("--frames", gl.frames, "Frames per size (median)")->capture_default_str();
  int share_repeats = 9;
  double share_until = 1000.0;
  CLI::App* share_cmd = app.add_subcommand(
      "share-link", "Time to open a share link (timeline of 5 changes) against a bare session");
  share_cmd->add_option("--repeats", share_repeats, "Measurements per case (median)")->capture_default_str();
  share_cmd->add_option("--until", share_until, "Simulated time the link shows")->capture_default_str();
  spinfold::bench::SoakOptions soak;
  CLI::App* soak_cmd = app.add_subcommand(
      "soak", "Mixed load for minutes: errors, latency percentiles, server memory (in-process or --url)");
  soak_cmd->add_option("--minutes", soak.minutes, "Duration")->capture_default_str();
  soak_cmd->add_option("--clients", soak.clients, "Concurrent clients")->capture_default_str();
  soak_cmd->add_option("--url", soak.url, "A running server or front, e.g. http://127.0.0.1:8080");
  soak_cmd->add_option("--pid", soak.server_pid, "With --url: the server process whose memory to report");
  soak_cmd->add_option("--data-dir", soak.data_dir,
                       "The in-process server's session store ('': memory only)");
  int companions_repeats = 5;
  double companions_until = 100.0;
  CLI::App* companions_cmd =
      app.add_subcommand("companions", "A run with 8 companions against the main body alone (engine)");
  companions_cmd->add_option("--repeats", companions_repeats, "Measurements per case (median)")
      ->capture_default_str();
  companions_cmd->add_option("--until", companions_until, "Simulated time")->capture_default_str();
  spinfold::bench::RecordBenchOptions record;
  CLI::App* record_cmd = app.add_subcommand(
      "record", "A clip in every format (wall time, size), and the live frame rate during a recording");
  record_cmd->add_option("--seconds", record.seconds, "Clip length [s]")->capture_default_str();
  record_cmd->add_option("--fps", record.fps, "Frames per second")->capture_default_str();
  record_cmd
      ->add_option("--live-seconds", record.live_seconds, "Live-rate measurement without a recording [s]")
      ->capture_default_str();
  record_cmd->add_option("--out", record.out_dir, "Where the clips are written")->capture_default_str();
  spinfold::bench::CrossCpuOptions cross;
  CLI::App* cross_cmd = app.add_subcommand(
      "cross-cpu", "Every integrator here against a copy with glibc's FMA/AVX2 libm hidden (another CPU)");
  cross_cmd->add_option("--until", cross.until, "Simulated time")->capture_default_str();
  cross_cmd->add_option("--scenes", cross.scenes, "Presets")->capture_default_str();
  cross_cmd->add_option("--tunable", cross.tunable, "GLIBC_TUNABLES of the other CPU")->capture_default_str();
  cross_cmd->add_flag("--dump", cross.dump, "Print this process's ends (hex floats) and stop");
  spinfold::bench::SurfacesBenchOptions surfaces;
  CLI::App* surfaces_cmd = app.add_subcommand(
      "surfaces", "A torus scene: the engine's stepping of the chart-free equations against Boost.Odeint's");
  surfaces_cmd->add_option("--t-end", surfaces.t_end, "Simulated time")->capture_default_str();
  surfaces_cmd->add_option("--target", surfaces.target_error, "Error at which methods are compared")
      ->capture_default_str();
  surfaces_cmd->add_option("--repeats", surfaces.repeats, "Timings per point (median)")
      ->capture_default_str();
  spinfold::bench::OracleSweepOptions sweep;
  CLI::App* sweep_cmd = app.add_subcommand(
      "oracle-sweep",
      "Random scenes of every regime, every integrator against the extended-precision oracle");
  sweep_cmd->add_option("--scenes", sweep.scenes, "Scenes per regime")->capture_default_str();
  sweep_cmd->add_option("--seed", sweep.seed, "First seed (scene i uses seed + i)")->capture_default_str();
  sweep_cmd->add_option("--t-end", sweep.t_end, "Horizon T")->capture_default_str();
  sweep_cmd->add_option("--regime", sweep.regime, "Only this regime");
  sweep_cmd->add_option("--integrator", sweep.integrator, "Only this integrator");
  sweep_cmd->add_flag("--verbose", sweep.verbose, "Print each failing scene's JSON");
  CLI11_PARSE(app, argc, argv);
  if (cross_cmd->parsed()) return spinfold::bench::run_cross_cpu(cross);
  if (sweep_cmd->parsed()) return spinfold::bench::run_oracle_sweep(sweep);
  if (surfaces_cmd->parsed()) return spinfold::bench::run_surfaces_bench(surfaces);
  if (record_cmd->parsed()) return spinfold::bench::run_record_bench(record);
  if (companions_cmd->parsed())
    return spinfold::bench::run_companions_bench(companions_repeats, companions_until);
  if (soak_cmd->parsed()) return spinfold::bench::run_soak(soak);
  if (share_cmd->parsed()) return spinfold::bench::run_share_link_bench(share_repeats, share_until);
  if (gl_cmd->parsed()) return spinfold::bench::run_gl_bench(gl);
  if (render_cmd->parsed()) return spinfold::bench::run_render_bench(render_frames);
  if (wp_cmd->parsed()) return spinfold::bench::run_work_precision(wp);
  if (stress_cmd->parsed()) return spinfold::bench::run_stress(stress_names, stress_size);
  return 0;
}
