// Work-precision benchmark: run time per unit simulated time against the error at T, for every
// integrator of the catalog and for Boost.Odeint's steppers integrating the same equations.
#pragma once

#include <string>
#include <vector>

namespace spinfold::bench {

struct WorkPrecisionOptions {
  std::vector<std::string> scenes;  // empty: all
  std::string out_dir = "out/work_precision";
  double periods = 100.0;            // T in characteristic periods
  double target_error = 1e-10;       // the error at which methods are compared
  double max_seconds_per_run = 1.0;  // stop refining a fixed-step sweep beyond this
};

// Writes work_precision.csv, one plot per scene (<scene>.png and .svg, and <scene>.gp as an export)
// and summary.md into out_dir; prints the summary. Returns 0, or 2 (nothing written) for an unknown
// scene name. The sweeps, the reference and the plots are workprecision/'s, as `spinfold
// work-precision` runs them on any scene.
int run_work_precision(const WorkPrecisionOptions& options);

}  // namespace spinfold::bench
