// Samples as tables: one name per value (the sample's keys flattened), a column block per body,
// empty cells for null values, quoted labels, unknown names refused.
#include "codec/sample_table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <sstream>

#include "codec/presets.h"
#include "codec/sample_json.h"
#include "codec/scene_json.h"
#include "engine/simulation.h"

namespace spinfold {
namespace {

using nlohmann::ordered_json;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> cells_of(const std::string& line) {  // no quoted cells in these rows
  std::vector<std::string> cells;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.push_back("");
  return cells;
}

Simulation preset_run(const char* name) {
  return start_simulation(*parse_scene_text(find_preset(name)->json).scene);
}

TEST(SampleTable, EveryValueOfASampleHasAColumnAndEveryColumnAValue) {
  // Over every preset (separable ones have actions; those without a radial potential M and the
  // casimir): each key of a sample is a column, and each column is a key of some sample.
  const std::vector<std::string> names = sample_column_names();
  std::set<std::string> seen;
  // And a torus, whose chart is (u, φ) and whose samples carry K, and a formula surface, with no
  // chart: X, V, e₁, e₂, n and the drift off F = 0.
  std::vector<std::string> scenes{
      R"({"surface": {"kind": "torus"}, "initial": {"u": 0.3, "u_dot": 0.2, "phi_dot": 0.4, "mu": 0.7}})",
      R"j({"surface": {"kind": "graph", "z": "0.2*x*y"}, "initial": {"X": [0.3, 0.1, 0], "speed": 0.5,
          "heading": 0.4, "mu": 0.7}})j"};
  for (const PresetSource& preset : preset_sources()) scenes.emplace_back(preset.json);
  for (const std::string& json : scenes) {
    Simulation run = start_simulation(*parse_scene_text(json).scene);
    advance_to(run, 0.5);
    for (const auto& [key, value] : flatten_sample(sample_to_json(run, -1.0))) {
      EXPECT_NE(std::find(names.begin(), names.end(), key), names.end()) << "no column for " << key;
      if (!value.is_null()) seen.insert(key);
    }
  }
  for (const std::string& name : names)
    EXPECT_TRUE(seen.contains(name)) << name << " has no value in any preset";
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size()) << "a name twice";
}

TEST(SampleTable, CellsHoldTheSamplesNumbersToTheBit) {
  Simulation run = preset_run("spinning_rigid_sphere");
  advance_to(run, 1.25);
  const ordered_json sample = sample_to_json(run, -1.0);
  const SampleTable table = make_sample_table("t,r,X.2,L.1.0,energy_error,status", sample);
  const std::vector<std::string> cells = cells_of(lines_of(table.csv_row(sample))[0]);
  ASSERT_EQ(cells.size(), 6u);
  EXPECT_EQ(std::stod(cells[1]), sample["r"].get<double>());
  EXPECT_EQ(std::stod(cells[2]), sample["X"][2].get<double>());
  EXPECT_EQ(std::stod(cells[3]), sample["L"][1][0].get<double>());
  EXPECT_EQ(std::stod(cells[4]), sample["energy_error"].get<double>());
  EXPECT_EQ(cells[5], "ok");
}

TEST(SampleTable, NullValuesAreEmptyCellsAndTheirNamesAreListed) {
  // At the pole φ and its rates are undefined (null in the sample, the reason under "undefined").
  nlohmann::json document = nlohmann::json::parse(find_preset("pole_crossing_sphere")->json);
  document["initial"]["r"] = 0.0;
  Simulation run = start_simulation(*parse_scene(document).scene);
  const ordered_json sample = sample_to_json(run, -1.0);
  ASSERT_TRUE(sample["phi"].is_null());
  const SampleTable table = make_sample_table("t,phi,undefined", sample);
  const std::vector<std::string> cells = cells_of(lines_of(table.csv_row(sample))[0]);
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_EQ(cells[1], "");
  EXPECT_NE(cells[2].find("phi"), std::string::npos) << cells[2];
}

TEST(SampleTable, OneColumnBlockPerCompanionNamedByItsLabel) {
  nlohmann::json document = nlohmann::json::parse(find_preset("opposite_spins_sphere")->json);
  document["companions"][0]["label"] = "s = -1, mirrored";  // a comma: the header cell is quoted
  Simulation run = start_simulation(*parse_scene(document).scene);
  std::vector<ordered_json> samples = {sample_to_json(run, -1.0)};
  advance_to(run, 1.0);
  samples.push_back(sample_to_json(run, 0.0));
  const SampleTable table = make_sample_table("t,r,status", samples.front());
  const std::vector<std::string> lines =
      lines_of(samples_csv(samples, table, std::vector<std::string>{"hello"}));
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "t,r,status,\"s = -1, mirrored_t\",\"s = -1, mirrored_r\",\"s = -1, mirrored_status\"");
  EXPECT_EQ(lines[1], "# hello");
  EXPECT_EQ(lines[3].rfind("1.0,", 0), 0u) << lines[3];
  EXPECT_NE(lines[3].find("," + nlohmann::json(samples[1]["companions"][0]["r"]).dump() + ","),
            std::string::npos);
  EXPECT_EQ(lines[3].substr(lines[3].size() - 3), ",ok");
}

TEST(SampleTable, UnknownFieldsAreRefusedByName) {
  Simulation run = preset_run("spinning_rigid_sphere");
  const ordered_json sample = sample_to_json(run, -1.0);
  try {
    make_sample_table("t,rr", sample);
    FAIL() << "an unknown field was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'rr'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make_sample_table(",", sample), std::invalid_argument);
  // By default every column of the scene's chart: (r, φ) here, (u, φ) and K where the curvature varies.
  const auto without = [](std::set<std::string> dropped) {
    std::vector<std::string> names = sample_column_names();
    std::erase_if(names, [&](const std::string& n) { return dropped.contains(n); });
    return names;
  };
  const std::set<std::string> free_only = {"V.0",
                                           "V.1",
                                           "V.2",
                                           "e1.0",
                                           "e1.1",
                                           "e1.2",
                                           "e2.0",
                                           "e2.1",
                                           "e2.2",
                                           "n.0",
                                           "n.1",
                                           "n.2",
                                           "constraint_drift"};
  std::set<std::string> dropped = free_only;
  dropped.insert({"u", "u_dot", "p_u", "K"});
  EXPECT_EQ(make_sample_table("", sample).columns, without(dropped));
  const Simulation torus = start_simulation(*parse_scene_text(R"({"surface": {"kind": "torus"}})").scene);
  dropped = free_only;
  dropped.insert({"r", "r_dot", "p_r"});
  EXPECT_EQ(make_sample_table("", sample_to_json(torus, -1.0)).columns, without(dropped));
  // On a formula surface neither chart's coordinates: the body in ℝ³, and K.
  const Simulation graph =
      start_simulation(*parse_scene_text(R"j({"surface": {"kind": "graph", "z": "0.2*x*y"}})j").scene);
  EXPECT_EQ(make_sample_table("", sample_to_json(graph, -1.0)).columns,
            without({"r", "r_dot", "p_r", "u", "u_dot", "p_u", "phi", "phi_dot"}));
}

// A vector, a matrix, a matrix's row or a group names its components (issue 35: `--fields X` was
// refused, only X.0,X.1,X.2 accepted); a name that is a prefix of a name but not a group is not one.
TEST(SampleTable, AVectorOrGroupNameSelectsItsComponents) {
  Simulation run = preset_run("spinning_rigid_sphere");
  const ordered_json sample = sample_to_json(run, -1.0);
  EXPECT_EQ(make_sample_table("t,X", sample).columns, (std::vector<std::string>{"t", "X.0", "X.1", "X.2"}));
  EXPECT_EQ(make_sample_table("L.1,frequencies", sample).columns,
            (std::vector<std::string>{"L.1.0", "L.1.1", "frequencies.r", "frequencies.phi", "frequencies.x",
                                      "frequencies.y"}));
  EXPECT_THROW(make_sample_table("X.", sample), std::invalid_argument);
  EXPECT_THROW(make_sample_table("energy_", sample), std::invalid_argument);  // a prefix, not a group
  // the cells are the components' own
  const auto cells = make_sample_table("X", sample).row(sample);
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_EQ(cells[2], sample["X"][2]);
}

// The column table's symbols and units for a figure's axes (`spinfold plot`).
TEST(SampleTable, ColumnSymbolsAndUnits) {
  EXPECT_EQ(column_unit("t"), "time");
  EXPECT_EQ(column_unit("r"), "length");
  EXPECT_EQ(column_unit("energy_error"), "");
  EXPECT_EQ(column_unit("frequencies.r"), "1/time");
  EXPECT_EQ(column_symbol("energy_error"), "\u0394H/H\u2080");
  EXPECT_EQ(column_symbol("lambda"), "\u03BB");
  EXPECT_EQ(column_symbol("X.2"), "X\u2082");
  EXPECT_EQ(column_symbol("frequencies.r"), "\u03BD_r");
  EXPECT_EQ(column_symbol("actions.J_r"), "J_r");
  // Every numeric column has a symbol of its own (no two columns share one but the vorticity, p_β).
  std::set<std::string> seen;
  for (const std::string& name : sample_value_names()) {
    const std::string symbol = column_symbol(name);
    EXPECT_FALSE(symbol.empty()) << name;
    if (name != "vorticity") {
      EXPECT_TRUE(seen.insert(symbol).second) << name << " " << symbol;
    }
  }
}

TEST(SampleTable, CellsNeverBreakALine) {
  EXPECT_EQ(csv_quote("a\nb"), "a b");
  EXPECT_EQ(csv_quote("say \"x\", y"), "\"say \"\"x\"\", y\"");
  EXPECT_EQ(csv_cell(ordered_json()), "");
  EXPECT_EQ(csv_cell(ordered_json(0.1)), "0.1");
}

// Labels that would make two columns one are refused naming companions[i].label: a repeated label
// (explicit, or the default "body N" of an unlabelled companion) and a label that is a main-body
// column group (`frequencies` + `.r`); the header of an accepted scene has no name twice.
TEST(SampleTable, CompanionLabelsThatWouldCollideAreRefused) {
  const auto first_error = [](const std::string& companions) {
    const SceneParse p = parse_scene_text(R"({"companions": )" + companions + "}");
    EXPECT_FALSE(p.scene) << companions;
    return p.errors.empty() ? FieldError{} : p.errors.front();
  };
  FieldError e = first_error(R"([{"label": "frequencies"}])");
  EXPECT_EQ(e.field, "companions[0].label");
  EXPECT_NE(e.reason.find("frequencies.r"), std::string::npos) << e.reason;
  EXPECT_EQ(first_error(R"([{"label": "a"}, {"label": "a"}])").field, "companions[1].label");
  EXPECT_EQ(first_error(R"([{}, {"label": "body 2"}])").field, "companions[1].label");
  EXPECT_EQ(first_error(R"([{"label": "body 3"}, {}])").field, "companions[1].label");
  EXPECT_EQ(first_error(R"([{"label": "L.0"}])").field, "companions[0].label");  // L.0 + .0 = L.0.0
  for (const char* fine :
       {R"([{"label": "a"}, {"label": "b"}, {}])", R"([{"label": "r"}, {"label": "body 9"}])"}) {
    const SceneParse p = parse_scene_text(std::string(R"({"companions": )") + fine + "}");
    ASSERT_TRUE(p.scene) << fine << ": " << (p.errors.empty() ? "" : p.errors[0].reason);
    Simulation run = start_simulation(*p.scene);
    const SampleTable table = make_sample_table("", sample_to_json(run, 0.0));
    const std::vector<std::string> header = table.header();
    EXPECT_EQ(std::set<std::string>(header.begin(), header.end()).size(), header.size()) << fine;
  }
}

}  // namespace
}  // namespace spinfold
