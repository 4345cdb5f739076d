#include "cli/sweep.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include "cli/commands/command.h"
#include "codec/npz_writer.h"
#include "codec/output_file.h"
#include "codec/provenance.h"
#include "codec/scene_source.h"
#include "sweep/grid.h"
#include "sweep/plan.h"
#include "sweep/rows.h"
#include "sweep/run.h"
#include "sweep/shard.h"

namespace spinfold::cli {

namespace {

using sweep::SweepError;

std::string read_text(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SweepError(what + ": cannot read '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The base scene by the one scene rule (codec/scene_source.h): a file if one has that name, else a
// preset; none: the default preset.
std::string base_text(const SweepOptions& opt) {
  try {
    return scene_source(opt.base, opt.scene).text;
  } catch (const SceneSourceError& e) {
    throw SweepError(std::string("the base scene: ") + e.what());
  }
}

void draw_progress(const sweep::Progress& p, double seconds) {
  constexpr int kBar = 30;
  const int filled = static_cast<int>(kBar * p.done / std::max<std::size_t>(1, p.total));
  const double rate = seconds > 0 ? static_cast<double>(p.done) / seconds : 0.0;
  const double left = rate > 0 ? static_cast<double>(p.total - p.done) / rate : 0.0;
  std::fprintf(stderr, "\r[%s%s] %zu/%zu runs  %zu not ok  %.1f runs/s  %.0f s left ",
               std::string(filled, '#').c_str(), std::string(kBar - filled, '.').c_str(), p.done, p.total,
               p.not_ok, rate, left);
  if (p.done == p.total) std::fputc('\n', stderr);
}

int run_sweep(const SweepOptions& opt, const std::string& command) {
  const sweep::Format format = sweep::format_of(opt.out);
  if (opt.jobs < 0 || opt.jobs > 1024) throw SweepError("--jobs: must be 0..1024 (0: one per core)");
  const sweep::Shard shard = sweep::parse_shard(opt.shard);
  std::optional<std::uint64_t> max_steps;  // read as simulate reads it: "-1" is refused, not wrapped
  if (opt.max_steps) max_steps = static_cast<std::uint64_t>(run_limit_value("max_steps", *opt.max_steps));
  sweep::Definition def{.base_text = base_text(opt),
                        .axes = {},
                        .zip = opt.zip,
                        .t_end = opt.t_end,
                        .every = opt.every,
                        .max_steps = max_steps,
                        .fields = opt.fields,
                        .summaries = opt.summaries,
                        .events = opt.events,
                        .chaos = opt.chaos,
                        .chaos_interval = opt.chaos_interval,
                        .trajectories = opt.trajectories,
                        .trajectory_fields = opt.trajectory_fields,
                        .trajectory_format = opt.trajectory_format,
                        .command = command,
                        .door = sweep::Door::cli};
  for (const std::string& s : opt.sets) def.axes.push_back(sweep::axis_from_assignment(s));
  if (!opt.table.empty())
    def.axes.push_back(sweep::axis_from_table(read_text(opt.table, "--table"), "--table " + opt.table));
  const sweep::Plan plan = sweep::make_plan(std::move(def));
  const std::vector<std::size_t> runs = sweep::shard_runs(plan.total, shard);

  if (format == sweep::Format::npz) {  // one array per column, written when every row is in
    const std::vector<std::string> names = sweep::column_names(plan);
    std::vector<NpzColumn> columns;
    for (const std::string& name : names) columns.push_back({name, {}});
    sweep::run_all(plan, runs, static_cast<unsigned>(opt.jobs), [&](sweep::Row&& row) {
      columns[0].cells.emplace_back(row.index);
      for (std::size_t i = 0; i < row.cells.size(); ++i)
        columns[i + 1].cells.push_back(std::move(row.cells[i].second));
    });
    columns.push_back({"provenance", {sweep::header_text(plan, sweep::Format::jsonl, shard, command)}});
    try {
      write_npz(opt.out, columns);
    } catch (const std::runtime_error& e) {
      throw SweepError(std::string("--out: ") + e.what());
    }
    return 0;
  }
  std::optional<OutputFile> opened;
  try {
    opened.emplace(opt.out);
  } catch (const WriteError& e) {
    throw SweepError(std::string("--out: ") + e.what());
  }
  OutputFile& out = *opened;
  // Every write checked (a full disk stops the sweep at that row: exit 1, naming the file).
  const auto put = [&](const std::string& text) {
    out.write(text);
    out.flush();
  };
  put(sweep::header_text(plan, format, shard, command));
  // Each row flushed as it comes, so a killed sweep leaves whole lines.
  const bool show = !opt.quiet && isatty(fileno(stderr));
  const auto start = std::chrono::steady_clock::now();
  auto last_drawn = start - std::chrono::seconds(1);
  sweep::run_all(
      plan, runs, static_cast<unsigned>(opt.jobs),
      [&](sweep::Row&& row) { put(sweep::row_text(row, format)); },
      [&](const sweep::Progress& p) {
        const auto now = std::chrono::steady_clock::now();
        if (show && (now - last_drawn > std::chrono::milliseconds(200) || p.done == p.total)) {
          draw_progress(p, std::chrono::duration<double>(now - start).count());
          last_drawn = now;
        }
      });
  out.close();
  return 0;
}

}  // namespace

CLI::App* add_sweep_command(CLI::App& app, SweepOptions& opt) {
  opt.fields = std::string(sweep::kDefaultFields);
  CLI::App* cmd =
      app.add_subcommand("sweep", "Run a scene over varied fields on every core: one row per run");
  cmd->add_option(
      "base", opt.base,
      "Base scene: a scene file, or a preset's name if no file has it (default: the default preset)");
  cmd->add_option("--scene", opt.scene, "The base scene named as the other commands name theirs");
  cmd->add_option(
         "--set", opt.sets,
         "FIELD=a:b:n (n values from a to b) or FIELD=v1,v2,...; FIELD a scene path such as initial.r, "
         "surface.curvature, potential.radial.gamma, integrator.name (repeatable)")
      ->allow_extra_args(false);
  cmd->add_option("--table", opt.table, "CSV: a header of field paths, then one row of values per run");
  cmd->add_flag("--zip", opt.zip, "Pair the varied values (all as many) instead of their Cartesian product");
  cmd->add_option("--t-end", opt.t_end, "Simulated time of each run")->capture_default_str();
  cmd->add_option("--every", opt.every, "Sample interval (as simulate's)")->capture_default_str();
  cmd->add_option("--fields", opt.fields, "Final-state and drift.NAME columns (see --list-fields)")
      ->capture_default_str();
  add_monitor_options(*cmd, opt.summaries, opt.events, opt.chaos, opt.chaos_interval);
  cmd->add_option("--jobs", opt.jobs, "Runs at once (0: one per core)")->capture_default_str();
  cmd->add_option("--out", opt.out, "FILE.csv, FILE.jsonl or FILE.npz (default: CSV on stdout)");
  cmd->add_option("--shard", opt.shard, "I/N: run only the runs i with i mod N = I (for job arrays)");
  cmd->add_option("--merge", opt.merge, "Join these shard outputs into --out, in run order");
  cmd->add_option("--trajectories", opt.trajectories,
                  "Directory: each run's samples as `simulate` prints them, INDEX.jsonl");
  cmd->add_option("--trajectory-fields", opt.trajectory_fields,
                  "The trajectories' columns, as simulate's --fields (default: every sample value)");
  cmd->add_option("--trajectory-format", opt.trajectory_format, "jsonl | csv | npz")->capture_default_str();
  cmd->add_option("--max-steps", opt.max_steps, "Step attempts per run before its status is max_steps");
  cmd->add_flag("--quiet", opt.quiet, "No progress line (there is none when stderr is not a terminal)");
  cmd->add_flag("--list-fields", opt.list_fields, "Print the names --fields accepts and exit");
  return cmd;
}

int run_sweep_command(const SweepOptions& opt, int argc, char** argv) {
  try {
    if (opt.list_fields) {
      for (const std::string& n : sweep::field_names()) std::printf("%s\n", n.c_str());
      return 0;
    }
    const std::string command = provenance_command(argc, argv);
    if (!opt.merge.empty()) {
      sweep::merge_shards(opt.merge, opt.out, command);
      return 0;
    }
    return run_sweep(opt, command);
  } catch (const SweepError& e) {
    const std::string message = e.what();
    std::fprintf(stderr, "spinfold: %s%s", message.c_str(), message.ends_with('\n') ? "" : "\n");
    return kExitBadInput;
  } catch (const BadInput& e) {
    std::fprintf(stderr, "spinfold: %s\n", e.message.c_str());
    return kExitBadInput;
  }
}

}  // namespace spinfold::cli
