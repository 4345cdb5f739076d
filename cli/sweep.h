// `spinfold sweep`: many runs of one base scene with fields varied, in this process on a thread
// pool, one result row per run (CSV or JSON Lines), written in run order and flushed row by row.
// `--shard I/N` runs a deterministic slice (runs i with i mod N = I); `--merge` joins the shards'
// outputs into the rows one process would have written. Each run takes the code path of
// `spinfold simulate`, so its numbers are the same to the bit.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace spinfold::cli {

struct SweepOptions {
  std::string base;               // a scene file, or a preset's name
  std::vector<std::string> sets;  // "FIELD=a:b:n" or "FIELD=v1,v2,…"
  std::string table;              // a CSV: a header of field paths, one row per run
  bool zip = false;               // pair the varied values instead of their Cartesian product
  double t_end = 10.0;
  double every = 0.5;
  std::string fields;              // the final-state and drift columns (sweep_field_names())
  int jobs = 0;                    // 0: one per core
  std::string out;                 // FILE.csv or FILE.jsonl; "" or "-": CSV on stdout
  std::string shard;               // "I/N"
  std::vector<std::string> merge;  // shard outputs to join
  std::string trajectories;        // a directory: each run's samples as `simulate` prints them
  std::optional<std::uint64_t> max_steps;
  bool quiet = false;
  bool list_fields = false;
};

inline constexpr std::string_view kDefaultSweepFields =
    "t,r,phi,lambda,mu,energy,energy_error,drift.energy,drift.p_phi";

// Registers the subcommand; `opt` must outlive the parse.
CLI::App* add_sweep_command(CLI::App& app, SweepOptions& opt);

// Runs the parsed subcommand (or the merge). Bad input: a message on stderr, exit code 2; a run
// that fails is its row's status. `argv` is written into the output's header.
int run_sweep_command(const SweepOptions& opt, int argc, char** argv);

// argv as one line, arguments with blanks or quotes single-quoted (the outputs' `# command:` header).
std::string command_line(int argc, char** argv);

// The names --fields accepts: final-state values of a sample (nested ones flattened with dots:
// X.0, L.0.1, actions.J_r, frequencies.r) and drift.NAME (final minus initial) of the numeric ones.
std::vector<std::string> sweep_field_names();

}  // namespace spinfold::cli
