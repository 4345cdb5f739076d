// `spinfold simulate`: a scene's samples as JSON Lines or CSV, in the one sampling loop
// (engine/sampling.h), with budgets of steps and wall time.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cli/commands/command.h"
#include "cli/commands/scene_options.h"
#include "codec/npz_writer.h"
#include "codec/output_file.h"
#include "codec/provenance.h"
#include "codec/sample_json.h"
#include "codec/sample_table.h"
#include "engine/chaos_indicators.h"
#include "engine/readout.h"
#include "engine/sampling.h"
#include "engine/simulation.h"
#include "engine/sliced_advance.h"

namespace spinfold::cli {

namespace {

struct SimulateOptions {
  SceneOptions scene;
  double t_end = 10.0;
  double every = 0.5;
  // simulate's output (codec/sample_table.h) and its budgets
  std::string format;     // jsonl | csv | npz; "": by --out's extension, else jsonl
  std::string fields;     // table columns; "": all (CSV), the whole sample (JSON Lines)
  std::string out;        // "" or "-": stdout
  std::string crossings;  // the recorded events' crossings (EventSpec::record): .csv, .npz, else JSON Lines
  std::optional<std::string> max_steps_text;  // read by run_limit_value (engine/run_limits.h)
  std::optional<std::uint64_t> max_steps;
  std::optional<double> max_seconds;
  std::vector<std::string> summaries;  // engine/run_summary.h's words
  std::vector<std::string> events;
  bool chaos = false;  // engine/chaos_indicators.h
  double chaos_interval = kDefaultChaosInterval;
  bool quiet = false;
  bool list_fields = false;
};

// "t = 41.5 / 100 (41%)  123456 steps  2.1 s", redrawn in place on stderr.
void draw_run_progress(const Simulation& run, double t_end, double seconds) {
  std::fprintf(stderr, "\rt = %.6g / %.6g (%.0f%%)  %llu steps  %.1f s ", run.state.t, t_end,
               t_end > 0 ? 100.0 * run.state.t / t_end : 100.0, static_cast<unsigned long long>(run.steps),
               seconds);
}

// Each recorded event's crossings (EventSpec::record), one row each: the event's name, the
// occurrence (1, 2, …) and the main body's sample there in the samples' columns (a Poincaré section).
void write_crossings(const std::string& path, bool npz, bool csv, std::optional<OutputFile>& out,
                     Simulation& run, SampleTable table, const nlohmann::ordered_json& provenance) {
  table.companion_labels.clear();  // the main body's crossings: its columns only
  std::vector<NpzColumn> columns{{"event", {}}, {"occurrence", {}}};
  for (const std::string& name : table.header()) columns.push_back({name, {}});
  if (csv) {
    out->write("event,occurrence," + table.csv_header());
    out->write("# spinfold simulate " + version_line() + " crossings\n# provenance: " + provenance.dump() +
               "\n");
  } else if (!npz) {
    out->write(nlohmann::ordered_json{{"provenance", provenance}}.dump() + "\n");
  }
  const State end = run.state;
  const MonitorSpec& spec = run.monitor->spec();
  for (std::size_t e = 0; e < spec.events.size(); ++e) {
    if (spec.events[e].record == 0) continue;
    std::uint64_t k = 0;
    for (const State& at : run.monitor->recorded(e)) {
      run.state = at;  // read as a sample is: the same read-out
      const nlohmann::ordered_json sample = sample_to_json(readout(run), {});
      ++k;
      if (npz) {
        columns[0].cells.emplace_back(spec.events[e].name);
        columns[1].cells.emplace_back(k);
        const std::vector<nlohmann::ordered_json> cells = table.row(sample);
        for (std::size_t i = 0; i < cells.size(); ++i) columns[i + 2].cells.push_back(cells[i]);
      } else if (csv) {
        out->write(spec.events[e].name + "," + std::to_string(k) + "," + table.csv_row(sample));
      } else {
        nlohmann::ordered_json row{{"event", spec.events[e].name}, {"occurrence", k}};
        const nlohmann::ordered_json cells = table.json_row(sample);
        for (const auto& [key, value] : cells.items()) row[key] = value;
        out->write(row.dump() + "\n");
      }
    }
  }
  run.state = end;
  if (!npz) {
    out->close();  // WriteError as the samples' file: exit 1 naming it
    return;
  }
  columns.push_back({"provenance", {provenance.dump()}});
  try {
    write_npz(path, columns);
  } catch (const std::runtime_error& e) {
    throw BadInput{std::string("--crossings: ") + e.what()};
  }
}

// Why a run ended before t_end without trouble of its own: a budget the user set.
enum class Budget { left, steps, seconds };

int simulate(SimulateOptions opt) {
  if (opt.max_steps_text)
    opt.max_steps = static_cast<std::uint64_t>(run_limit_value("max_steps", *opt.max_steps_text));
  check_run_limit("t_end", opt.t_end);
  check_run_limit("every", opt.every);
  if (const auto why = samples_refusal(opt.t_end, opt.every)) throw BadInput{"--every: " + *why};
  if (opt.max_seconds) check_run_limit("max_seconds", *opt.max_seconds);
  const bool to_stdout = opt.out.empty() || opt.out == "-";
  std::string format = opt.format;
  if (format.empty())
    format = !to_stdout && opt.out.ends_with(".csv")   ? "csv"
             : !to_stdout && opt.out.ends_with(".npz") ? "npz"
                                                       : "jsonl";
  if (format != "jsonl" && format != "csv" && format != "npz")
    throw BadInput{"--format: must be jsonl, csv or npz (got '" + format + "')"};
  if (format == "npz" && to_stdout)
    throw BadInput{"--format npz: give --out FILE.npz (an archive, not a stream)"};
  const bool csv = format == "csv", npz = format == "npz";
  const Scene scene = load_scene(opt.scene);

  Simulation run = start_simulation(scene);
  MonitorSpec monitor;
  try {
    monitor = parse_monitor(opt.summaries, opt.events);
    if (!monitor.empty()) watch(run, monitor);
  } catch (const MonitorRefusal& e) {
    throw BadInput{std::string(e.event ? "--event: " : "--summary: ") + e.what()};
  }
  const auto recording = std::find_if(monitor.events.begin(), monitor.events.end(),
                                      [](const EventSpec& e) { return e.record > 0; });
  if (recording != monitor.events.end() && opt.crossings.empty())
    throw BadInput{"--event: '" + recording->name +
                   "' records its crossings: give --crossings FILE (.csv, .jsonl or .npz) for their table"};
  if (recording == monitor.events.end() && !opt.crossings.empty())
    throw BadInput{
        "--crossings: no --event records its crossings (add :record to one, e.g. phi:up:0:record)"};
  if (opt.chaos)
    if (const auto why = chaos_interval_refusal(opt.chaos_interval, opt.t_end))
      throw BadInput{"--chaos-interval: " + *why};
  SampleTable table;
  try {
    table = make_sample_table(opt.fields, sample_to_json(run, -1.0));
  } catch (const std::invalid_argument& e) {
    throw BadInput{std::string("--fields: ") + e.what()};
  }
  // Line by line: a run killed at a cluster's time limit leaves whole lines (but for one cut in its
  // write). Every write checked: a full disk stops the command at that line (exit 1, naming the file).
  std::optional<OutputFile> out;
  if (!npz) {
    try {
      out.emplace(to_stdout ? "-" : opt.out, OutputFile::Buffering::line);
    } catch (const WriteError& e) {
      throw BadInput{std::string("--out: ") + e.what()};
    }
  }
  const auto write = [&](const std::string& line) { out->write(line); };
  // The crossings' table: opened now, so that a path that cannot be written stops before the run.
  const bool crossings_npz = opt.crossings.ends_with(".npz"), crossings_csv = opt.crossings.ends_with(".csv");
  std::optional<OutputFile> crossings_out;
  if (!opt.crossings.empty() && !crossings_npz) {
    try {
      crossings_out.emplace(opt.crossings);
    } catch (const WriteError& e) {
      throw BadInput{std::string("--crossings: ") + e.what()};
    }
  }

  const nlohmann::ordered_json provenance = provenance_json(scene, opt.scene.command);
  // npz: the table's columns, filled as the samples come and written at the end (numpy.load reads
  // them with nothing of spinfold installed), the provenance as an array of its own.
  std::vector<NpzColumn> columns;
  if (npz) {
    for (const std::string& name : table.header()) columns.push_back({name, {}});
  } else if (csv) {
    // The names first (numpy.genfromtxt takes them from the first line), then the provenance.
    write(table.csv_header());
    write("# spinfold simulate " + version_line() + "\n# provenance: " + provenance.dump() + "\n");
  } else {
    write(nlohmann::ordered_json{{"provenance", provenance}}.dump() + "\n");
  }
  double reported_until = -1.0;  // events up to this time were printed
  const auto emit = [&] {
    const nlohmann::ordered_json sample = sample_to_json(run, reported_until);
    if (npz) {
      const std::vector<nlohmann::ordered_json> cells = table.row(sample);
      for (std::size_t i = 0; i < cells.size(); ++i) columns[i].cells.push_back(cells[i]);
    } else if (csv) {
      write(table.csv_row(sample));
    } else {
      write((opt.fields.empty() ? sample : table.json_row(sample)).dump() + "\n");
    }
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
    const Advanced got = advance_in_slices(
        run, t, steps_left,
        [&] {
          if (show && elapsed() - drawn_at > 0.25) draw_run_progress(run, opt.t_end, drawn_at = elapsed());
          return !(opt.max_seconds && elapsed() > *opt.max_seconds);
        },
        kSlice);
    if (got == Advanced::stopped_by_caller) budget = Budget::seconds;
    if (got == Advanced::out_of_attempts) budget = Budget::steps;
    return got == Advanced::reached;
  };
  sample_run(run, opt.t_end, opt.every, advance, emit);
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
  } else if (run.state.status != Status::ok && run.state.status != Status::event_stop) {
    stopped = std::string(status_name(run.state.status));
    code = kExitRunStopped;
  }
  if (budget != Budget::left) {  // the last sample is not at the run's end: say where it got to
    const nlohmann::ordered_json end = {{"stopped", budget == Budget::steps ? "max_steps" : "max_seconds"},
                                        {"t", run.state.t},
                                        {"steps", run.steps}};
    if (npz)
      columns.push_back({"stopped", {end.dump()}});
    else
      write(csv ? "# stopped: " + end.dump() + "\n" : end.dump() + "\n");
  }
  if (!monitor.empty() || opt.chaos) {  // what the run did: one record after the samples
    std::vector<std::string> names = monitor_columns(monitor);
    std::vector<double> values = monitor_values(run);
    if (opt.chaos) {  // its own two runs, to where this one ended
      // Within what is left of --max-steps and --max-seconds: they bound the whole command.
      ChaosMonitor indicators(scene, opt.chaos_interval, run.start_time);
      std::optional<std::chrono::steady_clock::time_point> deadline;
      if (opt.max_seconds)
        deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                               std::chrono::duration<double>(*opt.max_seconds));
      indicators.advance_to(run.state.t, steps_left, deadline);
      const ChaosIndicators got = indicators.indicators();
      if (got.out_of_time || got.out_of_steps) {
        const bool seconds = got.out_of_time;
        if (code == 0)
          stopped = seconds ? "max_seconds (the chaos indicators' runs ran out of --max-seconds at t = " +
                                  shortest(got.t) + ")"
                            : "max_steps (the chaos indicators' runs ran out of --max-steps at t = " +
                                  shortest(got.t) + ")";
        code = kExitRunStopped;
      }
      const std::array<double, 5> c = chaos_values(got);
      for (std::size_t i = 0; i < c.size(); ++i) {
        names.emplace_back(kChaosColumns[i]);
        values.push_back(std::isfinite(c[i]) ? c[i] : NAN);
      }
    }
    nlohmann::ordered_json summary;
    for (std::size_t i = 0; i < names.size(); ++i)
      summary[names[i]] = std::isnan(values[i]) ? nlohmann::ordered_json(nullptr)
                          : names[i].ends_with(".count")
                              ? nlohmann::ordered_json(static_cast<std::uint64_t>(values[i]))
                              : nlohmann::ordered_json(values[i]);
    if (npz) {
      for (std::size_t i = 0; i < names.size(); ++i)
        columns.push_back({"summary." + names[i], {summary[names[i]]}});
    } else {
      write(csv ? "# summary: " + summary.dump() + "\n"
                : nlohmann::ordered_json{{"summary", summary}}.dump() + "\n");
    }
  }
  if (!opt.crossings.empty())
    write_crossings(opt.crossings, crossings_npz, crossings_csv, crossings_out, run, table, provenance);
  if (npz) {
    columns.push_back({"provenance", {provenance.dump()}});
    try {
      write_npz(opt.out, columns);
    } catch (const std::runtime_error& e) {
      throw BadInput{std::string("--out: ") + e.what()};
    }
  } else {
    out->close();
  }
  if (code != 0) std::cerr << "spinfold: run stopped at t = " << run.state.t << ": " << stopped << "\n";
  return code;
}

}  // namespace

Command register_simulate(CLI::App& app) {
  auto options = std::make_shared<SimulateOptions>();
  SimulateOptions& sim = *options;
  CLI::App* simulate_cmd = app.add_subcommand("simulate", "Simulate a scene and print JSON Lines samples");
  simulate_cmd->add_option(
      "scene_file", sim.scene.scene_file,
      "A scene file, or a preset's name if no file has it (default: the default preset)");
  simulate_cmd->add_option("--scene", sim.scene.preset,
                           "Simulate an embedded preset by name (see `spinfold scenes`)");
  simulate_cmd->add_option("--t-end", sim.t_end, "Simulated time to reach")->capture_default_str();
  simulate_cmd->add_option("--every", sim.every, "Sample interval")->capture_default_str();
  simulate_cmd->add_option("--integrator", sim.scene.integrator, "Override the scene's integrator name");
  simulate_cmd->add_option("--dt", sim.scene.dt, "Override the step (fixed-step) or first trial step");
  simulate_cmd->add_option("--tolerance", sim.scene.tolerance, "Override the error tolerance per step");
  simulate_cmd->add_option("--format", sim.format,
                           "jsonl | csv | npz (default: by --out's extension, else jsonl)");
  simulate_cmd->add_option("--fields", sim.fields,
                           "Comma-separated columns (see `spinfold simulate --list-fields`; default: all)");
  simulate_cmd->add_option("--out", sim.out, "File to write (default: stdout)");
  simulate_cmd->add_option("--crossings", sim.crossings,
                           "File for the crossings of the events that record them (:record): one row each, "
                           "with the --fields columns (.csv, .npz, else JSON Lines)");
  add_monitor_options(*simulate_cmd, sim.summaries, sim.events, sim.chaos, sim.chaos_interval);
  simulate_cmd->add_option("--max-steps", sim.max_steps_text, "Stop after this many step attempts (exit 3)");
  simulate_cmd->add_option("--max-seconds", sim.max_seconds, "Stop after this much wall time (exit 3)");
  simulate_cmd->add_flag("--quiet", sim.quiet,
                         "No progress line (there is none when stderr is not a terminal)");
  simulate_cmd->add_flag("--list-fields", sim.list_fields, "Print the column names --fields takes, and exit");
  return {simulate_cmd, [options](int argc, char** argv) {
            if (options->list_fields) {
              for (const std::string& name : sample_column_names()) std::printf("%s\n", name.c_str());
              return 0;
            }
            options->scene.command = provenance_command(argc, argv);
            return simulate(*options);
          }};
}

}  // namespace spinfold::cli
