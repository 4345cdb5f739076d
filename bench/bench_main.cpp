// spinfold-bench: benchmarks with their own command, never part of the test suite.
#include <CLI/CLI.hpp>

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
  CLI11_PARSE(app, argc, argv);
  if (wp_cmd->parsed()) return spinfold::bench::run_work_precision(wp);
  return 0;
}
