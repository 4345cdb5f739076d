#include "cli/sweep.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "cli/run_loop.h"
#include "codec/presets.h"
#include "codec/provenance.h"
#include "codec/sample_json.h"
#include "codec/sample_table.h"
#include "codec/scene_json.h"
#include "engine/run_limits.h"
#include "engine/scene_fields.h"
#include "engine/simulation.h"
#include "engine/validation.h"

namespace spinfold::cli {

namespace {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

constexpr int kExitBadInput = 2;
// kMaxRuns, kMaxSamples: engine/run_limits.h (Python's spinfold.sweep checks the same).

struct BadInput {
  std::string message;
};

// ---- the scene's field paths, from engine/scene_fields.h ---------------------------------------

enum class Leaf { number, text };
struct FieldPath {
  std::string path;
  Leaf leaf;
  Range range{};                   // numbers: the allowed values
  std::vector<std::string> names;  // names: the allowed ones (empty: free text)
};

template <typename Table>
void collect_paths(const Table& table, const std::string& prefix, std::vector<FieldPath>& out);

template <typename V, typename F>
void collect_value(const F& field, const std::string& path, std::vector<FieldPath>& out) {
  if constexpr (std::is_same_v<V, double> || OptionalNumber<V>) {
    out.push_back({path, Leaf::number, field.range, {}});
  } else if constexpr (Enumerated<V>) {
    std::vector<std::string> names;
    for (const auto& n : enum_names(std::type_identity<V>{})) names.emplace_back(n.name);
    out.push_back({path, Leaf::text, {}, names});
  } else if constexpr (std::is_same_v<V, std::string>) {
    std::vector<std::string> names;
    if (field.text_rule == TextRule::integrator_name)
      for (std::string_view n : integrator_names()) names.emplace_back(n);
    out.push_back({path, Leaf::text, {}, names});
  } else if constexpr (HasFields<V>) {
    collect_paths(fields_of(std::type_identity<V>{}), path + ".", out);
  } else if constexpr (OptionalSection<V>) {
    collect_paths(fields_of(std::type_identity<typename V::value_type>{}), path + ".", out);
  } else if constexpr (std::is_same_v<V, DeformationPotential>) {
    std::vector<std::string> kinds;
    for (std::string_view k : kDeformationKindNames)
      if (!k.empty()) kinds.emplace_back(k);
    out.push_back({path + ".kind", Leaf::text, {}, kinds});
    for_each_deformation_kind([&](auto, auto alternative) {
      using A = typename decltype(alternative)::type;
      collect_paths(fields_of(std::type_identity<A>{}), path + ".", out);
    });
  }
}

template <typename Table>
void collect_paths(const Table& table, const std::string& prefix, std::vector<FieldPath>& out) {
  for_each_field(table, [&](const auto& field) {
    using V = typename std::decay_t<decltype(field)>::Value;
    collect_value<V>(field, prefix + std::string(field.name), out);
  });
}

const std::vector<FieldPath>& scene_paths() {
  static const std::vector<FieldPath> paths = [] {
    std::vector<FieldPath> all;
    collect_paths(kSceneFields, "", all);
    // Two deformation kinds may share a coefficient name: list each path once.
    std::vector<FieldPath> unique;
    for (FieldPath& p : all)
      if (std::none_of(unique.begin(), unique.end(), [&](const FieldPath& u) { return u.path == p.path; }))
        unique.push_back(std::move(p));
    return unique;
  }();
  return paths;
}

const FieldPath& find_path(const std::string& path, const std::string& flag) {
  for (const FieldPath& p : scene_paths())
    if (p.path == path) return p;
  std::string names;
  for (const FieldPath& p : scene_paths())
    if (p.path != "name" && p.path != "description") names += (names.empty() ? "" : ", ") + p.path;
  throw BadInput{flag + ": no scene field '" + path + "' (fields: " + names + ")"};
}

// ---- values ----------------------------------------------------------------------------------

std::optional<double> parse_number(std::string_view text) {
  // The list's syntax (spaces around an item, a '+') here; the number: the one reader.
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  return number_from_text(text);
}

std::string number_text(double v) {  // shortest round-trip text, "1" not "1.0"
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, v).ptr);
}

// Why the field cannot hold this value whatever the other fields are (its range, its names), or "".
std::string refusal(const FieldPath& field, const json& value) {
  if (field.leaf == Leaf::text) {
    const std::string text = value.get<std::string>();
    if (field.names.empty() || std::find(field.names.begin(), field.names.end(), text) != field.names.end())
      return {};
    std::string names;
    for (const std::string& n : field.names) names += (names.empty() ? "" : ", ") + n;
    return "must be one of " + names;
  }
  const double v = value.get<double>();
  const Range& r = field.range;
  if (std::abs(v) > kMaxSceneMagnitude) return "must be at most 1e100 in magnitude";
  if (!r.contains(v) || (r.min == 0.0 && r.min_open && v < kMinScenePositive)) {
    std::string bounds;
    if (r.has_min()) bounds = std::string(r.min_open ? "> " : ">= ") + number_text(r.min);
    if (r.has_max())
      bounds += (bounds.empty() ? "" : " and ") + std::string(r.max_open ? "< " : "<= ") + number_text(r.max);
    return "must be " + bounds;
  }
  return {};
}

// A value of a field, as the scene JSON holds it.
json field_value(const FieldPath& field, std::string_view text, const std::string& flag) {
  json value;
  if (field.leaf == Leaf::text) {
    value = std::string(text);
  } else {
    const auto v = parse_number(text);
    if (!v)
      throw BadInput{flag + ": " + field.path + ": not a finite number (got '" + std::string(text) + "')"};
    value = *v;
  }
  if (const std::string why = refusal(field, value); !why.empty())
    throw BadInput{flag + ": " + field.path + ": " + why + " (got '" + std::string(text) + "')"};
  return value;
}

// One axis of the sweep: fields varied together (one for --set, the table's columns for --table),
// with one tuple of values per step along it.
struct Axis {
  std::vector<const FieldPath*> fields;
  std::vector<std::vector<json>> values;
  std::string flag;  // for messages
};

std::vector<std::string> split(std::string_view text, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t at = text.find(sep, start);
    parts.emplace_back(
        text.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start));
    if (at == std::string_view::npos) return parts;
    start = at + 1;
  }
}

Axis parse_set(const std::string& spec) {
  const std::size_t eq = spec.find('=');
  if (eq == std::string::npos || eq == 0)
    throw BadInput{"--set: must be FIELD=a:b:n or FIELD=v1,v2,... (got '" + spec + "')"};
  const std::string path = spec.substr(0, eq), list = spec.substr(eq + 1);
  const std::string flag = "--set " + path;
  Axis axis{.fields = {&find_path(path, "--set")}, .values = {}, .flag = flag};
  const FieldPath& field = *axis.fields[0];
  if (field.leaf == Leaf::number && list.find(':') != std::string::npos) {
    const auto parts = split(list, ':');
    const auto a = parts.size() == 3 ? parse_number(parts[0]) : std::nullopt;
    const auto b = parts.size() == 3 ? parse_number(parts[1]) : std::nullopt;
    long n = 0;
    const bool n_ok = parts.size() == 3 &&
                      std::from_chars(parts[2].data(), parts[2].data() + parts[2].size(), n).ptr ==
                          parts[2].data() + parts[2].size() &&
                      !parts[2].empty();
    if (!a || !b || !n_ok || n < 1 || n > static_cast<long>(kMaxRuns))
      throw BadInput{flag + ": a range is a:b:n, two finite numbers and a count 1.." +
                     std::to_string(kMaxRuns) + " (got '" + list + "')"};
    // n values from a to b inclusive; the last is b itself (not a + (b − a), which can round off).
    for (long k = 0; k < n; ++k)
      axis.values.push_back(
          {k == n - 1 && n > 1 ? *b : *a + (*b - *a) * static_cast<double>(k) / static_cast<double>(n - 1)});
    if (n == 1) axis.values = {{*a}};
    for (const auto& v : axis.values)
      if (const std::string why = refusal(field, v[0]); !why.empty())
        throw BadInput{flag + ": " + field.path + ": " + why + " (got " + number_text(v[0].get<double>()) +
                       " in '" + list + "')"};
    return axis;
  }
  for (const std::string& v : split(list, ',')) {
    if (v.empty()) throw BadInput{flag + ": an empty value in '" + list + "'"};
    axis.values.push_back({field_value(field, v, flag)});
  }
  return axis;
}

Axis parse_table(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw BadInput{"--table: cannot read '" + file + "'"};
  Axis axis{.fields = {}, .values = {}, .flag = "--table " + file};
  std::string line;
  long line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line.front() == '#') continue;
    const auto cells = split(line, ',');
    if (axis.fields.empty()) {
      for (const std::string& c : cells)
        axis.fields.push_back(&find_path(c, "--table " + file + " (header)"));
      continue;
    }
    const std::string where = "--table " + file + " line " + std::to_string(line_no);
    if (cells.size() != axis.fields.size())
      throw BadInput{where + ": " + std::to_string(cells.size()) + " values for " +
                     std::to_string(axis.fields.size()) + " columns"};
    std::vector<json> row;
    for (std::size_t i = 0; i < cells.size(); ++i)
      row.push_back(field_value(*axis.fields[i], cells[i], where));
    axis.values.push_back(std::move(row));
  }
  if (axis.fields.empty() || axis.values.empty())
    throw BadInput{"--table " + file + ": needs a header of field paths and at least one row"};
  return axis;
}

// Sets the fields in a scene document. A field that stands in for others drops them (curvature
// for kind and radius, and the reverse; initial's two forms through merge_scene_patch).
void apply(json& document, const std::vector<const FieldPath*>& fields, const std::vector<json>& values) {
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const auto segments = split(fields[i]->path, '.');
    json patch = values[i];
    for (auto s = segments.rbegin(); s != segments.rend(); ++s) patch = json{{*s, std::move(patch)}};
    if (segments[0] == "surface" && document.contains("surface")) {
      json& surface = document["surface"];
      if (segments[1] == "curvature") {
        surface.erase("kind");
        surface.erase("radius");
      } else if (segments[1] == "kind" || segments[1] == "radius") {
        surface.erase("curvature");
      }
    }
    merge_scene_patch(document, patch);
  }
}

struct Column {
  std::string name;
  bool drift = false;
  std::string key;  // the flattened sample key
};

std::vector<Column> parse_fields(const std::string& list) {
  std::vector<Column> columns;
  const auto names = sample_value_names();
  for (const std::string& f : split(list, ',')) {
    if (f.empty()) continue;
    const bool drift = f.starts_with("drift.");
    const std::string key = drift ? f.substr(6) : f;
    const bool known = std::find(names.begin(), names.end(), key) != names.end() ||
                       (!drift && (key == "integrator" || key == "status_detail"));
    if (!known) throw BadInput{"--fields: unknown field '" + f + "' (see `spinfold sweep --list-fields`)"};
    columns.push_back({f, drift, key});
  }
  return columns;
}

// ---- one run -----------------------------------------------------------------------------------

struct Plan {
  SweepOptions opt;
  json base;  // the base scene's document
  std::vector<Axis> axes;
  std::size_t total = 0;
  std::vector<Column> columns;
  bool jsonl = false;
  std::size_t shard = 0, shards = 1;
  std::string command{};  // the command line (the trajectories' provenance)
};

std::vector<std::size_t> axis_steps(const Plan& plan, std::size_t index) {
  std::vector<std::size_t> steps(plan.axes.size());
  if (plan.opt.zip) {
    std::fill(steps.begin(), steps.end(), index);
    return steps;
  }
  for (std::size_t a = plan.axes.size(); a-- > 0;) {  // the last axis varies fastest
    steps[a] = index % plan.axes[a].values.size();
    index /= plan.axes[a].values.size();
  }
  return steps;
}

// The varied columns' names and this run's values, in axis order.
std::vector<std::pair<std::string, json>> varied(const Plan& plan, std::size_t index) {
  std::vector<std::pair<std::string, json>> out;
  const auto steps = axis_steps(plan, index);
  for (std::size_t a = 0; a < plan.axes.size(); ++a)
    for (std::size_t f = 0; f < plan.axes[a].fields.size(); ++f)
      out.emplace_back(plan.axes[a].fields[f]->path, plan.axes[a].values[steps[a]][f]);
  return out;
}

std::string row_text(const Plan& plan, std::size_t index,
                     const std::vector<std::pair<std::string, ojson>>& cells) {
  if (plan.jsonl) {
    ojson row;
    row["index"] = index;
    for (const auto& [name, value] : cells) row[name] = value;
    return row.dump() + "\n";
  }
  std::string line = std::to_string(index);
  for (const auto& [name, value] : cells) line += "," + csv_cell(value);
  return line + "\n";
}

std::string run_one(const Plan& plan, std::size_t index) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::pair<std::string, ojson>> cells;
  for (auto& [name, value] : varied(plan, index)) cells.emplace_back(name, ojson(value));
  std::map<std::string, ojson> first, last;
  std::string status, detail;
  std::uint64_t steps = 0, events = 0;
  try {
    json document = plan.base;
    const auto steps_along = axis_steps(plan, index);
    for (std::size_t a = 0; a < plan.axes.size(); ++a)
      apply(document, plan.axes[a].fields, plan.axes[a].values[steps_along[a]]);
    const SceneParse parsed = parse_scene(document);
    if (!parsed.errors.empty()) {
      status = "invalid_scene";
      detail = describe_errors(parsed.errors);
      while (!detail.empty() && detail.back() == '\n') detail.pop_back();
      std::replace(detail.begin(), detail.end(), '\n', ';');
    } else {
      // `spinfold simulate`'s loop: samples at k·every up to t_end, the same advances.
      std::unique_ptr<std::ofstream> trajectory;
      if (!plan.opt.trajectories.empty())
        trajectory = std::make_unique<std::ofstream>(std::filesystem::path(plan.opt.trajectories) /
                                                     (std::to_string(index) + ".jsonl"));
      if (trajectory)  // as `spinfold simulate` writes: the provenance record, then the samples
        *trajectory << ojson{{"provenance", provenance_json(*parsed.scene, plan.command + " # run " +
                                                                               std::to_string(index))}}
                           .dump()
                    << '\n';
      Simulation run = start_simulation(*parsed.scene);
      double reported_until = -1.0;
      const auto sample = [&](std::map<std::string, ojson>* into) {
        if (trajectory || into) {
          const ojson s = sample_to_json(run, reported_until);
          events += s["events"].size();
          if (trajectory) *trajectory << s.dump() << '\n';
          if (into) *into = flatten_sample(s);
        } else {
          events += events_after(run, reported_until).size();
        }
        reported_until = run.state.t;
      };
      std::uint64_t attempts = plan.opt.max_steps.value_or(kNoStepLimit);
      bool budget_left = true, started = false;
      sample_run(
          run, plan.opt.t_end, plan.opt.every,
          [&](double t) {
            return budget_left = plan.opt.max_steps ? advance_within(run, t, attempts) : advance_to(run, t);
          },
          [&] {
            const bool final = run.state.status != Status::ok || run.state.t >= plan.opt.t_end;
            sample(!started ? &first : final ? &last : nullptr);
            started = true;
          });
      if (last.empty()) last = flatten_sample(sample_to_json(run, reported_until));
      status = budget_left ? last["status"].get<std::string>() : "max_steps";
      detail =
          budget_left ? last["status_detail"].get<std::string>() : "the step budget (--max-steps) ran out";
      steps = run.steps;
    }
  } catch (const std::exception& e) {
    status = "error";
    detail = e.what();
  }
  for (const Column& c : plan.columns) {
    ojson value;
    const auto f = last.find(c.key);
    if (f != last.end()) value = f->second;
    if (c.drift) {
      const auto i = first.find(c.key);
      value = (value.is_number() && i != first.end() && i->second.is_number())
                  ? ojson(value.get<double>() - i->second.get<double>())
                  : ojson(nullptr);
    }
    cells.emplace_back(c.name, value);
  }
  cells.emplace_back("events", events);
  cells.emplace_back("status", status);
  cells.emplace_back("detail", detail);
  cells.emplace_back("steps", steps);
  cells.emplace_back("seconds",
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return row_text(plan, index, cells);
}

// ---- the sweep ---------------------------------------------------------------------------------

bool jsonl_path(const std::string& out) {
  if (out.empty() || out == "-" || out.ends_with(".csv")) return false;
  if (out.ends_with(".jsonl")) return true;
  throw BadInput{"--out: must end in .csv or .jsonl (got '" + out + "')"};
}

// What makes the rows (base scene, varied values, times, budget): shards of one sweep share it, so
// --merge can refuse a shard of another. FNV-1a, 64 bits, of a canonical text.
std::string definition(const Plan& plan) {
  std::string text = plan.base.dump() + "|t_end=" + number_text(plan.opt.t_end) +
                     "|every=" + number_text(plan.opt.every) +
                     "|max_steps=" + (plan.opt.max_steps ? std::to_string(*plan.opt.max_steps) : "") +
                     "|zip=" + (plan.opt.zip ? "1" : "0");
  for (const Axis& a : plan.axes) {
    text += "|axis";
    for (const FieldPath* f : a.fields) text += "," + f->path;
    text += "=" + json(a.values).dump();
  }
  return fnv1a64_hex(text);
}

// The base scene's hash and integrator (codec/provenance.h; the command is the header's own).
ojson base_provenance(const Plan& plan) {
  const SceneParse parsed = parse_scene(plan.base);
  if (!parsed.scene) return nullptr;
  const json p = provenance_json(*parsed.scene, "");  // sorted keys, as --merge reads them back
  return ojson(json{{"scene_hash", p["scene_hash"]}, {"integrator", p["integrator"]}});
}

// The header: for CSV comment lines and the column names, for JSON Lines one record. Everything in
// it but the command line is the same for every shard of a sweep, and for the merged output.
std::string header_text(const Plan& plan, const std::vector<std::string>& column_names,
                        const std::string& command) {
  if (plan.jsonl) {
    ojson h;
    h["sweep"] = {{"version", std::string(build_version())},
                  {"commit", std::string(build_commit())},
                  {"command", command},
                  {"runs", plan.total},
                  {"definition", definition(plan)},
                  {"shard", std::to_string(plan.shard) + "/" + std::to_string(plan.shards)},
                  {"columns", column_names}};
    h["sweep"]["base"] = base_provenance(plan);
    return h.dump() + "\n";
  }
  std::string h = "# spinfold sweep " + version_line() + "\n# command: " + command +
                  "\n# runs: " + std::to_string(plan.total) + "\n# definition: " + definition(plan) +
                  "\n# shard: " + std::to_string(plan.shard) + "/" + std::to_string(plan.shards) +
                  "\n# base: " + base_provenance(plan).dump() + "\n";
  for (std::size_t i = 0; i < column_names.size(); ++i) h += (i ? "," : "") + csv_quote(column_names[i]);
  return h + "\n";
}

std::vector<std::string> column_names(const Plan& plan) {
  std::vector<std::string> names = {"index"};
  for (const auto& [name, value] : varied(plan, 0)) names.push_back(name);
  for (const Column& c : plan.columns) names.push_back(c.name);
  for (const char* n : {"events", "status", "detail", "steps", "seconds"}) names.push_back(n);
  return names;
}

std::string read_text(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BadInput{what + ": cannot read '" + path + "'"};
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

json load_base(const std::string& base) {
  std::string text;
  if (base.empty()) {
    text = find_preset(kDefaultPreset)->json;
  } else if (std::filesystem::is_regular_file(base)) {
    text = read_text(base, "the base scene");
  } else if (const PresetSource* preset = find_preset(base)) {
    text = preset->json;
  } else {
    throw BadInput{"the base scene: '" + base + "' is neither a file nor a preset (see `spinfold scenes`)"};
  }
  const SceneParse parsed = parse_scene_text(text);
  if (!parsed.errors.empty()) throw BadInput{"the base scene: " + describe_errors(parsed.errors)};
  return scene_to_json(*parsed.scene);
}

std::pair<std::size_t, std::size_t> parse_shard(const std::string& text) {
  if (text.empty()) return {0, 1};
  const auto parts = split(text, '/');
  std::size_t i = 0, n = 0;
  const auto whole = [](const std::string& s, std::size_t& v) {
    return !s.empty() && std::from_chars(s.data(), s.data() + s.size(), v).ptr == s.data() + s.size();
  };
  if (parts.size() != 2 || !whole(parts[0], i) || !whole(parts[1], n) || n < 1 || i >= n || n > kMaxRuns)
    throw BadInput{"--shard: must be I/N with 0 <= I < N (got '" + text + "')"};
  return {i, n};
}

void draw_progress(std::size_t done, std::size_t total, std::size_t failed, double seconds) {
  constexpr int kBar = 30;
  const int filled = static_cast<int>(kBar * done / std::max<std::size_t>(1, total));
  const double rate = seconds > 0 ? static_cast<double>(done) / seconds : 0.0;
  const double left = rate > 0 ? static_cast<double>(total - done) / rate : 0.0;
  std::fprintf(stderr, "\r[%s%s] %zu/%zu runs  %zu not ok  %.1f runs/s  %.0f s left ",
               std::string(filled, '#').c_str(), std::string(kBar - filled, '.').c_str(), done, total, failed,
               rate, left);
  if (done == total) std::fputc('\n', stderr);
}

int sweep(const SweepOptions& opt, const std::string& command) {
  Plan plan{.opt = opt, .base = {}, .axes = {}, .total = 0, .columns = {}, .jsonl = jsonl_path(opt.out)};
  plan.command = command;
  if (!std::isfinite(opt.t_end) || opt.t_end < 0.0) throw BadInput{"--t-end: must be a finite number >= 0"};
  if (!std::isfinite(opt.every) || !(opt.every > 0.0)) throw BadInput{"--every: must be a finite number > 0"};
  if (opt.t_end / opt.every > kMaxSamples) throw BadInput{"--every: more than 1e7 samples requested"};
  if (opt.jobs < 0 || opt.jobs > 1024) throw BadInput{"--jobs: must be 0..1024 (0: one per core)"};
  if (opt.max_steps && *opt.max_steps == 0) throw BadInput{"--max-steps: must be >= 1"};
  std::tie(plan.shard, plan.shards) = parse_shard(opt.shard);
  plan.base = load_base(opt.base);
  for (const std::string& s : opt.sets) plan.axes.push_back(parse_set(s));
  if (!opt.table.empty()) plan.axes.push_back(parse_table(opt.table));
  if (plan.axes.empty()) throw BadInput{"sweep: nothing to vary (give --set FIELD=... or --table FILE)"};
  plan.columns = parse_fields(opt.fields);
  std::set<std::string> seen;
  for (const Axis& a : plan.axes)
    for (const FieldPath* f : a.fields)
      if (!seen.insert(f->path).second) throw BadInput{a.flag + ": " + f->path + " is varied twice"};
  // A value its field refuses whatever the rest (out of its range, not one of its names) was
  // refused above; a path that the base scene has no place for (ghat in an abc deformation) is
  // refused here, each value alone on the base. A rule that ties fields together (a rigid body's
  // mu = lambda, r <= πR) is checked for the combination each run makes: its status invalid_scene.
  for (const Axis& a : plan.axes)
    for (const auto& values : a.values) {
      json document = plan.base;
      apply(document, a.fields, values);
      std::vector<FieldError> structural;
      for (const FieldError& e : parse_scene(document).errors)
        if (e.reason == "is not a known field here") structural.push_back(e);
      if (!structural.empty()) throw BadInput{a.flag + ": " + describe_errors(structural)};
    }
  if (opt.zip) {
    for (const Axis& a : plan.axes)
      if (a.values.size() != plan.axes[0].values.size())
        throw BadInput{"--zip: every varied field needs as many values (" + plan.axes[0].flag + ": " +
                       std::to_string(plan.axes[0].values.size()) + ", " + a.flag + ": " +
                       std::to_string(a.values.size()) + ")"};
    plan.total = plan.axes[0].values.size();
  } else {
    plan.total = 1;
    for (const Axis& a : plan.axes) {
      if (plan.total > kMaxRuns / a.values.size())
        throw BadInput{"sweep: more than " + std::to_string(kMaxRuns) + " runs"};
      plan.total *= a.values.size();
    }
  }
  if (!opt.trajectories.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(opt.trajectories, ec);
    if (!std::filesystem::is_directory(opt.trajectories))
      throw BadInput{"--trajectories: cannot create the directory '" + opt.trajectories + "'"};
  }

  std::vector<std::size_t> runs;  // this shard's: i mod N = I
  for (std::size_t i = plan.shard; i < plan.total; i += plan.shards) runs.push_back(i);

  FILE* out = stdout;
  if (!opt.out.empty() && opt.out != "-") {
    out = std::fopen(opt.out.c_str(), "w");
    if (!out) throw BadInput{"--out: cannot write '" + opt.out + "'"};
  }
  std::fputs(header_text(plan, column_names(plan), command).c_str(), out);
  std::fflush(out);

  // Workers take runs in order; rows are written in run order as soon as all before them are
  // done, each flushed, so a killed sweep leaves whole lines.
  const unsigned jobs =
      opt.jobs > 0 ? static_cast<unsigned>(opt.jobs) : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::optional<std::string>> rows(runs.size());
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::size_t written = 0, done = 0, not_ok = 0;
  const bool show = !opt.quiet && isatty(fileno(stderr));
  const auto start = std::chrono::steady_clock::now();
  auto last_drawn = start - std::chrono::seconds(1);
  const auto work = [&] {
    for (std::size_t k; (k = next++) < runs.size();) {
      std::string row = run_one(plan, runs[k]);
      const bool ok = plan.jsonl ? row.find("\"status\":\"ok\"") != std::string::npos
                                 : row.find(",ok,") != std::string::npos;
      std::lock_guard lock(mutex);
      rows[k] = std::move(row);
      ++done;
      not_ok += ok ? 0 : 1;
      for (; written < rows.size() && rows[written]; ++written) {
        std::fputs(rows[written]->c_str(), out);
        std::fflush(out);
        rows[written].reset();
      }
      const auto now = std::chrono::steady_clock::now();
      if (show && (now - last_drawn > std::chrono::milliseconds(200) || done == runs.size())) {
        draw_progress(done, runs.size(), not_ok, std::chrono::duration<double>(now - start).count());
        last_drawn = now;
      }
    }
  };
  std::vector<std::thread> threads;
  for (unsigned j = 1; j < std::min<std::size_t>(jobs, runs.size()); ++j) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  if (out != stdout) std::fclose(out);
  return 0;
}

// ---- merging shards ------------------------------------------------------------------------------

struct ShardFile {
  std::vector<std::string> header;  // CSV: the comment lines and the column line; JSON Lines: one
  std::map<std::size_t, std::string> rows;
  std::size_t shard = 0, shards = 0, total = 0;
};

ShardFile read_shard(const std::string& path, bool jsonl) {
  const std::string text = read_text(path, "--merge");
  ShardFile f;
  std::size_t pos = 0;
  bool columns_seen = false;  // CSV: comment lines, then the column names, then rows
  while (pos < text.size()) {
    const std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) break;  // a line cut short by a kill: not a row
    const std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    const bool header = jsonl ? f.header.empty() : !columns_seen;
    if (!jsonl && !line.starts_with("#")) columns_seen = true;
    if (header) {
      if (jsonl) {
        const json h = json::parse(line, nullptr, false);
        if (!h.is_object() || !h.contains("sweep"))
          throw BadInput{"--merge: '" + path + "' is not a sweep's JSON Lines"};
        const auto [i, n] = parse_shard(h["sweep"].value("shard", ""));
        f.shard = i, f.shards = n, f.total = h["sweep"].value("runs", std::size_t{0});
        json canonical = h;
        canonical["sweep"].erase("command");
        canonical["sweep"].erase("shard");
        f.header.push_back(canonical.dump());
      } else if (line.starts_with("# shard: ")) {
        std::tie(f.shard, f.shards) = parse_shard(line.substr(9));
        f.header.push_back("# shard");
      } else if (line.starts_with("# runs: ")) {
        f.total = std::strtoull(line.c_str() + 8, nullptr, 10);
        f.header.push_back(line);
      } else if (line.starts_with("# command: ")) {
        f.header.push_back("# command");
      } else {
        f.header.push_back(line);
      }
      continue;
    }
    std::size_t index = 0, digits = 0;  // a row starts with its index: `7,...` or `{"index":7,...`
    if (jsonl) {
      digits = line.find("\"index\":");
      if (digits == std::string::npos) throw BadInput{"--merge: '" + path + "': a row without an index"};
      digits += 8;
    }
    const char* at = line.c_str() + digits;
    if (std::from_chars(at, line.c_str() + line.size(), index).ec != std::errc{})
      throw BadInput{"--merge: '" + path + "': a row without an index"};
    f.rows[index] = line;
  }
  if (f.header.empty() || f.shards == 0) throw BadInput{"--merge: '" + path + "' has no sweep header"};
  return f;
}

int merge(const SweepOptions& opt, const std::string& command) {
  if (opt.out.empty() || opt.out == "-") throw BadInput{"--merge: --out FILE.csv|FILE.jsonl is required"};
  const bool jsonl = jsonl_path(opt.out);
  std::vector<ShardFile> shards;
  for (const std::string& path : opt.merge) {
    if ((path.ends_with(".jsonl")) != jsonl)
      throw BadInput{"--merge: '" + path + "' is not in --out's format (" + (jsonl ? "jsonl" : "csv") + ")"};
    shards.push_back(read_shard(path, jsonl));
  }
  if (shards.empty()) throw BadInput{"--merge: no shard outputs given"};
  std::set<std::size_t> indices;
  std::map<std::size_t, std::string> rows;
  for (std::size_t s = 0; s < shards.size(); ++s) {
    const ShardFile& f = shards[s];
    if (f.header != shards[0].header || f.shards != shards[0].shards)
      throw BadInput{"--merge: '" + opt.merge[s] + "' is from another sweep (its header differs from '" +
                     opt.merge[0] + "')"};
    if (!indices.insert(f.shard).second)
      throw BadInput{"--merge: shard " + std::to_string(f.shard) + " given twice"};
    for (const auto& [i, row] : f.rows) {
      if (i >= f.total || i % f.shards != f.shard)
        throw BadInput{"--merge: '" + opt.merge[s] + "': run " + std::to_string(i) + " is not in its shard"};
      rows[i] = row;
    }
  }
  const std::size_t total = shards[0].total;
  std::string missing;
  std::size_t count = 0;
  for (std::size_t i = 0; i < total && count < 10; ++i)
    if (!rows.contains(i)) missing += (count++ ? ", " : "") + std::to_string(i);
  if (!missing.empty())
    throw BadInput{"--merge: runs missing (" + missing + (count == 10 ? ", ..." : "") + ") of " +
                   std::to_string(total) + ": give every shard's complete output"};

  FILE* out = std::fopen(opt.out.c_str(), "w");
  if (!out) throw BadInput{"--out: cannot write '" + opt.out + "'"};
  if (jsonl) {
    const json h = json::parse(shards[0].header[0]);
    // The same key order as a sweep writes.
    ojson o;
    o["sweep"] = {{"version", h["sweep"]["version"]},
                  {"commit", h["sweep"]["commit"]},
                  {"command", command},
                  {"runs", h["sweep"]["runs"]},
                  {"definition", h["sweep"]["definition"]},
                  {"shard", "0/1"},
                  {"columns", h["sweep"]["columns"]},
                  {"base", h["sweep"]["base"]}};
    std::fputs((o.dump() + "\n").c_str(), out);
  } else {
    for (const std::string& line : shards[0].header) {
      const std::string text = line == "# command" ? "# command: " + command
                               : line == "# shard" ? "# shard: 0/1"
                                                   : line;
      std::fputs((text + "\n").c_str(), out);
    }
  }
  for (const auto& [i, row] : rows) std::fputs((row + "\n").c_str(), out);
  std::fclose(out);
  return 0;
}

}  // namespace

std::vector<std::string> sweep_field_names() {
  std::vector<std::string> names(sample_value_names().begin(), sample_value_names().end());
  names.push_back("integrator");
  names.push_back("status_detail");
  for (const std::string& n : sample_value_names()) names.push_back("drift." + n);
  return names;
}

CLI::App* add_sweep_command(CLI::App& app, SweepOptions& opt) {
  opt.fields = std::string(kDefaultSweepFields);
  CLI::App* cmd =
      app.add_subcommand("sweep", "Run a scene over varied fields on every core: one row per run");
  cmd->add_option("base", opt.base,
                  "Base scene: a JSON file or a preset's name (default: the default preset)");
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
  cmd->add_option("--jobs", opt.jobs, "Runs at once (0: one per core)")->capture_default_str();
  cmd->add_option("--out", opt.out, "FILE.csv or FILE.jsonl (default: CSV on stdout)");
  cmd->add_option("--shard", opt.shard, "I/N: run only the runs i with i mod N = I (for job arrays)");
  cmd->add_option("--merge", opt.merge, "Join these shard outputs into --out, in run order");
  cmd->add_option("--trajectories", opt.trajectories,
                  "Directory: each run's samples as `simulate` prints them, INDEX.jsonl");
  cmd->add_option("--max-steps", opt.max_steps, "Step attempts per run before its status is max_steps");
  cmd->add_flag("--quiet", opt.quiet, "No progress line (there is none when stderr is not a terminal)");
  cmd->add_flag("--list-fields", opt.list_fields, "Print the names --fields accepts and exit");
  return cmd;
}

int run_sweep_command(const SweepOptions& opt, int argc, char** argv) {
  try {
    if (opt.list_fields) {
      for (const std::string& n : sweep_field_names()) std::printf("%s\n", n.c_str());
      return 0;
    }
    const std::string command = spinfold::command_line(argc, argv);
    return opt.merge.empty() ? sweep(opt, command) : merge(opt, command);
  } catch (const BadInput& e) {
    std::fprintf(stderr, "spinfold: %s%s", e.message.c_str(), e.message.ends_with('\n') ? "" : "\n");
    return kExitBadInput;
  }
}

}  // namespace spinfold::cli
