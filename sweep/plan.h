// A sweep's definition (base scene, axes, times, columns) checked and made a plan: what every run of
// it is, and its columns. The CLI's `spinfold sweep` and Python's `spinfold.sweep` build one and
// hand it to sweep/run.h; its rules (times, the field columns, the run limit) are here only.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/chaos_indicators.h"
#include "engine/run_summary.h"
#include "sweep/grid.h"

namespace spinfold::sweep {

// The columns a sweep writes by default after the varied fields (CLI and Python alike).
inline constexpr std::string_view kDefaultFields =
    "t,r,phi,lambda,mu,energy,energy_error,drift.energy,drift.p_phi";
// The same where the base scene's curvature varies: its chart's u in place of r, and K at the end.
inline constexpr std::string_view kDefaultProfileFields =
    "t,u,phi,lambda,mu,energy,energy_error,drift.energy,drift.p_phi,K";
// On a formula surface (no chart): the position in ℝ³, the drift off the surface, K at the end.
inline constexpr std::string_view kDefaultFormulaFields =
    "t,X.0,X.1,X.2,lambda,mu,energy,energy_error,drift.energy,spin,constraint_drift,K";

// The names `fields` accepts: final-state values of a sample (nested ones flattened with dots:
// X.0, L.0.1, actions.J_r, frequencies.r), integrator, status_detail, and drift.NAME (final minus
// initial) of the numeric ones.
std::vector<std::string> field_names();

// Which front door's names messages use for the options: the CLI's (`--t-end`) or Python's (`t_end`).
enum class Door { cli, python };
// The option `cli_flag` ("--t-end") as `door` spells it.
std::string option_name(Door door, std::string_view cli_flag);

struct Definition {
  std::string base_text;  // the base scene's JSON text (a file's, a preset's)
  std::vector<Axis> axes;
  bool zip = false;
  double t_end = 10.0;
  double every = 0.5;
  std::optional<std::uint64_t> max_steps;
  std::string fields = std::string(kDefaultFields);  // comma-separated field_names()
  // What each run did (engine/run_summary.h): summaries ("r", "r.max") and events ("r:up:1.2").
  std::vector<std::string> summaries;
  std::vector<std::string> events;
  // The maximal Lyapunov exponent and MEGNO of each run (engine/chaos_indicators.h), every interval.
  bool chaos = false;
  double chaos_interval = kDefaultChaosInterval;
  std::string trajectories;  // a directory for each run's samples as `simulate` prints them, or ""
  // Their columns (simulate's --fields; "": every sample value, JSON Lines only) and format.
  std::string trajectory_fields;
  std::string trajectory_format = "jsonl";  // jsonl | csv | npz
  std::string command;                      // the command line (the trajectories' provenance)
  Door door = Door::cli;
};

struct Column {
  std::string name;
  bool drift = false;
  std::string key;  // the flattened sample key
};

struct Plan {
  Definition def;
  nlohmann::json base;  // the base scene's canonical document
  std::vector<Column> columns;
  MonitorSpec monitor;    // the summaries and events, parsed
  std::size_t total = 0;  // runs
};

// Checks the definition (times, fields, base scene, each axis's values on the base, the run limit)
// and makes the plan; SweepError naming what is wrong. Creates the trajectories' directory.
Plan make_plan(Definition def);

// Run `index`'s scene document: the base with its values set (may be a scene the engine refuses).
nlohmann::json run_document(const Plan& plan, std::size_t index);
// The varied columns' names and run `index`'s values, in axis order.
std::vector<std::pair<std::string, nlohmann::json>> varied_values(const Plan& plan, std::size_t index);

// Sets an axis's fields in a scene document through merge_scene_patch, so that a field that stands
// in for others drops them (curvature for kind and radius, spin for alpha_dot, and the reverse).
void apply_values(nlohmann::json& document, const std::vector<const FieldPath*>& fields,
                  const std::vector<nlohmann::json>& values);

}  // namespace spinfold::sweep
