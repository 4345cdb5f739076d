// The subcommands of `spinfold`, one file each (cli/commands/<name>.cpp): register_<name> adds the
// subcommand and its options to the app and returns what runs it once parsed. cli/main.cpp has the
// table of them. A command translates its options and calls the libraries; it decides nothing.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "codec/provenance.h"
#include "engine/number_text.h"
#include "engine/run_limits.h"
#include "engine/state.h"

namespace spinfold::cli {

inline constexpr int kExitBadInput = 2;
inline constexpr int kExitRunStopped = 3;

// Bad input: main prints "spinfold: MESSAGE" on stderr and exits 2.
struct BadInput {
  std::string message;
};

// A run limit as given (engine/run_limits.h): the row's rule and words, BadInput naming the option.
inline void check_run_limit(std::string_view name, double value) {
  const RunLimit& limit = run_limit(name);
  if (!allows(limit.rule, value))
    throw BadInput{refused(run_limit_option(name), must_be(limit.rule), "'" + shortest(value) + "'")};
}

// A run limit given as text, read by the one number reader (engine/number_rule.h).
inline double run_limit_value(std::string_view name, const std::string& text) {
  const RunLimit& limit = run_limit(name);
  const std::optional<double> x = number_from_text(text);
  if (!x || !allows(limit.rule, *x))
    throw BadInput{refused(run_limit_option(name), must_be(limit.rule), "'" + text + "'")};
  return *x;
}

// The exit code of a run that reached its end or stopped: 0, or kExitRunStopped with the reason on
// stderr (render, plot).
inline int run_exit_code(const State& state) {
  if (state.status == Status::ok || state.status == Status::event_stop) return 0;
  std::cerr << "spinfold: run stopped at t = " << state.t << ": " << status_name(state.status) << "\n";
  return kExitRunStopped;
}

// --summary and --event (engine/run_summary.h's grammar) and --chaos (engine/chaos_indicators.h), as
// simulate and sweep take them.
inline void add_monitor_options(CLI::App& cmd, std::vector<std::string>& summaries,
                                std::vector<std::string>& events, bool& chaos, double& chaos_interval) {
  cmd.add_option(
         "--summary", summaries,
         "Reductions over the run's own steps: FIELD (its min, max, mean, final, t_min, t_max) or "
         "FIELD.REDUCTION; comma-separated, repeatable (fields: r or u, phi, lambda, mu, det_L, energy, "
         "energy_error, spin, speed, X.0-2, K)")
      ->delimiter(',');
  cmd.add_option(
      "--event", events,
      "FIELD:up|down|any:LEVEL[:period=P][:stop=N][:name=NAME]: a crossing located inside the steps; "
      "its count, first and last time (stop=N ends the run at the N-th); repeatable");
  CLI::Option* chaos_flag = cmd.add_flag(
      "--chaos", chaos,
      "Add the maximal Lyapunov exponent and MEGNO (chaos.lyapunov, chaos.megno, chaos.megno_mean, "
      "chaos.lyapunov_time, chaos.t): two more runs, a shadow restarted every --chaos-interval");
  cmd.add_option("--chaos-interval", chaos_interval, "The shadow's restart interval [time]")
      ->capture_default_str()
      ->needs(chaos_flag);
}

// The command line for an output's provenance: codec/provenance.h's command_line, or while
// `spinfold rerun` runs a recorded command (cli/commands/rerun.cpp) the line it recorded, so the
// re-run's bytes are the output's.
inline std::optional<std::string>& recorded_command() {  // set by rerun while it runs one
  static std::optional<std::string> command;
  return command;
}
inline std::string provenance_command(int argc, const char* const* argv) {
  return recorded_command() ? *recorded_command() : command_line(argc, argv);
}

// The whole command line parsed and run (cli/main.cpp): what main returns; rerun runs its recorded
// command through it.
int run_command_line(int argc, char** argv);

// A registered subcommand: run(argc, argv) when it is the one parsed (argv for the provenance).
struct Command {
  CLI::App* app = nullptr;
  std::function<int(int argc, char** argv)> run;
};

Command register_simulate(CLI::App& app);
Command register_sweep(CLI::App& app);
Command register_scenes(CLI::App& app);
Command register_integrators(CLI::App& app);
Command register_rerun(CLI::App& app);
#ifndef SPINFOLD_COMPUTE_ONLY
Command register_render(CLI::App& app);
Command register_record(CLI::App& app);
Command register_work_precision(CLI::App& app);
Command register_plot(CLI::App& app);
Command register_serve(CLI::App& app);
#endif

}  // namespace spinfold::cli
