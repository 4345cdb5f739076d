// What `spinfold simulate` writes besides its samples: tables with the columns a user picks, the
// provenance of every output (JSON Lines, CSV, PNG), budgets that stop a run with a status, and
// whole lines when a run is killed.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "codec/presets.h"
#include "codec/sample_table.h"
#include "tests/cli/run_spinfold.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using spinfold::cli_test::Result;

Result spinfold(const std::string& args) {
  return spinfold::cli_test::run_spinfold(args);
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> cells;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.push_back("");
  return cells;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("spinfold_simulate_output_" + std::to_string(getpid()) + "_" +
                                               std::to_string(std::rand()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

TEST(SimulateOutput, CsvRowsHoldTheNumbersOfTheJsonLinesToTheBit) {
  const std::string run = "simulate --scene separable_radial_abc --t-end 3 --every 0.75";
  const Result jsonl = spinfold(run);
  const Result csv = spinfold(run + " --format csv --fields t,r,phi,X.2,L.0.1,actions.J_r,status");
  ASSERT_EQ(jsonl.exit_code, 0) << jsonl.err;
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  const auto samples = lines_of(jsonl.out);
  const auto rows = lines_of(csv.out);
  // The header (dots written '_', as numpy.genfromtxt keeps them), "# spinfold simulate …",
  // "# provenance: {…}", 5 rows.
  ASSERT_EQ(rows.size(), 8u) << csv.out;
  EXPECT_EQ(rows[0], "t,r,phi,X_2,L_0_1,actions_J_r,status");
  EXPECT_TRUE(rows[1].starts_with("# spinfold simulate ")) << rows[1];
  ASSERT_TRUE(rows[2].starts_with("# provenance: ")) << rows[2];
  ASSERT_EQ(samples.size(), 6u);  // the provenance record and 5 samples
  for (int k = 0; k < 5; ++k) {
    const json s = json::parse(samples[k + 1]);
    const auto cells = cells_of(rows[k + 3]);
    ASSERT_EQ(cells.size(), 7u) << rows[k + 3];
    EXPECT_EQ(std::stod(cells[0]), s["t"].get<double>());
    EXPECT_EQ(std::stod(cells[1]), s["r"].get<double>());
    EXPECT_EQ(std::stod(cells[2]), s["phi"].get<double>());
    EXPECT_EQ(std::stod(cells[3]), s["X"][2].get<double>());
    EXPECT_EQ(std::stod(cells[4]), s["L"][0][1].get<double>());
    EXPECT_EQ(std::stod(cells[5]), s["actions"]["J_r"].get<double>());
    EXPECT_EQ(cells[6], s["status"]);
  }
}

TEST(SimulateOutput, EveryListedFieldIsAColumnAndTheDefaultIsAll) {
  const Result names = spinfold("simulate --list-fields");
  ASSERT_EQ(names.exit_code, 0) << names.err;
  const auto listed = lines_of(names.out);
  EXPECT_EQ(listed, spinfold::sample_column_names());
  const Result csv = spinfold("simulate --scene spinning_rigid_sphere --t-end 1 --every 1 --format csv");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  std::string header;
  // every column but those of the (u, φ) chart (the torus's, …) and of a formula surface (no chart)
  const auto free_only = [](const std::string& n) {
    return n == "constraint_drift" || n.starts_with("V.") || n.starts_with("e1.") || n.starts_with("e2.") ||
           n.starts_with("n.");
  };
  for (const std::string& n : listed)
    if (n != "u" && n != "u_dot" && n != "p_u" && n != "K" && !free_only(n)) {
      if (!header.empty()) header += ',';
      header += spinfold::csv_name(n);
    }
  EXPECT_EQ(lines_of(csv.out)[0], header);
  // JSON Lines with --fields: flat records of those names.
  const Result flat =
      spinfold("simulate --scene spinning_rigid_sphere --t-end 1 --every 1 --fields t,X.0,alpha");
  ASSERT_EQ(flat.exit_code, 0) << flat.err;
  const json row = json::parse(lines_of(flat.out).back());
  EXPECT_EQ(row.size(), 3u) << row;
  EXPECT_TRUE(row["alpha"].is_null());  // λ = μ: undefined, null as in the full sample
}

TEST(SimulateOutput, UnknownFieldsAndFormatsAreRefusedBeforeAnyOutput) {
  TempDir dir;
  for (const char* args : {"--fields t,rr", "--format xml", "--max-steps 0", "--max-seconds -1"}) {
    const Result r =
        spinfold(std::string("simulate --t-end 1 --out ") + (dir.path / "x.csv").string() + " " + args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_TRUE(r.out.empty()) << args;
    EXPECT_FALSE(fs::exists(dir.path / "x.csv")) << args;
  }
  const Result r = spinfold("simulate --t-end 1 --fields t,rr");
  EXPECT_NE(r.err.find("--fields: unknown field 'rr'"), std::string::npos) << r.err;
}

TEST(SimulateOutput, ProvenanceNamesTheBuildTheSceneTheIntegratorAndTheCommand) {
  const Result version = spinfold("--version");
  ASSERT_EQ(version.exit_code, 0);
  // "spinfold 0.3.0 (commit 1a2b3c4d5e6f)" or "(commit …-dirty)"; "unknown" only without git.
  EXPECT_TRUE(version.out.starts_with("spinfold ")) << version.out;
  EXPECT_NE(version.out.find("(commit "), std::string::npos) << version.out;
  const Result r = spinfold("simulate --scene spinning_rigid_sphere --t-end 1 --every 1 --tolerance 1e-9");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json p = json::parse(lines_of(r.out)[0])["provenance"];
  EXPECT_EQ(p["software"], "spinfold");
  EXPECT_NE(version.out.find(p["version"].get<std::string>()), std::string::npos);
  EXPECT_NE(version.out.find(p["commit"].get<std::string>()), std::string::npos);
  EXPECT_EQ(p["scene_hash"].get<std::string>().size(), 16u);
  EXPECT_EQ(p["integrator"]["name"], "auto");
  EXPECT_FALSE(p["integrator"]["runs"].get<std::string>().empty());
  EXPECT_EQ(p["integrator"]["tolerance"], 1e-9);
  EXPECT_NE(p["command"].get<std::string>().find("--tolerance 1e-9"), std::string::npos) << p["command"];
  // The same scene from a file spelled differently hashes the same; another scene does not.
  TempDir dir;
  const fs::path file = dir.path / "scene.json";
  const Result scene = spinfold("simulate --scene spinning_rigid_sphere --t-end 0 --every 1");
  std::ofstream(file) << json::parse(spinfold::find_preset("spinning_rigid_sphere")->json).dump(4);
  const Result same = spinfold("simulate " + file.string() + " --t-end 0 --every 1");
  ASSERT_EQ(same.exit_code, 0) << same.err;
  const auto hash = [](const Result& x) {
    return json::parse(lines_of(x.out)[0])["provenance"]["scene_hash"];
  };
  EXPECT_EQ(hash(same), hash(scene));
  EXPECT_NE(hash(scene), p["scene_hash"]);  // the tolerance differs
}

TEST(SimulateOutput, RenderedPngsCarryTheProvenanceAsTextChunks) {
  TempDir dir;
  const fs::path png = dir.path / "frame.png";
  const Result r =
      spinfold("render --scene spinning_rigid_sphere --t 0.5 --width 64 --height 48 --out " + png.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string bytes = slurp(png);
  const std::size_t software = bytes.find("tEXtSoftware");
  ASSERT_NE(software, std::string::npos);
  EXPECT_EQ(bytes.compare(software + 13, 9, "spinfold "), 0);
  const std::size_t source = bytes.find("tEXtSource");
  ASSERT_NE(source, std::string::npos);
  // The chunk's length precedes its type: the text is the JSON provenance with the time and view.
  const auto length = [&](std::size_t at) {
    std::uint32_t n = 0;
    for (int k = 0; k < 4; ++k) n = n << 8 | static_cast<unsigned char>(bytes[at - 4 + k]);
    return n;
  };
  const std::string text = bytes.substr(source + 11, length(source) - 7);
  const json p = json::parse(text);
  EXPECT_EQ(p["t"], 0.5);
  EXPECT_EQ(p["view"], "sphere");
  EXPECT_NE(p["command"].get<std::string>().find("render --scene spinning_rigid_sphere"), std::string::npos);
  EXPECT_LT(source, bytes.find("IDAT"));
}

TEST(SimulateOutput, MaxStepsStopsTheRunWithItsStatusAndWhereItGot) {
  const Result r = spinfold(
      "simulate --scene spinning_rigid_sphere --integrator rk4 --dt 0.001 --t-end 10 "
      "--every 1 --max-steps 2500");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("max_steps"), std::string::npos) << r.err;
  const auto lines = lines_of(r.out);
  ASSERT_GE(lines.size(), 3u);
  const json last = json::parse(lines.back());
  EXPECT_EQ(last["stopped"], "max_steps");
  // 2500 attempts: the accepted steps and the cut steps to the sample times 1 and 2.
  EXPECT_NEAR(last["t"].get<double>(), 2.5, 0.0031);
  EXPECT_LE(last["steps"].get<int>(), 2500);
  EXPECT_GE(last["steps"].get<int>(), 2497);
  EXPECT_EQ(lines.size(), 1u + 3u + 1u);  // provenance, samples at 0, 1, 2, the stop record
  // The samples before the stop are those of the run without a budget, to the bit.
  const Result full =
      spinfold("simulate --scene spinning_rigid_sphere --integrator rk4 --dt 0.001 --t-end 2 --every 1");
  EXPECT_EQ(lines_of(full.out)[3], lines[3]);
}

TEST(SimulateOutput, MaxSecondsStopsALongRunWithItsStatus) {
  const auto start = std::chrono::steady_clock::now();
  const Result r = spinfold(
      "simulate --scene spinning_rigid_sphere --integrator rk4 --dt 1e-5 --t-end 1e4 "
      "--every 100 --format csv --max-seconds 0.3");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("max_seconds"), std::string::npos) << r.err;
  EXPECT_TRUE(lines_of(r.out).back().starts_with("# stopped: {\"stopped\":\"max_seconds\""))
      << lines_of(r.out).back();
  EXPECT_LT(seconds, 5.0);
}

// --chaos's two runs go on after the main run only within what is left of --max-seconds (they took
// 14-27 s for a 3 s limit on the catenoid): the command ends near its limit with exit 3 and says so.
TEST(SimulateOutput, MaxSecondsBoundsTheChaosIndicatorsRunsToo) {
  const auto start = std::chrono::steady_clock::now();
  const Result r = spinfold(
      "simulate --scene spin_vs_geodesic_catenoid --t-end 1e4 --every 1000 --chaos --chaos-interval 0.01 "
      "--format csv --max-seconds 1.5");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("max_seconds"), std::string::npos) << r.err;
  EXPECT_LT(seconds, 1.5 + 4.0);
}

// An event whose period is far below what double tells apart where its field is (issue 48: it ran
// until killed, whatever --max-seconds or --max-steps said): the run stops at once with its status.
TEST(SimulateOutput, AnEventPeriodBelowTheFieldsPrecisionStopsTheRunWithItsStatus) {
  for (const char* limit : {"--max-seconds 3", "--max-steps 10", ""}) {
    const auto start = std::chrono::steady_clock::now();
    const Result r = spinfold(
        std::string(
            "simulate spinning_rigid_sphere --t-end 10 --event phi:any:0:period=1e-300 --format csv ") +
        limit);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.exit_code, 3) << limit << ": " << r.err;
    EXPECT_NE(r.err.find("event_unresolved"), std::string::npos) << r.err;
    EXPECT_LT(seconds, 3.0) << limit;
  }
  // 1e-8: millions of crossings, every one counted (10,000 a step were, silently), in a moment.
  const auto start = std::chrono::steady_clock::now();
  const Result r = spinfold(
      "simulate spinning_rigid_sphere --t-end 10 --every 10 --event phi:any:0:period=1e-8 --format jsonl");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 3.0);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json summary = json::parse(lines_of(r.out).back())["summary"];
  EXPECT_GT(summary["phi_any_0.count"].get<double>(), 1e6) << summary;
}

// A write the system refuses (a full disk: /dev/full) is an error naming the file and the reason,
// exit 1, never a short file and exit 0 (every writer checks its writes, its flush and its close).
// The zip formats (png-zip, npz) are not asked to: libzip writes a file beside the path and renames
// it over it, which in /dev would replace the device (their checks: tests/record, tests/codec).
// Every crossing with its state (issue 51 item 3): --crossings FILE holds one row per recorded
// occurrence, the event's name, the occurrence and the sample's --fields there, in JSON Lines, CSV and
// npz; the summary's count, t_first and t_last agree; the same rows at another --every.
TEST(SimulateOutput, RecordedCrossingsAreATableOfTheirOwn) {
  TempDir dir;
  const std::string run =
      "simulate spin_vs_geodesic_torus --t-end 60 --fields t,u,phi,heading --event u:up:0:record "
      "--crossings ";
  const Result jsonl = spinfold(run + (dir.path / "c.jsonl").string());
  ASSERT_EQ(jsonl.exit_code, 0) << jsonl.err;
  const json summary = json::parse(lines_of(jsonl.out).back())["summary"];
  const std::vector<std::string> rows = lines_of(slurp(dir.path / "c.jsonl"));
  ASSERT_TRUE(json::parse(rows[0]).contains("provenance"));
  const auto count = summary["u_up_0.count"].get<std::uint64_t>();
  ASSERT_GE(count, 2u);
  ASSERT_EQ(rows.size(), count + 1) << "one row per crossing after the provenance";
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const json row = json::parse(rows[k]);
    EXPECT_EQ(row["event"], "u_up_0");
    EXPECT_EQ(row["occurrence"], k);
    EXPECT_LT(std::abs(row["u"].get<double>()), 1e-9) << rows[k];
  }
  EXPECT_EQ(json::parse(rows[1])["t"], summary["u_up_0.t_first"]);
  EXPECT_EQ(json::parse(rows.back())["t"], summary["u_up_0.t_last"]);
  // Sampled elsewhere: the same rows; as CSV and npz: the same numbers.
  const Result finer = spinfold(
      "simulate spin_vs_geodesic_torus --t-end 60 --every 0.07 --fields t,u,phi,heading "
      "--event u:up:0:record --crossings " +
      (dir.path / "f.jsonl").string());
  ASSERT_EQ(finer.exit_code, 0) << finer.err;
  const std::vector<std::string> again = lines_of(slurp(dir.path / "f.jsonl"));
  EXPECT_EQ(std::vector<std::string>(again.begin() + 1, again.end()),
            std::vector<std::string>(rows.begin() + 1, rows.end()))
      << "the same rows after the provenance (whose command differs)";
  ASSERT_EQ(spinfold(run + (dir.path / "c.csv").string()).exit_code, 0);
  const std::vector<std::string> csv = lines_of(slurp(dir.path / "c.csv"));
  EXPECT_EQ(csv[0], "event,occurrence,t,u,phi,heading");
  std::size_t data = 0;
  for (const std::string& line : csv)
    if (!line.empty() && line[0] != '#' && line != csv[0]) {
      const json row = json::parse(rows[++data]);
      const std::vector<std::string> cells = cells_of(line);
      EXPECT_EQ(cells[0], "u_up_0");
      EXPECT_EQ(std::stod(cells[2]), row["t"].get<double>()) << line;
    }
  EXPECT_EQ(data, count);
  ASSERT_EQ(spinfold(run + (dir.path / "c.npz").string()).exit_code, 0);
  EXPECT_GT(fs::file_size(dir.path / "c.npz"), 100u);
  // Asked for, it has a file; a file with nothing recording is refused; a sweep has no room for it.
  const Result no_file = spinfold("simulate spinning_rigid_sphere --t-end 1 --event phi:up:0:record");
  EXPECT_EQ(no_file.exit_code, 2);
  EXPECT_NE(no_file.err.find("give --crossings FILE"), std::string::npos) << no_file.err;
  const Result no_event = spinfold("simulate spinning_rigid_sphere --t-end 1 --event phi:up:0 --crossings " +
                                   (dir.path / "x.csv").string());
  EXPECT_EQ(no_event.exit_code, 2);
  EXPECT_NE(no_event.err.find("--crossings: no --event records"), std::string::npos) << no_event.err;
  const Result sweep =
      spinfold("sweep spinning_rigid_sphere --set initial.spin=0,1 --t-end 1 --event phi:up:0:record");
  EXPECT_EQ(sweep.exit_code, 2);
  EXPECT_NE(sweep.err.find("record them with `spinfold simulate --crossings`"), std::string::npos)
      << sweep.err;
}

TEST(SimulateOutput, AFullDeviceIsAnErrorNamingTheFile) {
  for (const std::string args : {
           "simulate spinning_rigid_sphere --t-end 1 --format csv --out /dev/full",
           "simulate spinning_rigid_sphere --t-end 1 --format jsonl --out /dev/full",
           "simulate spinning_rigid_sphere --t-end 200 --every 0.01 --format csv --out /dev/full",
           "render spinning_rigid_sphere --width 64 --height 48 --out /dev/full",
           "render spinning_rigid_sphere --width 64 --height 48 --format svg --out /dev/full",
           "sweep spinning_rigid_sphere --set initial.spin=0,1 --t-end 1 --out /dev/full",
           "record spinning_rigid_sphere --t-end 0.3 --fps 10 --width 64 --height 48 --format gif --out "
           "/dev/full",
           "record spinning_rigid_sphere --t-end 0.3 --fps 10 --width 64 --height 48 --format webm --out "
           "/dev/full",
           "record spinning_rigid_sphere --t-end 0.3 --fps 10 --width 64 --height 48 --format mp4 --out "
           "/dev/full",
       }) {
    const Result r = spinfold(args);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_NE(r.exit_code, 3) << args << ": not a run's stop";
    EXPECT_NE(r.err.find("/dev/full"), std::string::npos) << args << ": " << r.err;
  }
  for (const std::string args : {"simulate spinning_rigid_sphere --t-end 1 --format csv --out /dev/full",
                                 "render spinning_rigid_sphere --width 64 --height 48 --out /dev/full"}) {
    const Result r = spinfold(args);
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << args << ": " << r.err;
  }
  // Standard output on a full device.
  const Result r = spinfold("simulate spinning_rigid_sphere --t-end 1 > /dev/full");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("standard output"), std::string::npos) << r.err;
}

TEST(SimulateOutput, AKilledRunLeavesWholeLinesButTheOneBeingWritten) {
  TempDir dir;
  const fs::path out = dir.path / "run.csv";
  // A long run; killed with SIGKILL once rows are in the file.
  std::system(
      ("bash -c '" + std::string(SPINFOLD_BINARY) +
       " simulate --scene spinning_rigid_sphere --integrator rk4 --dt 1e-4 --t-end 1e5 --every 0.5 --out " +
       out.string() + " & p=$!; i=0; while [ $i -lt 200 ]; do [ -f " + out.string() + " ] && [ $(wc -l < " +
       out.string() + ") -ge 6 ] && break; sleep 0.05; i=$((i+1)); done; kill -KILL $p; wait $p'")
          .c_str());
  std::string text = slurp(out);
  ASSERT_FALSE(text.empty());
  // Every line is written whole by one write(2); a SIGKILL that lands inside that write can still cut
  // it (the kernel stops a write to a file between pages on a fatal signal: 1 run in ~8 under load).
  // So: every line that ended is whole, and at most an unended last piece is a row's beginning, which
  // the readers (`sweep --merge`) drop.
  const std::size_t last_newline = text.rfind('\n');
  ASSERT_NE(last_newline, std::string::npos);
  const std::string tail = text.substr(last_newline + 1);
  text.resize(last_newline + 1);
  const auto lines = lines_of(text);
  ASSERT_GE(lines.size(), 5u);
  const std::size_t columns = cells_of(lines[0]).size();  // the header
  for (std::size_t i = 3; i < lines.size(); ++i) EXPECT_EQ(cells_of(lines[i]).size(), columns) << lines[i];
  if (!tail.empty()) {
    EXPECT_LE(cells_of(tail).size(), columns) << tail;
  }
}

}  // namespace

namespace {

// A GIF's comment extension (0x21 0xFE) joined from its sub-blocks (each at most 255 bytes).
std::string gif_comment(const std::string& gif) {
  const std::size_t at = gif.find("\x21\xFE");
  if (at == std::string::npos) return "";
  std::string text;
  for (std::size_t pos = at + 2; pos < gif.size() && gif[pos] != 0;) {
    const auto length = static_cast<unsigned char>(gif[pos]);
    text += gif.substr(pos + 1, length);
    pos += 1 + length;
  }
  return text;
}

TEST(SimulateOutput, RecordingsCarryTheProvenanceInTheirContainers) {
  TempDir dir;
  for (const char* format : {"gif", "png-zip", "webm"}) {
    const fs::path out =
        dir.path / (std::string("clip.") + (std::string(format) == "png-zip" ? "zip" : format));
    const Result r =
        spinfold(std::string("record --scene spinning_rigid_sphere --t-end 0.2 --fps 10 --width 64 "
                             "--height 48 --quiet --format ") +
                 format + " --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << format << ": " << r.err;
    // A GIF comment extension, the zip's archive comment (and each PNG's Source text), the WebM
    // container's comment tag: each holds the provenance JSON with the window and the view.
    const std::string bytes = std::string(format) == "gif" ? gif_comment(slurp(out)) : slurp(out);
    const std::size_t at = bytes.find("\"scene_hash\":\"");
    ASSERT_NE(at, std::string::npos) << format;
    EXPECT_NE(bytes.find("\"t_end\":0.2"), std::string::npos) << format;
    EXPECT_NE(bytes.find("\"view\":\"sphere\""), std::string::npos) << format;
    EXPECT_NE(bytes.find("record --scene spinning_rigid_sphere"), std::string::npos) << format;
  }
}

}  // namespace
