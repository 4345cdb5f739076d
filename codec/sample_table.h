// Samples as table rows (CSV): one name per value, the same everywhere a table is written —
// `spinfold simulate --format csv`, `spinfold sweep`'s columns and the API's trajectory CSV. A
// sample's nested values are flattened with dots (X.0, L.0.1, actions.J_r, frequencies.r); a null
// value (undefined at a pole, lost far out on H²; the reason is in the JSON sample's "undefined") is
// an empty cell, which NumPy's genfromtxt and pandas read as NaN.
//
// A CSV file is read as it is by numpy.genfromtxt(f, delimiter=",", names=True, comments="#") and
// pandas.read_csv(f, comment="#"): the column names are its first line, with each dot written '_'
// (X_0, L_0_1, initial_spin: numpy drops dots from names), and the provenance comes after them as
// '#' lines (numpy takes the names from the first line, commented or not).
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene.h"
#include "engine/validation.h"

namespace spinfold {

// The numeric values of a sample (codec/sample_json.h), flattened, in the sample's order.
std::span<const std::string> sample_value_names();
// The rest a row can show: steps (accepted so far), events (det L = 0 crossings since the previous
// row), status, status_detail, integrator, undefined (the null values' names joined by ';').
std::span<const std::string> sample_text_names();
// Every column name a table accepts: the values, then the rest.
std::vector<std::string> sample_column_names();

// A column's symbol and unit for a figure's axis: "φ" and "rad", "ΔH/H₀" and "" (a pure number),
// "X₀" and "length", "L₀₁", "det L", "ν_r" and "1/time"; the name itself and "" for one the table
// lacks. The one table `spinfold plot`'s labels come from.
std::string column_symbol(std::string_view name);
std::string column_unit(std::string_view name);

// The columns a name selects: itself when it is a column, a vector's or matrix's components or a
// group's members when it names one ("X": X.0, X.1, X.2; "L": L.0.0 … L.1.1; "L.1": L.1.0, L.1.1;
// "actions": actions.J_r …), in the table's order; none for an unknown name. `names` is the
// vocabulary (sample_column_names(), or a part of it).
std::vector<std::string> expand_field(std::string_view name, std::span<const std::string> names);
// Every name `fields` takes: the columns (sample_column_names()) and each group of them that
// expand_field selects ("X", "L", "L.1", "actions", …), in the columns' order.
std::vector<std::string> sample_field_names();

// The sample's values by flattened name (objects by key, arrays by index); "events" becomes the
// count of events and "undefined" the names joined by ';'. Companions are left out.
std::map<std::string, nlohmann::ordered_json> flatten_sample(const nlohmann::ordered_json& sample);

// The columns of a table: the names chosen (empty: all of sample_column_names() that the scene's
// chart has: r, r_dot, p_r or u, u_dot, p_u, K), then the same
// columns of each companion named "LABEL.name".
struct SampleTable {
  std::vector<std::string> columns;
  std::vector<std::string> companion_labels;

  std::vector<std::string> header() const;
  std::vector<nlohmann::ordered_json> row(const nlohmann::ordered_json& sample) const;
  std::string csv_header() const;                                               // the column names line
  std::string csv_row(const nlohmann::ordered_json& sample) const;              // one line
  nlohmann::ordered_json json_row(const nlohmann::ordered_json& sample) const;  // {"name": value}
};

// Companions' labels that would make two columns one (a table's companion columns are
// "<label>.<column>"): a label that another companion's repeats (explicit or the default "body N"),
// or one that, with a column's name after it, is a main-body column (`frequencies` makes
// `frequencies.r`). Each error names companions[i].label.
std::vector<FieldError> companion_label_errors(const Scene& scene);

// `fields`: a comma-separated list of names ("" for all); `first_sample` gives the companions'
// labels. Throws std::invalid_argument "unknown field 'x' (…)" naming the first unknown one.
SampleTable make_sample_table(std::string_view fields, const nlohmann::ordered_json& first_sample);

// The samples as CSV: the header, `comment` lines (each prefixed "# "), one row per sample.
std::string samples_csv(std::span<const nlohmann::ordered_json> samples, const SampleTable& table,
                        std::span<const std::string> comment = {});

// A value as a cell: numbers as nlohmann writes them (the shortest text that reads back to the same
// double), text as is (quoted per RFC 4180 when it holds a comma or quote; a line break becomes a space so
// that one row is one line), null empty.
std::string csv_cell(const nlohmann::ordered_json& value);
// A column's name in a CSV header: the name with each '.' written '_' (quoted per RFC 4180 if need be).
std::string csv_name(std::string_view name);
std::string csv_quote(std::string_view text);

}  // namespace spinfold
