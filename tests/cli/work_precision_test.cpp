// `spinfold work-precision` as a user runs it: a user's scene file in, the CSV, a real PNG and SVG
// and a summary with a recommendation out; bad input exits 2 and writes nothing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "codec/presets.h"
#include "codec/provenance.h"
#include "codec/provenance_reader.h"
#include "tests/cli/run_spinfold.h"

namespace {

namespace fs = std::filesystem;
using spinfold::cli_test::run_spinfold;

struct TempDir {
  fs::path path =
      fs::temp_directory_path() / ("spinfold_wp_" + std::to_string(getpid()) + "_" +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempDir() { fs::remove_all(path); }
  ~TempDir() { fs::remove_all(path); }
};

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Well-formed XML whose root element is <svg>: tags balance, attributes' quoted values skipped,
// declarations, comments and CDATA passed over. (No XML library is among the project's packages.)
bool is_svg_xml(const std::string& text, std::string& why) {
  std::vector<std::string> open;
  std::string root;
  for (std::size_t i = text.find('<'); i != std::string::npos; i = text.find('<', i)) {
    const auto skip_to = [&](const char* end) {
      const std::size_t e = text.find(end, i);
      return e == std::string::npos ? e : e + std::string(end).size();
    };
    if (text.compare(i, 4, "<!--") == 0) {
      i = skip_to("-->");
    } else if (text.compare(i, 9, "<![CDATA[") == 0) {
      i = skip_to("]]>");
    } else if (text.compare(i, 2, "<?") == 0 || text.compare(i, 2, "<!") == 0) {
      i = skip_to(">");
    } else {
      std::size_t e = i + 1;
      char quote = 0;
      for (; e < text.size() && (quote || text[e] != '>'); ++e)
        if (quote && text[e] == quote)
          quote = 0;
        else if (!quote && (text[e] == '"' || text[e] == '\''))
          quote = text[e];
      if (e >= text.size()) return why = "an unclosed tag", false;
      const std::string tag = text.substr(i + 1, e - i - 1);
      const bool closing = tag.starts_with("/"), empty = tag.ends_with("/");
      const std::string name = tag.substr(closing, tag.find_first_of(" \t\r\n/>", closing) - closing);
      if (closing) {
        if (open.empty() || open.back() != name) return why = "</" + name + "> closes nothing open", false;
        open.pop_back();
      } else {
        if (root.empty()) root = name;
        if (!empty) open.push_back(name);
      }
      i = e + 1;
    }
    if (i == std::string::npos) return why = "an unterminated comment or declaration", false;
  }
  if (root != "svg") return why = "the root element is <" + root + ">", false;
  if (!open.empty()) return why = "<" + open.back() + "> is never closed", false;
  return true;
}

struct Row {
  std::string method, parameter;
  double value, seconds, state_error;
};

std::vector<Row> csv_rows(const std::string& text, std::string& comments) {
  std::vector<Row> rows;
  std::istringstream in(text);
  bool header_seen = false;
  for (std::string line; std::getline(in, line);) {
    if (line.starts_with("#")) {
      comments += line + "\n";
      continue;
    }
    if (!header_seen) {
      EXPECT_EQ(line,
                "method,parameter,value,seconds_per_unit_time,state_error,energy_error,steps,position_error,"
                "velocity_error,frame_error");
      header_seen = true;
      continue;
    }
    std::istringstream cells(line);
    std::vector<std::string> c;
    for (std::string cell; std::getline(cells, cell, ',');) c.push_back(cell);
    EXPECT_EQ(c.size(), 10u) << line;
    if (c.size() == 10) rows.push_back({c[0], c[1], std::stod(c[2]), std::stod(c[3]), std::stod(c[4])});
  }
  return rows;
}

// A user's scene: the W5 preset (radial + abc potentials, no closed form) with a stiffer abc
// potential, two integrators and T = 2, so the whole sweep takes about a second.
TEST(WorkPrecision, UserSceneGivesCsvPlotsAndARecommendation) {
  TempDir dir;
  fs::create_directories(dir.path);
  nlohmann::json scene = nlohmann::json::parse(spinfold::find_preset("separable_radial_abc")->json);
  scene["potential"]["deformation"]["C"] = 0.6;
  const fs::path scene_file = dir.path / "my_scene.json";
  std::ofstream(scene_file) << scene.dump();
  const fs::path out = dir.path / "out";
  const auto r = run_spinfold("work-precision " + scene_file.string() +
                              " --integrators dop853,rk4 --t-end 2 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;

  std::string comments;
  const std::vector<Row> rows = csv_rows(read(out / "work_precision.csv"), comments);
  EXPECT_NE(comments.find("# spinfold work-precision "), std::string::npos) << comments;
  EXPECT_NE(comments.find("# command: "), std::string::npos) << comments;
  EXPECT_NE(comments.find("reference: oracle"), std::string::npos) << comments;
  EXPECT_NE(comments.find("geodesic distance"), std::string::npos) << comments;
  std::map<std::string, std::vector<Row>> curves;
  for (const Row& row : rows) curves[row.method].push_back(row);
  ASSERT_EQ(curves.size(), 2u);
  EXPECT_EQ(curves["dop853"].front().parameter, "tol");
  EXPECT_EQ(curves["rk4"].front().parameter, "dt");
  for (const auto& [method, curve] : curves) {
    ASSERT_GE(curve.size(), 4u) << method;
    // coarse to fine: the error falls by orders of magnitude and ends near round-off
    EXPECT_GT(curve.front().value, curve.back().value) << method;
    EXPECT_GT(curve.front().state_error, 1e3 * curve.back().state_error) << method;
    EXPECT_LT(curve.back().state_error, 1e-9) << method;
    for (std::size_t i = 0; i + 3 < curve.size(); ++i)  // falling (a plateau allowed at round-off)
      EXPECT_LT(curve[i + 3].state_error, std::max(curve[i].state_error, 1e-12)) << method << " row " << i;
  }

  const std::string png = read(out / "work_precision.png");
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_GT(png.size(), 1000u);
  std::string why;
  EXPECT_TRUE(is_svg_xml(read(out / "work_precision.svg"), why)) << why;
  EXPECT_NE(read(out / "work_precision.gp").find("set output 'work_precision.svg'"), std::string::npos);
  // Every file says where it came from (issue 35): the provenance JSON, with the scene's hash and the
  // command, in the PNG's Source chunk, the SVG's <metadata>, the script's and the summary's comments.
  // Read back as spinfold rerun reads them (codec/provenance_reader.h); the script's comment line.
  for (const std::string file :
       {"work_precision.png", "work_precision.svg", "summary.md", "work_precision.csv"}) {
    const spinfold::RecordedRun run = spinfold::recorded_run((out / file).string());
    EXPECT_NE(run.command.find("work-precision"), std::string::npos) << file;
    EXPECT_EQ(run.version, std::string(spinfold::build_version())) << file;
    EXPECT_TRUE(run.scene.is_object() && run.scene.contains("surface")) << file;
  }
  const std::string script = read(out / "work_precision.gp");
  const std::size_t line = script.find("# provenance: ");
  ASSERT_NE(line, std::string::npos);
  const nlohmann::json p =
      nlohmann::json::parse(script.substr(line + 14, script.find('\n', line) - line - 14), nullptr, false);
  ASSERT_TRUE(p.is_object());
  EXPECT_EQ(p["software"], "spinfold");
  EXPECT_EQ(p["scene_hash"].get<std::string>().size(), 16u);
  EXPECT_NE(p["command"].get<std::string>().find("work-precision"), std::string::npos);
  EXPECT_TRUE(read(out / "work_precision.gp").starts_with("# spinfold work-precision "));

  const std::string summary = read(out / "summary.md");
  // The file: the provenance as an HTML comment (not rendered), then what the command printed.
  EXPECT_TRUE(summary.starts_with("<!--\n# spinfold work-precision ")) << summary.substr(0, 200);
  EXPECT_TRUE(summary.ends_with("-->\n" + r.out)) << summary.substr(0, 400);
  EXPECT_NE(summary.find("**Recommendation.** For this scene at error 1e-10 over T = 2: "), std::string::npos)
      << summary;
  EXPECT_NE(summary.find("Reference: oracle"), std::string::npos) << summary;
  EXPECT_NE(summary.find("| dop853 | tol |"), std::string::npos) << summary;
}

// Where the closed form holds, auto (which picks it) is recommended, not the cheapest stepper: the
// "Use …" button of the UI sets what is named first.
TEST(WorkPrecision, AutoIsRecommendedWhereItIsCheapest) {
  TempDir dir;
  const fs::path out = dir.path / "out";
  const auto r = run_spinfold(
      "work-precision --scene spinning_rigid_sphere --integrators dop853,auto --t-end 2 "
      "--out " +
      out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("over T = 2: auto (picks exact) at the scene's tol 1e-10, "), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("the cheapest stepping setting, dop853 at tol "), std::string::npos) << r.out;
  // The verdict on chaos is said in every case (it was silent where the motion is regular).
  EXPECT_NE(r.out.find("- Chaos: the motion is not chaotic (MEGNO mean "), std::string::npos) << r.out;
}

// The researcher's chaotic scene (issue 35): every method's error at the default T was the chaos's
// (0.3-2.5) and the summary still named one. Now T is the predictable horizon and the setting named
// reaches the target; a --t-end beyond the horizon gets no recommendation, with the exponent.
TEST(WorkPrecision, AChaoticSceneIsMeasuredOverItsPredictableHorizon) {
  TempDir dir;
  const std::string scene = std::string(SPINFOLD_EXAMPLES_DIR) + "/chaotic_anisotropic_pseudosphere.json";
  // A wall-clock limit generous enough for a loaded or sanitised build: at 0.1 s the ASan build of
  // the fresh-clone CI stopped refining dop853 at tol 1e-6 and recommended nothing.
  const auto r =
      run_spinfold("work-precision " + scene + " --integrators dop853 --max-seconds-per-run 5 --out " +
                   (dir.path / "a").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(the predictable horizon: the motion is chaotic (Lyapunov exponent 0.4"),
            std::string::npos)
      << r.out;
  const std::size_t line = r.out.find("**Recommendation.** For this scene at error 1e-10 over T = 15.");
  ASSERT_NE(line, std::string::npos) << r.out;
  const std::size_t error = r.out.find("(error ", line);
  ASSERT_NE(error, std::string::npos);
  EXPECT_LE(std::stod(r.out.substr(error + 7)), 1e-10) << r.out.substr(line, 200);
  // The state error is its position, velocity and frame parts' largest, each in the CSV.
  std::istringstream csv(read(dir.path / "a" / "work_precision.csv"));
  int rows = 0;
  for (std::string row; std::getline(csv, row);) {
    if (row.empty() || row[0] == '#' || row.starts_with("method,")) continue;
    std::vector<std::string> cells;
    std::istringstream in(row);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 10u) << row;
    if (cells[4] == "inf") continue;
    const double parts = std::max({std::stod(cells[7]), std::stod(cells[8]), std::stod(cells[9])});
    EXPECT_EQ(std::stod(cells[4]), parts) << row;
    ++rows;
  }
  EXPECT_GT(rows, 5);

  const auto beyond = run_spinfold("work-precision " + scene +
                                   " --t-end 60 --integrators dop853 --max-seconds-per-run 0.1 --out " +
                                   (dir.path / "b").string());
  ASSERT_EQ(beyond.exit_code, 0) << beyond.err;
  EXPECT_NE(
      beyond.out.find("**Recommendation.** No recommendation over T = 60: the motion is chaotic (Lyapunov "
                      "exponent 0.4"),
      std::string::npos)
      << beyond.out;
  const std::size_t give = beyond.out.find("(give --t-end ");
  ASSERT_NE(give, std::string::npos) << beyond.out;
  const double horizon = std::stod(beyond.out.substr(give + 14));
  EXPECT_GT(horizon, 12.0);  // ln(1e-10 / 1e-13) / λ with λ ≈ 0.4-0.5 from the probe over 60
  EXPECT_LT(horizon, 20.0);
  // Decided, it measures nothing it cannot recommend (it spent 54 s on --t-end 100 to say so).
  EXPECT_EQ(beyond.err.find("computing the reference"), std::string::npos) << beyond.err;
  EXPECT_NE(beyond.out.find("- Nothing measured: T lies beyond the predictable horizon"), std::string::npos);

  // A T shorter than the chaos takes to show in MEGNO (issue 51: at --t-end 25 it saw no chaos and
  // named the reference's own disagreement "the most accurate"): the probe looks over at least 200.
  const auto short_t = run_spinfold("work-precision " + scene + " --t-end 25 --integrators dop853 --out " +
                                    (dir.path / "c").string());
  ASSERT_EQ(short_t.exit_code, 0) << short_t.err;
  EXPECT_NE(short_t.out.find("**Recommendation.** No recommendation over T = 25: the motion is chaotic"),
            std::string::npos)
      << short_t.out;
}

TEST(WorkPrecision, UnknownPresetExits2AndWritesNothing) {
  TempDir dir;
  const auto r = run_spinfold("work-precision --scene no_such_scene --out " + dir.path.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no_such_scene"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path));
  EXPECT_TRUE(r.out.empty());
}

TEST(WorkPrecision, UnknownIntegratorExits2NamingItAndTheValidOnes) {
  TempDir dir;
  const auto r =
      run_spinfold("work-precision --scene spinning_rigid_sphere --integrators dop853,rk5,gauss8 --out " +
                   dir.path.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'rk5', 'gauss8'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("valid: exact, dop853, rk4"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path));
}

TEST(WorkPrecision, BadOptionsAndFilesExit2) {
  TempDir dir;
  for (const std::string args :
       {"--scene spinning_rigid_sphere --t-end -1", "--scene spinning_rigid_sphere --target-error 0",
        "/no/such/scene.json", "--scene spinning_rigid_sphere"}) {
    const std::string out = std::string(args).ends_with("sphere") ? "" : " --out " + dir.path.string();
    const auto r = run_spinfold("work-precision " + args + out);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_FALSE(r.err.empty()) << args;
    EXPECT_FALSE(fs::exists(dir.path)) << args;
  }
  fs::create_directories(dir.path);
  const fs::path invalid = dir.path / "invalid.json";
  std::ofstream(invalid) << R"({"body": {"mass": -1}})";
  const auto r = run_spinfold("work-precision " + invalid.string() + " --out " + (dir.path / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("body.mass"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path / "out"));
}

}  // namespace
