#include "sweep/plan.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "codec/sample_json.h"
#include "codec/sample_table.h"
#include "codec/scene_json.h"
#include "engine/number_rule.h"
#include "engine/run_limits.h"

namespace spinfold::sweep {

using json = nlohmann::json;

namespace {

std::vector<Column> parse_columns(const std::string& list, Door door) {
  std::vector<Column> columns;
  const auto names = sample_value_names();
  for (const std::string& f : split(list, ',')) {
    if (f.empty()) continue;
    const bool drift = f.starts_with("drift.");
    const std::string key = drift ? f.substr(6) : f;
    std::vector<std::string> keys = expand_field(key, names);  // X: X.0, X.1, X.2
    if (!drift && (key == "integrator" || key == "status_detail")) keys = {key};
    if (keys.empty())
      throw SweepError(
          option_name(door, "--fields") + ": unknown field '" + f + "' (" +
          (door == Door::cli ? "see `spinfold sweep --list-fields`" : "see spinfold.sweep_fields()") + ")");
    for (const std::string& k : keys) columns.push_back({drift ? "drift." + k : k, drift, k});
  }
  return columns;
}

}  // namespace

std::vector<std::string> field_names() {
  std::vector<std::string> names(sample_value_names().begin(), sample_value_names().end());
  names.push_back("integrator");
  names.push_back("status_detail");
  for (const std::string& n : sample_value_names()) names.push_back("drift." + n);
  return names;
}

std::string option_name(Door door, std::string_view cli_flag) {
  if (door == Door::cli) return std::string(cli_flag);
  std::string name(cli_flag.substr(cli_flag.starts_with("--") ? 2 : 0));
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

void apply_values(json& document, const std::vector<const FieldPath*>& fields,
                  const std::vector<json>& values) {
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const auto segments = split(fields[i]->path, '.');
    json patch = values[i];
    for (auto s = segments.rbegin(); s != segments.rend(); ++s) patch = json{{*s, std::move(patch)}};
    merge_scene_patch(document, patch);  // a field that stands in for others drops them
  }
}

Plan make_plan(Definition def) {
  const Door door = def.door;
  const auto option = [&](std::string_view flag) { return option_name(door, flag); };
  // The run limits' rows (engine/run_limits.h), in the words simulate and Python's simulate use.
  const auto check = [&](std::string_view name, double value) {
    const RunLimit& limit = run_limit(name);
    if (allows(limit.rule, value)) return;
    std::string given = shortest(value);
    if (door == Door::cli) given = std::string("'").append(given).append("'");  // as --set quotes it
    throw SweepError(refused(option(run_limit_option(name)), must_be(limit.rule), given));
  };
  check("t_end", def.t_end);
  check("every", def.every);
  if (const auto why = samples_refusal(def.t_end, def.every))
    throw SweepError(option("--every") + ": " + *why);
  if (def.max_steps) check("max_steps", static_cast<double>(*def.max_steps));
  if (def.chaos)
    if (const auto why = chaos_interval_refusal(def.chaos_interval, def.t_end))
      throw SweepError(option("--chaos-interval") + ": " + *why);
  Plan plan;
  bool profile = false;  // the base's curvature varies: its chart is (u, φ)
  bool formula = false;  // the base is a formula surface: no chart
  {
    const SceneParse parsed = parse_scene_text(def.base_text);
    if (!parsed.errors.empty()) throw SweepError("the base scene: " + describe_errors(parsed.errors));
    plan.base = scene_to_json(*parsed.scene);
    profile = offers(parsed.scene->surface, Offer::profile_chart);
    formula = offers(parsed.scene->surface, Offer::formula);
  }
  if (profile && def.fields == kDefaultFields) def.fields = std::string(kDefaultProfileFields);
  if (formula && def.fields == kDefaultFields) def.fields = std::string(kDefaultFormulaFields);
  if (def.axes.empty())
    throw SweepError(door == Door::cli ? "sweep: nothing to vary (give --set FIELD=... or --table FILE)"
                                       : "vary: give at least one field and its values");
  plan.columns = parse_columns(def.fields, door);
  // Summaries and events in the engine's words, behind this door's option names.
  try {
    plan.monitor = parse_monitor(def.summaries, def.events);
    check_monitor(plan.monitor, *parse_scene(plan.base).scene);
  } catch (const MonitorRefusal& error) {
    throw SweepError((door == Door::cli ? (error.event ? "--event: " : "--summary: ")
                                        : (error.event ? "events: " : "summaries: ")) +
                     std::string(error.what()));
  }
  for (const EventSpec& e : plan.monitor.events)
    if (e.record > 0)
      throw SweepError(std::string(door == Door::cli ? "--event: '" : "events: '") + e.name +
                       "': a sweep's row has no room for every crossing; record them with `spinfold simulate "
                       "--crossings` or Python's simulate");
  std::set<std::string> seen;
  for (const Axis& a : def.axes)
    for (const FieldPath* f : a.fields)
      if (!seen.insert(f->path).second) throw SweepError(a.label + ": " + f->path + " is varied twice");
  // The run limit before anything per run is made.
  plan.total = run_count(def.axes, def.zip, option("--zip"));
  // A value its field refuses whatever the rest (out of its range, not one of its names) was
  // refused with its axis; a path that the base scene has no place for (ghat in an abc
  // deformation) is refused here, each value alone on the base. A rule that ties fields together
  // (a rigid body's mu = lambda, r <= πR) is checked for the combination each run makes: its
  // status invalid_scene.
  bool kind_varied = false;
  for (const Axis& a : def.axes)
    for (const FieldPath* f : a.fields) kind_varied = kind_varied || f->path == "surface.kind";
  for (const Axis& a : def.axes)
    for (const auto& values : a.values) {
      json document = plan.base;
      apply_values(document, a.fields, values);
      std::vector<FieldError> structural;
      // A field of another surface family (initial.r on a torus) is structural too, unless an axis
      // varies the surface's kind (then each run's combination decides).
      for (const FieldError& e : parse_scene(document).errors)
        if (e.reason == "is not a known field here" ||
            (!kind_varied && e.reason.starts_with("is not defined on the ")))
          structural.push_back(e);
      if (!structural.empty()) throw SweepError(a.label + ": " + describe_errors(structural));
    }
  const std::string& tf = def.trajectory_format;
  if (tf != "jsonl" && tf != "csv" && tf != "npz")
    throw SweepError(option("--trajectory-format") + ": must be jsonl, csv or npz (got '" + tf + "')");
  if (!def.trajectory_fields.empty() || tf != "jsonl") {
    if (def.trajectories.empty())
      throw SweepError(option(def.trajectory_fields.empty() ? "--trajectory-format" : "--trajectory-fields") +
                       ": give " + option("--trajectories") + " DIR too");
    // The columns simulate's --fields takes, checked on the base scene's first sample.
    const SceneParse parsed = parse_scene(plan.base);
    try {
      make_sample_table(def.trajectory_fields, sample_to_json(start_simulation(*parsed.scene), -1.0));
    } catch (const std::invalid_argument& error) {
      throw SweepError(option("--trajectory-fields") + ": " + error.what());
    }
  }
  if (!def.trajectories.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(def.trajectories, ec);
    if (!std::filesystem::is_directory(def.trajectories))
      throw SweepError(option("--trajectories") + ": cannot create the directory '" + def.trajectories + "'");
  }
  plan.def = std::move(def);
  return plan;
}

json run_document(const Plan& plan, std::size_t index) {
  json document = plan.base;
  const auto steps = axis_steps(plan.def.axes, plan.def.zip, index);
  for (std::size_t a = 0; a < plan.def.axes.size(); ++a)
    apply_values(document, plan.def.axes[a].fields, plan.def.axes[a].values[steps[a]]);
  return document;
}

std::vector<std::pair<std::string, json>> varied_values(const Plan& plan, std::size_t index) {
  std::vector<std::pair<std::string, json>> out;
  const auto steps = axis_steps(plan.def.axes, plan.def.zip, index);
  for (std::size_t a = 0; a < plan.def.axes.size(); ++a)
    for (std::size_t f = 0; f < plan.def.axes[a].fields.size(); ++f)
      out.emplace_back(plan.def.axes[a].fields[f]->path, plan.def.axes[a].values[steps[a]][f]);
  return out;
}

}  // namespace spinfold::sweep
