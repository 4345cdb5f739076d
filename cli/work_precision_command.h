// `spinfold work-precision SCENE.json | --scene PRESET [--integrators a,b] [--t-end T]
// [--target-error E] --out DIR` (issue 24): run time against error for each integrator on any scene,
// measured against the most accurate reference there is for it (workprecision/work_precision.h).
// DIR gets work_precision.csv, work_precision.{gp,png,svg} and summary.md; the summary is printed.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace spinfold::cli {

struct WorkPrecisionOptions {
  std::string scene_file;
  std::string preset;
  std::string integrators;      // comma-separated catalog names and/or auto; "": all
  std::optional<double> t_end;  // [time]; default work_precision::default_t_end
  double target_error = 1e-10;  // the error the recommendation is made for
  double max_seconds_per_run = 1.0;
  std::string out;
};

// Registers the subcommand; `opt` must outlive the parse.
CLI::App* add_work_precision_command(CLI::App& app, WorkPrecisionOptions& opt);

// Runs it. Bad input (unknown preset or integrator, unreadable or invalid scene, bad option): a
// message on stderr, exit code 2, nothing written. `argv` goes into the CSV's header.
int run_work_precision_command(const WorkPrecisionOptions& opt, int argc, char** argv);

}  // namespace spinfold::cli
