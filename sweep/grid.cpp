#include "sweep/grid.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "engine/validation.h"

namespace spinfold::sweep {

using json = nlohmann::json;

std::vector<double> grid_values(double a, double b, std::size_t n) {
  if (n <= 1) return {a};
  std::vector<double> values(n);
  const double delta = b - a, div = static_cast<double>(n - 1), step = delta / div;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double y = static_cast<double>(k);
    values[k] = (step == 0.0 ? (y / div) * delta : y * step) + a;
  }
  values[n - 1] = b;
  return values;
}

namespace {

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

// A value of a field from its text, as the scene JSON holds it.
json field_value(const FieldPath& field, std::string_view text, const std::string& where) {
  json value;
  if (field.leaf == Leaf::text) {
    value = std::string(text);
  } else {
    const auto v = parse_number(text);
    if (!v)
      throw SweepError(where + ": " + field.path + ": not a finite number (got '" + std::string(text) + "')");
    value = *v;
  }
  if (const std::string why = refusal(field, value); !why.empty())
    throw SweepError(where + ": " + field.path + ": " + why + " (got '" + std::string(text) + "')");
  return value;
}

}  // namespace

const FieldPath& scene_field(const std::string& path, const std::string& where) {
  if (const FieldPath* p = find_scene_path(path)) return *p;
  std::string names;
  for (const FieldPath& p : scene_paths())
    if (p.path != "name" && p.path != "description") names += (names.empty() ? "" : ", ") + p.path;
  throw SweepError(where + ": no scene field '" + path + "' (fields: " + names + ")");
}

// ---- values ----------------------------------------------------------------------------------

std::optional<double> parse_number(std::string_view text) {
  // The list's syntax (spaces around an item, a '+') here; the number: the one reader.
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  return number_from_text(text);
}

std::string number_text(double v) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, v).ptr);
}

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

// ---- axes ------------------------------------------------------------------------------------

Axis axis_from_spec(const std::string& path, const std::string& spec, const std::string& label) {
  Axis axis{.fields = {&scene_field(path, label)}, .values = {}, .label = label};
  const FieldPath& field = *axis.fields[0];
  if (field.leaf == Leaf::number && spec.find(':') != std::string::npos) {
    const auto parts = split(spec, ':');
    const auto a = parts.size() == 3 ? parse_number(parts[0]) : std::nullopt;
    const auto b = parts.size() == 3 ? parse_number(parts[1]) : std::nullopt;
    std::size_t n = 0;
    const bool n_ok = parts.size() == 3 && !parts[2].empty() &&
                      std::from_chars(parts[2].data(), parts[2].data() + parts[2].size(), n).ptr ==
                          parts[2].data() + parts[2].size();
    if (!a || !b || !n_ok || n < 1 || n > kMaxRuns)
      throw SweepError(label + ": a range is a:b:n, two finite numbers and a count 1.." +
                       std::to_string(kMaxRuns) + " (got '" + spec + "')");
    for (const double v : grid_values(*a, *b, n)) {
      if (const std::string why = refusal(field, v); !why.empty())
        throw SweepError(label + ": " + field.path + ": " + why + " (got " + number_text(v) + " in '" + spec +
                         "')");
      axis.values.push_back({v});
    }
    return axis;
  }
  for (const std::string& v : split(spec, ',')) {
    if (v.empty()) throw SweepError(label + ": an empty value in '" + spec + "'");
    axis.values.push_back({field_value(field, v, label)});
  }
  return axis;
}

Axis axis_from_assignment(const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SweepError("--set: must be FIELD=a:b:n or FIELD=v1,v2,... (got '" + assignment + "')");
  const std::string path = assignment.substr(0, eq);
  scene_field(path, "--set");  // an unknown path named as --set's
  return axis_from_spec(path, assignment.substr(eq + 1), "--set " + path);
}

Axis axis_from_values(const std::string& path, const json& values, const std::string& label) {
  Axis axis{.fields = {&scene_field(path, label)}, .values = {}, .label = label};
  const FieldPath& field = *axis.fields[0];
  if (!values.is_array() || values.empty()) throw SweepError(label + ": give at least one value");
  if (values.size() > kMaxRuns)
    throw SweepError(label + ": more than " + std::to_string(kMaxRuns) + " values");
  for (const json& v : values) {
    const bool number = field.leaf == Leaf::number;
    if (number ? !v.is_number() : !v.is_string())
      throw SweepError(label + ": " + field.path + ": " + (number ? "not a finite number" : "not a text") +
                       " (got " + v.dump() + ")");
    const json value = number ? json(v.get<double>()) : v;
    if (number && !std::isfinite(value.get<double>()))
      throw SweepError(label + ": " + field.path + ": not a finite number (got " + v.dump() + ")");
    if (const std::string why = refusal(field, value); !why.empty())
      throw SweepError(label + ": " + field.path + ": " + why + " (got " + v.dump() + ")");
    axis.values.push_back({value});
  }
  return axis;
}

Axis axis_from_table(const std::string& csv_text, const std::string& label) {
  Axis axis{.fields = {}, .values = {}, .label = label};
  long line_no = 0;
  for (std::string line : split(csv_text, '\n')) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line.front() == '#') continue;
    const auto cells = split(line, ',');
    if (axis.fields.empty()) {
      for (const std::string& c : cells) axis.fields.push_back(&scene_field(c, label + " (header)"));
      continue;
    }
    const std::string where = label + " line " + std::to_string(line_no);
    if (cells.size() != axis.fields.size())
      throw SweepError(where + ": " + std::to_string(cells.size()) + " values for " +
                       std::to_string(axis.fields.size()) + " columns");
    std::vector<json> row;
    for (std::size_t i = 0; i < cells.size(); ++i)
      row.push_back(field_value(*axis.fields[i], cells[i], where));
    axis.values.push_back(std::move(row));
  }
  if (axis.fields.empty() || axis.values.empty())
    throw SweepError(label + ": needs a header of field paths and at least one row");
  return axis;
}

// ---- runs ------------------------------------------------------------------------------------

std::size_t run_count(const std::vector<Axis>& axes, bool zip, const std::string& zip_label) {
  if (axes.empty()) return 0;
  if (zip) {
    for (const Axis& a : axes)
      if (a.values.size() != axes[0].values.size())
        throw SweepError(zip_label + ": every varied field needs as many values (" + axes[0].label + ": " +
                         std::to_string(axes[0].values.size()) + ", " + a.label + ": " +
                         std::to_string(a.values.size()) + ")");
    return axes[0].values.size();
  }
  std::size_t total = 1;
  for (const Axis& a : axes) {
    if (total > kMaxRuns / a.values.size())
      throw SweepError(a.label + ": the sweep would be more than " + std::to_string(kMaxRuns) + " runs (" +
                       std::to_string(total) + " × " + std::to_string(a.values.size()) + ")");
    total *= a.values.size();
  }
  return total;
}

std::vector<std::size_t> axis_steps(const std::vector<Axis>& axes, bool zip, std::size_t index) {
  std::vector<std::size_t> steps(axes.size());
  if (zip) {
    std::fill(steps.begin(), steps.end(), index);
    return steps;
  }
  for (std::size_t a = axes.size(); a-- > 0;) {  // the last axis varies fastest
    steps[a] = index % axes[a].values.size();
    index /= axes[a].values.size();
  }
  return steps;
}

}  // namespace spinfold::sweep
