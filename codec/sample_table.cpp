#include "codec/sample_table.h"

#include <algorithm>
#include <stdexcept>

namespace spinfold {

using nlohmann::ordered_json;

namespace {

void flatten(const ordered_json& j, const std::string& prefix, std::map<std::string, ordered_json>& out) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) flatten(it.value(), prefix + it.key() + ".", out);
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) flatten(j[i], prefix + std::to_string(i) + ".", out);
  } else {
    out[prefix.substr(0, prefix.size() - 1)] = j;
  }
}

// A sample's nulls (actions, frequencies, M) have no members to flatten: their names come from here.
const std::vector<std::string>& value_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n = {"t",
                                  "r",
                                  "phi",
                                  "alpha",
                                  "beta",
                                  "theta",
                                  "lambda",
                                  "mu",
                                  "r_dot",
                                  "phi_dot",
                                  "alpha_dot",
                                  "beta_dot",
                                  "theta_dot",
                                  "lambda_dot",
                                  "mu_dot",
                                  "p_r",
                                  "p_phi",
                                  "p_alpha",
                                  "p_beta",
                                  "p_lambda",
                                  "p_mu",
                                  "X.0",
                                  "X.1",
                                  "X.2",
                                  "L.0.0",
                                  "L.0.1",
                                  "L.1.0",
                                  "L.1.1",
                                  "det_L",
                                  "energy",
                                  "energy_error",
                                  "energy_reference_t",
                                  "energy_orbital",
                                  "energy_deformation",
                                  "spin",
                                  "speed",
                                  "heading",
                                  "vorticity",
                                  "C_x",
                                  "C_y",
                                  "M.0",
                                  "M.1",
                                  "M.2",
                                  "casimir"};
    for (const char* a : {"J_r", "J_phi", "J_alpha", "J_beta", "J_x", "J_y"})
      n.push_back(std::string("actions.") + a);
    for (const char* f : {"r", "phi", "x", "y"}) n.push_back(std::string("frequencies.") + f);
    // Where the curvature varies: the chart (u, φ) in place of (r, φ), and the curvature at the body.
    for (const char* f : {"u", "u_dot", "p_u", "K"}) n.push_back(f);
    // On a formula surface (no chart): the body's vectors in ℝ³, the normal and the drift off F = 0.
    for (const char* v : {"V", "e1", "e2", "n"})
      for (const char* i : {".0", ".1", ".2"}) n.push_back(std::string(v) + i);
    n.push_back("constraint_drift");
    return n;
  }();
  return names;
}

const std::vector<std::string>& text_names() {
  static const std::vector<std::string> names = {"steps",         "events",     "status",
                                                 "status_detail", "integrator", "undefined"};
  return names;
}

// "actions", "frequencies", "M": values whose members are the columns.
bool is_group(const std::string& key) {
  for (const std::string& name : value_names())
    if (name.size() > key.size() && name.starts_with(key) && name[key.size()] == '.') return true;
  return false;
}

}  // namespace

std::span<const std::string> sample_value_names() {
  return value_names();
}

std::span<const std::string> sample_text_names() {
  return text_names();
}

std::vector<std::string> sample_column_names() {
  std::vector<std::string> all = value_names();
  all.insert(all.end(), text_names().begin(), text_names().end());
  return all;
}

namespace {

struct ColumnLabel {
  std::string_view name, symbol, unit;
};
// ̇ (U+0307) puts the dot of a time derivative over the symbol before it.
constexpr ColumnLabel kColumnLabels[] = {
    {"t", "t", "time"},
    {"r", "r", "length"},
    {"phi", "φ", "rad"},
    {"alpha", "α", "rad"},
    {"beta", "β", "rad"},
    {"theta", "θ", "rad"},
    {"lambda", "λ", ""},
    {"mu", "μ", ""},
    {"r_dot", "r\u0307", "length/time"},
    {"phi_dot", "φ\u0307", "rad/time"},
    {"alpha_dot", "α\u0307", "rad/time"},
    {"beta_dot", "β\u0307", "rad/time"},
    {"theta_dot", "θ\u0307", "rad/time"},
    {"lambda_dot", "λ\u0307", "1/time"},
    {"mu_dot", "μ\u0307", "1/time"},
    {"p_r", "p_r", "mass·length/time"},
    {"p_phi", "p_φ", "mass·length²/time"},
    {"p_alpha", "p_α", "mass·length²/time"},
    {"p_beta", "p_β", "mass·length²/time"},
    {"p_lambda", "p_λ", "mass·length²/time"},
    {"p_mu", "p_μ", "mass·length²/time"},
    {"X.0", "X₀", "length"},
    {"X.1", "X₁", "length"},
    {"X.2", "X₂", "length"},
    {"L.0.0", "L₀₀", ""},
    {"L.0.1", "L₀₁", ""},
    {"L.1.0", "L₁₀", ""},
    {"L.1.1", "L₁₁", ""},
    {"det_L", "det L", ""},
    {"energy", "H", "energy"},
    {"energy_error", "ΔH/H₀", ""},
    {"energy_reference_t", "t₀", "time"},
    {"energy_orbital", "E_orb", "energy"},
    {"energy_deformation", "E_def", "energy"},
    {"spin", "s", "mass·length²/time"},
    {"speed", "v", "length/time"},
    {"heading", "h", "rad"},
    {"vorticity", "p_β", "mass·length²/time"},
    {"C_x", "C_x", "energy"},
    {"C_y", "C_y", "energy"},
    {"M.0", "M₀", "mass·length²/time"},
    {"M.1", "M₁", "mass·length²/time"},
    {"M.2", "M₂", "mass·length²/time"},
    {"casimir", "C", "(mass·length²/time)²"},
    {"u", "u", ""},
    {"u_dot", "u\u0307", "1/time"},
    {"p_u", "p_u", ""},
    {"K", "K", "1/length²"},
    {"V.0", "V₀", "length/time"},
    {"V.1", "V₁", "length/time"},
    {"V.2", "V₂", "length/time"},
    {"e1.0", "e₁₀", "length"},
    {"e1.1", "e₁₁", "length"},
    {"e1.2", "e₁₂", "length"},
    {"e2.0", "e₂₀", "length"},
    {"e2.1", "e₂₁", "length"},
    {"e2.2", "e₂₂", "length"},
    {"n.0", "n₀", ""},
    {"n.1", "n₁", ""},
    {"n.2", "n₂", ""},
    {"constraint_drift", "|F|/|∇F|", "length"},
};

const ColumnLabel* column_label(std::string_view name) {
  for (const ColumnLabel& c : kColumnLabels)
    if (c.name == name) return &c;
  return nullptr;
}

}  // namespace

std::string column_symbol(std::string_view name) {
  if (const ColumnLabel* c = column_label(name)) return std::string(c->symbol);
  if (name.starts_with("actions.")) return std::string(name.substr(8));              // J_r, …
  if (name.starts_with("frequencies.")) return "ν_" + std::string(name.substr(12));  // ν_r, …
  return std::string(name);
}

std::string column_unit(std::string_view name) {
  if (const ColumnLabel* c = column_label(name)) return std::string(c->unit);
  if (name.starts_with("frequencies.")) return "1/time";
  if (name.starts_with("actions.")) return "action";
  return "";
}

std::vector<std::string> expand_field(std::string_view name, std::span<const std::string> names) {
  std::vector<std::string> out;
  for (const std::string& n : names)
    if (n == name || (n.size() > name.size() && n.starts_with(name) && n[name.size()] == '.'))
      out.push_back(n);
  return out;
}

std::vector<std::string> sample_field_names() {
  std::vector<std::string> names;
  const std::vector<std::string> columns = sample_column_names();
  for (const std::string& column : columns) {
    for (std::size_t dot = column.find('.'); dot != std::string::npos; dot = column.find('.', dot + 1)) {
      const std::string group = column.substr(0, dot);
      if (std::ranges::find(names, group) == names.end() &&
          std::ranges::find(columns, group) == columns.end())
        names.push_back(group);
    }
    names.push_back(column);
  }
  return names;
}

std::map<std::string, ordered_json> flatten_sample(const ordered_json& sample) {
  std::map<std::string, ordered_json> out;
  for (auto it = sample.begin(); it != sample.end(); ++it) {
    const std::string& key = it.key();
    if (key == "companions") continue;
    if (key == "events") {
      out["events"] = it.value().size();
    } else if (key == "undefined") {
      std::string names;
      for (auto u = it.value().begin(); u != it.value().end(); ++u) {
        if (!names.empty()) names += ';';
        names += u.key();
      }
      out["undefined"] = names;
    } else if (it.value().is_null() && is_group(key)) {
      continue;  // a null group (actions of a non-separable scene): its members' cells are empty
    } else {
      flatten(it.value(), key + ".", out);
    }
  }
  return out;
}

std::vector<std::string> SampleTable::header() const {
  std::vector<std::string> h = columns;
  for (const std::string& label : companion_labels)
    for (const std::string& c : columns) h.push_back(label + "." + c);
  return h;
}

std::vector<ordered_json> SampleTable::row(const ordered_json& sample) const {
  std::vector<ordered_json> cells;
  const auto block = [&](const ordered_json& body) {
    const auto values = flatten_sample(body);
    for (const std::string& c : columns) {
      const auto v = values.find(c);
      cells.push_back(v == values.end() ? ordered_json() : v->second);
    }
  };
  block(sample);
  const ordered_json none = ordered_json::array();
  const ordered_json& companions = sample.contains("companions") ? sample.at("companions") : none;
  for (std::size_t i = 0; i < companion_labels.size(); ++i)
    block(i < companions.size() ? companions.at(i) : ordered_json::object());
  return cells;
}

std::string SampleTable::csv_header() const {
  std::string line;
  for (const std::string& name : header()) {
    if (!line.empty()) line += ',';
    line += csv_name(name);
  }
  return line + "\n";
}

std::string SampleTable::csv_row(const ordered_json& sample) const {
  std::string line;
  bool first = true;
  for (const ordered_json& cell : row(sample)) {
    if (!first) line += ',';
    line += csv_cell(cell);
    first = false;
  }
  return line + "\n";
}

ordered_json SampleTable::json_row(const ordered_json& sample) const {
  ordered_json j = ordered_json::object();
  const std::vector<std::string> names = header();
  const std::vector<ordered_json> cells = row(sample);
  for (std::size_t i = 0; i < names.size(); ++i) j[names[i]] = cells[i];
  return j;
}

std::vector<FieldError> companion_label_errors(const Scene& scene) {
  std::vector<FieldError> errors;
  const std::vector<std::string> columns = sample_column_names();
  for (std::size_t i = 0; i < scene.companions.size(); ++i) {
    const std::string label = companion_label(scene, i),
                      field = "companions[" + std::to_string(i) + "].label";
    for (std::size_t j = 0; j < i; ++j)
      if (companion_label(scene, j) == label) {
        errors.push_back(
            {field, label,
             "is companions[" + std::to_string(j) +
                 "]'s label too: each body's columns are named by its label, which must be unique"});
        break;
      }
    const std::string prefix = label + ".";
    for (const std::string& c : columns)
      if (c.starts_with(prefix)) {
        errors.push_back({field, label,
                          "would name its columns like the main body's own (" + c +
                              "): choose a label that is not a column group"});
        break;
      }
  }
  return errors;
}

SampleTable make_sample_table(std::string_view fields, const ordered_json& first_sample) {
  SampleTable table;
  const std::vector<std::string> known = sample_column_names();
  if (fields.empty()) {
    // The chart's columns that this scene's samples have: (u, φ) and K where the curvature varies,
    // (r, φ) elsewhere; every other column always.
    // On a formula surface neither chart: X, V, e₁, e₂, n and the drift off F = 0, and K.
    const bool profile = first_sample.contains("u");
    const bool free = first_sample.contains("n");
    for (const std::string& name : known) {
      const bool polar_only = name == "r" || name == "r_dot" || name == "p_r";
      const bool profile_only = name == "u" || name == "u_dot" || name == "p_u";
      const bool free_only = name == "constraint_drift" || name.starts_with("V.") ||
                             name.starts_with("e1.") || name.starts_with("e2.") || name.starts_with("n.");
      const bool chart_angle = name == "phi" || name == "phi_dot";  // none without a chart
      const bool keep = free      ? !polar_only && !profile_only && !chart_angle
                        : profile ? !polar_only && !free_only
                                  : !profile_only && !free_only && name != "K";
      if (keep) table.columns.push_back(name);
    }
  } else {
    std::size_t start = 0;
    while (start <= fields.size()) {
      const std::size_t end = std::min(fields.find(',', start), fields.size());
      const std::string name(fields.substr(start, end - start));
      start = end + 1;
      if (name.empty()) continue;
      const std::vector<std::string> selected = expand_field(name, known);
      if (selected.empty())
        throw std::invalid_argument("unknown field '" + name + "' (the names: " + [&] {
          std::string all;
          for (const std::string& k : known) {
            if (!all.empty()) all += ", ";
            all += k;
          }
          return all;
        }() + ")");
      table.columns.insert(table.columns.end(), selected.begin(), selected.end());
    }
    if (table.columns.empty()) throw std::invalid_argument("no field named (give a comma-separated list)");
  }
  if (first_sample.contains("companions"))
    for (const ordered_json& c : first_sample.at("companions"))
      table.companion_labels.push_back(c.value("label", std::string()));
  return table;
}

std::string samples_csv(std::span<const ordered_json> samples, const SampleTable& table,
                        std::span<const std::string> comment) {
  std::string csv = table.csv_header();
  for (const std::string& line : comment) csv += "# " + line + "\n";
  for (const ordered_json& s : samples) csv += table.csv_row(s);
  return csv;
}

std::string csv_name(std::string_view name) {
  std::string text(name);
  std::replace(text.begin(), text.end(), '.', '_');
  return csv_quote(text);
}

std::string csv_cell(const ordered_json& value) {
  if (value.is_null()) return "";
  if (value.is_string()) return csv_quote(value.get<std::string>());
  return value.dump();
}

std::string csv_quote(std::string_view text) {
  std::string s(text);
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace spinfold
