#include "sweep/rows.h"

#include "codec/provenance.h"
#include "codec/sample_table.h"
#include "codec/scene_json.h"

namespace spinfold::sweep {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

Format format_of(const std::string& out) {
  if (out.empty() || out == "-" || out.ends_with(".csv")) return Format::csv;
  if (out.ends_with(".jsonl")) return Format::jsonl;
  if (out.ends_with(".npz")) return Format::npz;
  throw SweepError("--out: must end in .csv, .jsonl or .npz (got '" + out + "')");
}

std::vector<std::string> column_names(const Plan& plan) {
  std::vector<std::string> names = {"index"};
  for (const Axis& a : plan.def.axes)
    for (const FieldPath* f : a.fields) names.push_back(f->path);
  for (const Column& c : plan.columns) names.push_back(c.name);
  for (const std::string& c : monitor_columns(plan.monitor)) names.push_back(c);
  if (plan.def.chaos)
    for (const std::string_view c : kChaosColumns) names.emplace_back(c);
  for (const char* n : {"events", "status", "detail", "steps", "seconds"}) names.push_back(n);
  return names;
}

std::string definition_hash(const Plan& plan) {
  const Definition& def = plan.def;
  std::string text =
      plan.base.dump() + "|t_end=" + number_text(def.t_end) + "|every=" + number_text(def.every) +
      "|max_steps=" + (def.max_steps ? std::to_string(*def.max_steps) : "") + "|zip=" + (def.zip ? "1" : "0");
  for (const std::string& m : def.summaries) text += "|summary=" + m;
  for (const std::string& e : def.events) text += "|event=" + e;
  if (def.chaos) text += "|chaos=" + number_text(def.chaos_interval);
  for (const Axis& a : def.axes) {
    text += "|axis";
    for (const FieldPath* f : a.fields) {
      text += ',';
      text += f->path;
    }
    text += '=';
    text += json(a.values).dump();
  }
  return fnv1a64_hex(text);
}

namespace {

// The base scene's hash and integrator (codec/provenance.h; the command is the header's own).
ojson base_provenance(const Plan& plan) {
  const SceneParse parsed = parse_scene(plan.base);
  if (!parsed.scene) return nullptr;
  const json p = provenance_json(*parsed.scene, "");  // sorted keys, as a merge reads them back
  // the base scene as given (before --set), so a shard re-runs without its file (spinfold rerun)
  return ojson(json{{"scene_hash", p["scene_hash"]}, {"integrator", p["integrator"]}, {"scene", plan.base}});
}

}  // namespace

std::string header_text(const Plan& plan, Format format, Shard shard, const std::string& command) {
  const std::vector<std::string> names = column_names(plan);
  const std::string shard_text = std::to_string(shard.index) + "/" + std::to_string(shard.count);
  if (format == Format::jsonl) {
    ojson h;
    h["sweep"] = {{"version", std::string(build_version())},
                  {"commit", std::string(build_commit())},
                  {"command", command},
                  {"runs", plan.total},
                  {"definition", definition_hash(plan)},
                  {"shard", shard_text},
                  {"columns", names}};
    h["sweep"]["base"] = base_provenance(plan);
    return h.dump() + "\n";
  }
  // The names first (numpy.genfromtxt takes them from the first line), then the provenance.
  std::string h;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i) h += ',';
    h += csv_name(names[i]);
  }
  return h + "\n# spinfold sweep " + version_line() + "\n# command: " + command +
         "\n# runs: " + std::to_string(plan.total) + "\n# definition: " + definition_hash(plan) +
         "\n# shard: " + shard_text + "\n# base: " + base_provenance(plan).dump() + "\n";
}

std::string row_text(const Row& row, Format format) {
  if (format == Format::jsonl) {
    ojson o;
    o["index"] = row.index;
    for (const auto& [name, value] : row.cells) o[name] = value;
    return o.dump() + "\n";
  }
  std::string line = std::to_string(row.index);
  for (const auto& [name, value] : row.cells) {
    line += ',';
    line += csv_cell(value);
  }
  return line + "\n";
}

}  // namespace spinfold::sweep
