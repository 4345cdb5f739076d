// The sweep's grid (sweep/, the library `spinfold sweep` and Python's `spinfold.sweep` both call):
// the scene fields a sweep can vary, the values of one axis (`a:b:n`, a list, a table's column),
// and which values run i takes. One rule each, so the CLI and Python make the same runs to the bit.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "engine/run_limits.h"  // kMaxRuns: Python and the CLI refuse alike
#include "engine/scene_paths.h"

namespace spinfold::sweep {

// Bad input to a sweep: the message names the option or field, the value and the reason. The CLI
// prints it (exit 2); Python raises it as ValueError (pybind11 maps std::invalid_argument).
struct SweepError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// A sweep is at most kMaxRuns runs (engine/run_limits.h), refused before anything is allocated.
using spinfold::kMaxRuns;

// The grid `a:b:n`: n values from a to b, both included, numpy.linspace(a, b, n) to the bit (its
// formula, NumPy 1.24): step = (b − a)/(n − 1), value k = k·step + a, or (k/(n − 1))·(b − a) + a
// where step is 0 (it underflowed); the last is b exactly; n = 1 is a alone. So a sweep's rows and
// a researcher's numpy grid name the same doubles.
std::vector<double> grid_values(double a, double b, std::size_t n);

// A scene field a sweep can set, by its dotted path: the engine's walk of the tables
// (engine/scene_paths.h).
using FieldPath = ScenePath;
using Leaf = ScenePath::Leaf;

// The path's field; SweepError "`where`: no scene field 'PATH' (fields: …)" if there is none.
const FieldPath& scene_field(const std::string& path, const std::string& where);

// One axis of the sweep: fields varied together (one for a --set, a table's columns), with one
// tuple of values per step along it. `label` begins its messages ("--set initial.r").
struct Axis {
  std::vector<const FieldPath*> fields;
  std::vector<std::vector<nlohmann::json>> values;
  std::string label;
};

// `spec`: "a:b:n" (a number field: grid_values) or "v1,v2,…". Each value is checked against its
// field alone (range, names); `label` begins each message.
Axis axis_from_spec(const std::string& path, const std::string& spec, const std::string& label);
// `--set FIELD=spec`: the label is "--set FIELD".
Axis axis_from_assignment(const std::string& assignment);
// Values given one by one (a JSON array: numbers for a number field, strings for a text field),
// checked as a spec's are (Python's lists and arrays).
Axis axis_from_values(const std::string& path, const nlohmann::json& values, const std::string& label);
// A table: a header of field paths, then one row of values per step; lines starting with '#'
// skipped. `label` is "--table FILE".
Axis axis_from_table(const std::string& csv_text, const std::string& label);

// How many runs the axes make (their product, or with `zip` the common length); SweepError naming
// the axis past which there would be more than kMaxRuns, or (`zip_label` first) the axes of
// unequal length with zip.
std::size_t run_count(const std::vector<Axis>& axes, bool zip, const std::string& zip_label = "--zip");

// Run `index`'s step along each axis: the last axis varies fastest (with zip: all at `index`).
std::vector<std::size_t> axis_steps(const std::vector<Axis>& axes, bool zip, std::size_t index);

// A number as text: the shortest that reads back to the same double ("1", not "1.0").
std::string number_text(double v);
// A finite number (spaces and a leading '+' allowed), or nothing.
std::optional<double> parse_number(std::string_view text);
std::vector<std::string> split(std::string_view text, char sep);

}  // namespace spinfold::sweep
