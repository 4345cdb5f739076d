// `spinfold sweep` as a user runs it: every row the same run as `spinfold simulate` to the bit,
// shards that merge into one process's rows, bad input exit 2, a failed run only its row's status.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "codec/presets.h"
#include "tests/cli/run_spinfold.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using spinfold::cli_test::Result;
Result run(const std::string& args) {
  return spinfold::cli_test::run_spinfold(args);
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, sep);) cells.push_back(cell);
  if (!line.empty() && line.back() == sep) cells.emplace_back();
  return cells;
}

// A CSV sweep output: the column names (dots written '_') and the rows as name → cell (no quoted cells
// in these tests).
struct Table {
  std::vector<std::string> header_comments;
  std::vector<std::string> columns;
  std::vector<std::map<std::string, std::string>> rows;
};

Table read_csv(const std::string& text) {
  Table t;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.starts_with("#")) {
      t.header_comments.push_back(line);
    } else if (t.columns.empty()) {
      t.columns = split(line, ',');
    } else {
      const auto cells = split(line, ',');
      std::map<std::string, std::string> row;
      for (size_t i = 0; i < cells.size() && i < t.columns.size(); ++i) row[t.columns[i]] = cells[i];
      EXPECT_EQ(cells.size(), t.columns.size()) << line;
      t.rows.push_back(row);
    }
  }
  return t;
}

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("spinfold_sweep_" + std::to_string(getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

json preset(const std::string& name) {
  return json::parse(spinfold::find_preset(name)->json);
}

// The last sample `simulate` printed, flattened as the sweep names its fields.
// A sample's values by their CSV column names (nested keys joined with '_', as the CSV header writes them).
void flatten(const json& j, const std::string& prefix, std::map<std::string, json>& out) {
  if (j.is_object())
    for (auto it = j.begin(); it != j.end(); ++it) flatten(it.value(), prefix + it.key() + "_", out);
  else if (j.is_array())
    for (size_t i = 0; i < j.size(); ++i) flatten(j[i], prefix + std::to_string(i) + "_", out);
  else
    out[prefix.substr(0, prefix.size() - 1)] = j;
}

const char* kAllFields =
    "t,r,phi,alpha,beta,lambda,mu,r_dot,phi_dot,alpha_dot,beta_dot,lambda_dot,mu_dot,p_r,p_phi,X.0,X.1,X.2,"
    "L.0.0,L.1.1,det_L,energy,energy_error,spin,speed,heading,integrator,drift.energy,drift.p_phi";

// Runs every row of `table` again as `simulate` on the base scene with the row's values and checks
// that the trajectory and the row's numbers are the same text (the same doubles).
void expect_rows_equal_simulate(const Table& table, const std::string& base_preset, const fs::path& dir,
                                double t_end, double every) {
  ASSERT_FALSE(table.rows.empty());
  for (const auto& row : table.rows) {
    json scene = preset(base_preset);
    std::string integrator_flag;
    for (const auto& [name, value] : row) {
      if (name == "initial_r") scene["initial"]["r"] = std::stod(value);
      if (name == "initial_phi_dot") scene["initial"]["phi_dot"] = std::stod(value);
      if (name == "integrator_tolerance") scene["integrator"]["tolerance"] = std::stod(value);
      if (name == "integrator_name") integrator_flag = " --integrator " + value;
    }
    const fs::path scene_file = dir / ("scene_" + row.at("index") + ".json");
    std::ofstream(scene_file) << scene.dump();
    std::ostringstream args;
    args.precision(17);
    args << "simulate " << scene_file.string() << integrator_flag << " --t-end " << t_end << " --every "
         << every;
    const auto sim = run(args.str());
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    // The whole trajectory, byte for byte, after the provenance records (their commands differ).
    const auto after_provenance = [](const std::string& text) {
      EXPECT_TRUE(text.starts_with("{\"provenance\":")) << text.substr(0, 80);
      return text.substr(text.find('\n') + 1);
    };
    EXPECT_EQ(after_provenance(slurp(dir / "traj" / (row.at("index") + ".jsonl"))), after_provenance(sim.out))
        << "row " << row.at("index");
    // The row's final values and drifts.
    std::vector<json> samples;
    std::istringstream in(sim.out);
    int events = 0;
    for (std::string line; std::getline(in, line);) {
      if (line.starts_with("{\"provenance\":")) continue;
      samples.push_back(json::parse(line));
      events += static_cast<int>(samples.back()["events"].size());
    }
    std::map<std::string, json> first, last;
    flatten(samples.front(), "", first);
    flatten(samples.back(), "", last);
    for (const std::string& column : table.columns) {
      if (column == "index" || column.starts_with("initial_") || column.starts_with("integrator_")) continue;
      const std::string& cell = row.at(column);
      if (column.starts_with("drift_")) {
        const std::string key = column.substr(6);
        EXPECT_EQ(cell, json(last[key].get<double>() - first[key].get<double>()).dump()) << column;
      } else if (last.count(column)) {
        const json& v = last[column];
        EXPECT_EQ(cell, v.is_string() ? v.get<std::string>()
                        : v.is_null() ? ""
                                      : v.dump())
            << "row " << row.at("index") << " column " << column;
      }
    }
    EXPECT_EQ(row.at("events"), std::to_string(events));
    EXPECT_EQ(row.at("status"), samples.back()["status"].get<std::string>());
    EXPECT_EQ(row.at("steps"), samples.back()["steps"].dump());
  }
}

TEST(Sweep, RowsAreTheSameRunsAsSimulateToTheBit) {
  TempDir dir;
  const auto r =
      run("sweep spinning_rigid_sphere --set integrator.name=dop853,gauss6,auto,rk4,split6 "
          "--set initial.r=0.5:1.1:3 --t-end 3 --every 0.5 --jobs 2 --fields " +
          std::string(kAllFields) + " --trajectories " + (dir.path / "traj").string() + " --out " +
          (dir.path / "rows.csv").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table table = read_csv(slurp(dir.path / "rows.csv"));
  ASSERT_EQ(table.rows.size(), 15u);
  EXPECT_EQ(table.columns[1], "integrator_name");
  EXPECT_EQ(table.columns[2], "initial_r");
  // Cartesian product, the last field varying fastest; a:b:n ends at b exactly.
  EXPECT_EQ(table.rows[0].at("integrator_name"), "dop853");
  EXPECT_EQ(table.rows[2].at("initial_r"), "1.1");
  EXPECT_EQ(table.rows[3].at("integrator_name"), "gauss6");
  for (size_t i = 0; i < table.rows.size(); ++i) {
    EXPECT_EQ(table.rows[i].at("index"), std::to_string(i));
    EXPECT_EQ(table.rows[i].at("status"), "ok");
  }
  expect_rows_equal_simulate(table, "spinning_rigid_sphere", dir.path, 3, 0.5);
}

TEST(Sweep, TableRowsWithEventsAreTheSameRunsAsSimulate) {
  TempDir dir;
  std::ofstream(dir.path / "rows.csv") << "integrator.name,integrator.tolerance\n"
                                          "dop853,1e-9\nauto,1e-10\ngauss6,1e-8\nsplit4,1e-10\n";
  const auto r =
      run("sweep degenerate_crossing --table " + (dir.path / "rows.csv").string() +
          " --t-end 2 --every 0.25 --jobs 3 --fields " + std::string(kAllFields) + " --trajectories " +
          (dir.path / "traj").string() + " --out " + (dir.path / "out.csv").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table table = read_csv(slurp(dir.path / "out.csv"));
  ASSERT_EQ(table.rows.size(), 4u);
  // The crossing at t = 0.5 is counted (where the integrator locates it: as simulate reports it).
  EXPECT_EQ(table.rows[1].at("events"), "1");
  expect_rows_equal_simulate(table, "degenerate_crossing", dir.path, 2, 0.25);
}

// Everything but the timing column and the command line.
std::string without_timing(const std::string& text, bool jsonl) {
  std::string result;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.starts_with("# command:") || line.starts_with("# merge:")) continue;
    if (jsonl) {
      json j = json::parse(line);
      if (j.contains("sweep")) {
        j["sweep"].erase("command");
        j["sweep"].erase("merge");
      }
      j.erase("seconds");
      result += j.dump() + "\n";
    } else {
      result += line.substr(0, line.rfind(',')) + "\n";  // seconds is the last column
    }
  }
  return result;
}

TEST(Sweep, ShardsMergeIntoTheRowsOfOneProcess) {
  TempDir dir;
  for (const std::string ext : {"csv", "jsonl"}) {
    const std::string common =
        "sweep spinning_rigid_sphere --set initial.r=0.4:1.2:5 --set initial.phi_dot=0.3,0.6 --t-end 2 "
        "--every 1 --fields t,r,phi,energy_error,drift.p_phi --quiet";
    const auto whole = run(common + " --jobs 2 --out " + (dir.path / ("whole." + ext)).string());
    ASSERT_EQ(whole.exit_code, 0) << whole.err;
    std::string shards;
    for (int i = 0; i < 3; ++i) {
      const std::string file = (dir.path / ("shard" + std::to_string(i) + "." + ext)).string();
      const auto s = run(common + " --jobs 1 --shard " + std::to_string(i) + "/3 --out " + file);
      ASSERT_EQ(s.exit_code, 0) << s.err;
      shards = file + " " + shards;  // given out of order on purpose
    }
    const auto merged = run("sweep --merge " + shards + "--out " + (dir.path / ("merged." + ext)).string());
    ASSERT_EQ(merged.exit_code, 0) << merged.err;
    const std::string expected = without_timing(slurp(dir.path / ("whole." + ext)), ext == "jsonl");
    EXPECT_EQ(without_timing(slurp(dir.path / ("merged." + ext)), ext == "jsonl"), expected);
    // The merged output keeps the sweep's own command (shard 0's) and adds the merge's.
    const std::string merged_text = slurp(dir.path / ("merged." + ext));
    if (ext == "jsonl") {
      const json h = json::parse(merged_text.substr(0, merged_text.find('\n')))["sweep"];
      EXPECT_NE(h["command"].get<std::string>().find("--shard 0/3"), std::string::npos) << h.dump();
      EXPECT_NE(h["merge"].get<std::string>().find("--merge"), std::string::npos) << h.dump();
    } else {
      EXPECT_NE(merged_text.find("\n# command: "), std::string::npos);
      EXPECT_NE(merged_text.find("--shard 0/3 "), std::string::npos) << merged_text;
      EXPECT_NE(merged_text.find("\n# merge: "), std::string::npos) << merged_text;
    }
    // CSV: version, runs, definition, shard and base lines (the command aside), the header, 10 rows.
    EXPECT_EQ(std::count(expected.begin(), expected.end(), '\n'), ext == "csv" ? 5 + 1 + 10 : 1 + 10);
    // A missing shard is refused, naming the runs missing.
    const auto partial = run("sweep --merge " + (dir.path / ("shard0." + ext)).string() + " --out " +
                             (dir.path / ("partial." + ext)).string());
    EXPECT_EQ(partial.exit_code, 2);
    EXPECT_NE(partial.err.find("runs missing (1, 2, 4"), std::string::npos) << partial.err;
  }
}

TEST(Sweep, MergeRefusesOtherSweepsAndCutRows) {
  TempDir dir;
  const std::string common = "sweep spinning_rigid_sphere --set initial.r=0.5:1:4 --t-end 1 --quiet";
  const auto path = [&](const std::string& name) { return (dir.path / name).string(); };
  ASSERT_EQ(run(common + " --shard 0/2 --out " + path("a0.csv")).exit_code, 0);
  ASSERT_EQ(run(common + " --shard 1/2 --out " + path("a1.csv")).exit_code, 0);
  // Shards of other sweeps: other columns, or the same columns with another --t-end or other values.
  const std::string other_sweep = "sweep spinning_rigid_sphere --quiet --shard 1/2 --out ";
  ASSERT_EQ(run(common + " --fields t --shard 1/2 --out " + path("c1.csv")).exit_code, 0);
  ASSERT_EQ(run(other_sweep + path("d1.csv") + " --set initial.r=0.5:1:4 --t-end 2").exit_code, 0);
  ASSERT_EQ(run(other_sweep + path("e1.csv") + " --set initial.r=0.5:1.1:4 --t-end 1").exit_code, 0);
  for (const char* shard : {"c1.csv", "d1.csv", "e1.csv"}) {
    const auto other = run("sweep --merge " + path("a0.csv") + " " + path(shard) + " --out " + path("m.csv"));
    EXPECT_EQ(other.exit_code, 2) << shard;
    EXPECT_NE(other.err.find("another sweep"), std::string::npos) << shard << ": " << other.err;
  }
  const auto twice =
      run("sweep --merge " + path("a0.csv") + " " + path("a0.csv") + " --out " + path("m.csv"));
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_NE(twice.err.find("given twice"), std::string::npos) << twice.err;
  // A shard cut in the middle of its last row (a kill): that row is missing, not half a row.
  std::string cut = slurp(path("a1.csv"));
  cut.resize(cut.size() - 10);
  std::ofstream(path("cut1.csv")) << cut;
  const auto merged =
      run("sweep --merge " + path("a0.csv") + " " + path("cut1.csv") + " --out " + path("m.csv"));
  EXPECT_EQ(merged.exit_code, 2);
  EXPECT_NE(merged.err.find("runs missing (3)"), std::string::npos) << merged.err;
  const auto whole =
      run("sweep --merge " + path("a0.csv") + " " + path("a1.csv") + " --out " + path("m.csv"));
  EXPECT_EQ(whole.exit_code, 0) << whole.err;
}

TEST(Sweep, BadFieldsAndValuesAreExitTwoNamingThem) {
  struct Case {
    std::string args, expected;
  };
  for (const Case& c : std::vector<Case>{
           {"--set initial.nope=1", "no scene field 'initial.nope'"},
           {"--set initial.lambda=-1,1", "initial.lambda: must be > 0 (got '-1')"},
           {"--set integrator.tolerance=1e-20", "integrator.tolerance: must be >= 1e-15"},
           {"--set initial.r=-1:1:3", "initial.r: must be >= 0 (got -1 in"},
           {"--set surface.kind=klein_bottle",
            "must be one of sphere, pseudosphere, plane, torus, spheroid, bump, catenoid"},
           {"--set potential.deformation.ghat=1", "potential.deformation.ghat: is not a known field here"},
           {"--set initial.r=1:2:x", "a:b:n"},
           {"--set initial.r=abc", "not a finite number (got 'abc')"},
           {"--set integrator.name=dop853,nosuch", "nosuch"},
           {"--set initial.r=1 --fields t,bogus", "unknown field 'bogus'"},
           {"--set initial.r=1,2 --set initial.phi=1 --zip", "--zip"},
           {"--set initial.r=1 --shard 3/3", "--shard"},
           {"--set initial.r=1 --out rows.txt", "--out"},
           // The run limits in simulate's words (engine/run_limits.h); -1 was a whole run.
           {"--set initial.r=1 --max-steps -1", "--max-steps: must be a whole number from 1 to"},
           {"--set initial.r=1 --t-end -1", "--t-end: must be a number >= 0 [time] (got '-1')"},
           // Summaries and events in the engine's words (engine/run_summary.h).
           {"--set initial.r=1 --summary nope",
            "--summary: summary 'nope': unknown field 'nope' for this scene"},
           {"--set initial.r=1 --event r:sideways:1",
            "--event: event 'r:sideways:1': the direction must be up, down or any"},
           {"--set initial.r=1 --event u:up:1", "unknown field 'u' for this scene (one of r, phi,"},
           {"--set initial.r=1 --trajectories t --trajectory-format xml",
            "--trajectory-format: must be jsonl, csv or npz (got 'xml')"},
           {"--set initial.r=1 --trajectory-fields t,r", "--trajectory-fields: give --trajectories DIR too"},
           {"--set initial.r=1 --chaos-interval 2", "--chaos-interval requires --chaos"},
           {"--set initial.r=1 --summary r.maxx", "or FIELD.REDUCTION, REDUCTION one of min, max, mean"},
           {"--set initial.r=1 --chaos --chaos-interval -1",
            "--chaos-interval: must be a number > 0 [time] (got -1)"},
           {"--set initial.r=1 --chaos --chaos-interval 1e-6 --t-end 10",
            "--chaos-interval: t_end / interval must be at most 1e6"},
       }) {
    const auto r = run((c.args.find("deformation") != std::string::npos ? "sweep breathing_ellipse_sphere "
                                                                        : "sweep spinning_rigid_sphere ") +
                       c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(r.out, "") << c.args;
  }
  const auto lambda = run("sweep spinning_rigid_sphere --set initial.lambda=-1");
  EXPECT_NE(lambda.err.find("initial.lambda"), std::string::npos);
}

// Summaries and events come from each run's own steps: the same cells however the runs are sampled,
// and the same numbers as simulate's summary record of that run; a terminal event ends a run as
// event_stop (a good row), at the crossing.
TEST(Sweep, SummariesAndEventsAreTheRunsOwnWhateverTheSampling) {
  TempDir dir;
  const std::string common =
      "sweep separable_radial_abc --set integrator.name=dop853,exact --set initial.r=1.2,1.1 --t-end 20 "
      "--fields t,r --summary r,phi.max --event r:up:1.3 --event 'r:down:1.25:stop=1:name=back' --quiet ";
  ASSERT_EQ(run(common + "--every 0.5 --out " + (dir.path / "a.csv").string()).exit_code, 0);
  ASSERT_EQ(run(common + "--every 0.07 --out " + (dir.path / "b.csv").string()).exit_code, 0);
  const Table a = read_csv(slurp(dir.path / "a.csv")), b = read_csv(slurp(dir.path / "b.csv"));
  ASSERT_EQ(a.rows.size(), 4u);
  for (const char* c : {"r_max", "r_min", "r_mean", "r_t_max", "phi_max", "r_up_1_3_count",
                        "r_up_1_3_t_first", "r_up_1_3_at_phi", "back_count", "back_t_last"})
    ASSERT_NE(std::find(a.columns.begin(), a.columns.end(), c), a.columns.end()) << c;
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    for (const std::string& c : a.columns) {
      if (c.starts_with("r_") || c.starts_with("phi_") || c.starts_with("back_")) {
        EXPECT_EQ(a.rows[i].at(c), b.rows[i].at(c)) << "row " << i << " column " << c;
      }
    }
    EXPECT_EQ(a.rows[i].at("status"), "event_stop") << i;
    EXPECT_EQ(a.rows[i].at("back_count"), "1");
    EXPECT_EQ(a.rows[i].at("t"), a.rows[i].at("back_t_last")) << "the run ends on the crossing";
    EXPECT_LT(std::abs(std::stod(a.rows[i].at("r")) - 1.25), 1e-9);
  }
  // simulate's summary record of run 0 (dop853, the preset's r = 1.2): the sweep row's numbers.
  const auto sim =
      run("simulate separable_radial_abc --integrator dop853 --t-end 20 --every 3 --fields t "
          "--summary r,phi.max --event r:up:1.3 --event 'r:down:1.25:stop=1:name=back'");
  EXPECT_EQ(sim.exit_code, 0) << sim.err;
  {
    const json summary = json::parse(sim.out.substr(sim.out.rfind("{\"summary\"")))["summary"];
    EXPECT_EQ(summary["r.max"].dump(), a.rows[0].at("r_max"));
    EXPECT_EQ(summary["back.t_first"].dump(), a.rows[0].at("back_t_first"));
    EXPECT_EQ(summary["r_up_1.3.count"].get<int>(), std::stoi(a.rows[0].at("r_up_1_3_count")));
  }
}

TEST(Sweep, AFailedRunIsItsRowsStatusNotTheSweepsEnd) {
  // R = 0.5 with r = 3 is past the antipode (r <= πR): only that combination is invalid. A step
  // budget too small for a long run stops that run alone.
  const auto r =
      run("sweep spinning_rigid_sphere --set surface.radius=0.5,2 --set initial.r=1,3 --t-end 1 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = read_csv(r.out);
  ASSERT_EQ(t.rows.size(), 4u);
  EXPECT_EQ(t.rows[0].at("status"), "ok");
  EXPECT_EQ(t.rows[1].at("status"), "invalid_scene");
  EXPECT_NE(t.rows[1].at("detail").find("initial.r"), std::string::npos);
  EXPECT_EQ(t.rows[2].at("status"), "ok");
  EXPECT_EQ(t.rows[3].at("status"), "ok");

  // A rigid body's lambda and mu go together: paired they run, crossed the unequal ones are rows.
  const auto zipped = run(
      "sweep spinning_rigid_sphere --set initial.lambda=1,2 --set initial.mu=1,2 --zip --t-end 1 --quiet");
  ASSERT_EQ(zipped.exit_code, 0) << zipped.err;
  const Table z = read_csv(zipped.out);
  ASSERT_EQ(z.rows.size(), 2u);
  for (const auto& row : z.rows) EXPECT_EQ(row.at("status"), "ok");
  const auto crossed =
      run("sweep spinning_rigid_sphere --set initial.lambda=1,2 --set initial.mu=1,2 --t-end 1 --quiet");
  ASSERT_EQ(crossed.exit_code, 0) << crossed.err;
  const Table c = read_csv(crossed.out);
  ASSERT_EQ(c.rows.size(), 4u);
  EXPECT_EQ(c.rows[0].at("status"), "ok");
  EXPECT_EQ(c.rows[1].at("status"), "invalid_scene");
  EXPECT_EQ(c.rows[2].at("status"), "invalid_scene");
  EXPECT_EQ(c.rows[3].at("status"), "ok");

  const auto budget =
      run("sweep spinning_rigid_sphere --set integrator.name=rk4,dop853 --t-end 5 --max-steps 50 --quiet");
  ASSERT_EQ(budget.exit_code, 0) << budget.err;
  const Table b = read_csv(budget.out);
  ASSERT_EQ(b.rows.size(), 2u);
  EXPECT_EQ(b.rows[0].at("status"), "max_steps");  // rk4 at dt = 0.01: 500 steps
  EXPECT_EQ(b.rows[1].at("status"), "ok");
}

TEST(Sweep, AnyVocabularyFieldCanBeVaried) {
  const auto r =
      run("sweep spinning_rigid_sphere --set surface.curvature=1,0,-0.5 "
          "--set potential.radial.gamma=0,0.05 --set body.inertia=0.5,0.7 --t-end 1 --quiet "
          "--fields r,energy --out -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = read_csv(r.out);
  ASSERT_EQ(t.rows.size(), 12u);
  EXPECT_EQ(t.columns[1], "surface_curvature");
  EXPECT_EQ(t.columns[2], "potential_radial_gamma");
  EXPECT_EQ(t.columns[3], "body_inertia");
  std::set<std::string> energies;
  for (const auto& row : t.rows) {
    EXPECT_EQ(row.at("status"), "ok") << row.at("index") << " " << row.at("detail");
    energies.insert(row.at("energy"));
  }
  EXPECT_EQ(energies.size(), 12u);  // each value reached its run
}

TEST(Sweep, EveryListedFieldIsAColumnAndNoProgressOffATerminal) {
  const auto list = run("sweep --list-fields");
  ASSERT_EQ(list.exit_code, 0);
  std::string fields;
  int count = 0;
  std::istringstream in(list.out);
  for (std::string name; std::getline(in, name); ++count) fields += (fields.empty() ? "" : ",") + name;
  EXPECT_GT(count, 100);
  EXPECT_NE(fields.find(",drift.casimir,"), std::string::npos);
  // action_variables_sphere has actions and frequencies: most columns hold numbers.
  const auto r = run("sweep action_variables_sphere --set initial.r=1,1.1 --t-end 1 --fields " + fields);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // stderr is not a terminal here: no progress line
  const Table t = read_csv(r.out);
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.columns.size(), 1u + 1u + count + 5u);
  EXPECT_NE(t.rows[0].at("actions_J_r"), "");
  EXPECT_NE(t.rows[0].at("drift_energy"), "");
}

TEST(Sweep, AKilledSweepLeavesWholeLines) {
  TempDir dir;
  const fs::path out = dir.path / "rows.jsonl";
  // Killed once a few rows are out (not after a fixed time: a sanitizer build is 10x slower), long
  // before the 1000 runs end.
  const std::string sweep =
      std::string(SPINFOLD_BINARY) +
      " sweep spinning_rigid_sphere --set initial.r=0.5:1.5:1000 --set integrator.name=rk4 "
      "--t-end 200 --jobs 1 --out " +
      out.string() + " 2>/dev/null";
  (void)std::system(("sh -c '" + sweep + " & p=$!; i=0; while [ $i -lt 1200 ]; do [ -f " + out.string() +
                     " ] && [ $(wc -l < " + out.string() +
                     ") -ge 4 ] && break; sleep 0.05; i=$((i+1)); done; " + "kill -KILL $p; wait $p'")
                        .c_str());
  const std::string text = slurp(out);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  std::istringstream in(text);
  int rows = 0;
  for (std::string line; std::getline(in, line); ++rows) EXPECT_TRUE(json::accept(line)) << line;
  EXPECT_GT(rows, 2);
  EXPECT_LT(rows, 1001);
}

}  // namespace
