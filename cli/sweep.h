// `spinfold sweep`: the front door of the sweep library (sweep/): it parses the options, calls the
// library (grid, plan, runs, shards, rows) and writes the rows to a file or stdout, row by row.
// Python's `spinfold.sweep` calls the same library, so both give the same rows for one definition.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace spinfold::cli {

struct SweepOptions {
  std::string base;               // a scene file, or a preset's name (codec/scene_source.h)
  std::string scene;              // --scene: the same, named
  std::vector<std::string> sets;  // "FIELD=a:b:n" or "FIELD=v1,v2,…"
  std::string table;              // a CSV: a header of field paths, one row per run
  bool zip = false;               // pair the varied values instead of their Cartesian product
  double t_end = 10.0;
  double every = 0.5;
  std::string fields;                  // the final-state and drift columns (sweep::field_names())
  std::vector<std::string> summaries;  // "r", "r.max" (engine/run_summary.h)
  std::vector<std::string> events;     // "r:up:1.2[:period=P][:stop=N][:name=NAME]"
  bool chaos = false;                  // the Lyapunov exponent and MEGNO (engine/chaos_indicators.h)
  double chaos_interval = 1.0;
  int jobs = 0;                             // 0: one per core
  std::string out;                          // FILE.csv or FILE.jsonl; "" or "-": CSV on stdout
  std::string shard;                        // "I/N"
  std::vector<std::string> merge;           // shard outputs to join
  std::string trajectories;                 // a directory: each run's samples as `simulate` prints them
  std::string trajectory_fields;            // their columns (simulate's --fields); "": the whole sample
  std::string trajectory_format = "jsonl";  // jsonl | csv | npz
  std::optional<std::string> max_steps;     // as given: read by run_limit_value (engine/run_limits.h)
  bool quiet = false;
  bool list_fields = false;
};

// Registers the subcommand; `opt` must outlive the parse.
CLI::App* add_sweep_command(CLI::App& app, SweepOptions& opt);

// Runs the parsed subcommand (or the merge). Bad input: a message on stderr, exit code 2; a run
// that fails is its row's status. `argv` is written into the output's header.
int run_sweep_command(const SweepOptions& opt, int argc, char** argv);

}  // namespace spinfold::cli
