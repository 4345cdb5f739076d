// `spinfold rerun FILE` (cli/commands/rerun.cpp) as a user runs it: an output made in one folder from
// a scene file, a preset, a sweep shard or a figure is made again from another folder, its scene
// file changed or gone, to the same bytes; what cannot be re-run is refused naming why.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>

#include "codec/presets.h"
#include "tests/cli/run_spinfold.h"

namespace spinfold {
namespace {

namespace fs = std::filesystem;
using cli_test::run_spinfold;

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A sweep's output without its `seconds` column (each run's wall time): CSV rows cut at their last
// comma, JSON Lines without the member, an npz's stored entries by name without seconds.npy.
std::map<std::string, std::string> without_seconds(const std::string& bytes, const std::string& ext) {
  std::map<std::string, std::string> parts;
  if (ext == "npz") {
    const auto u = [&](std::size_t at, int n) {
      std::size_t v = 0;
      for (int k = n - 1; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(bytes[at + k]);
      return v;
    };
    for (std::size_t at = 0; at + 30 <= bytes.size() && bytes.compare(at, 4, "PK\x03\x04") == 0;) {
      const std::size_t size = u(at + 18, 4), name = u(at + 26, 2), extra = u(at + 28, 2);
      const std::string entry = bytes.substr(at + 30, name);
      if (entry != "seconds.npy") parts[entry] = bytes.substr(at + 30 + name + extra, size);
      at += 30 + name + extra + size;
    }
    return parts;
  }
  std::istringstream lines(bytes);
  std::string line, kept;
  while (std::getline(lines, line)) {
    if (ext == "csv" && !line.starts_with('#')) line = line.substr(0, line.rfind(','));
    if (ext == "jsonl") line = std::regex_replace(line, std::regex(R"(,"seconds":[-+.0-9e]+)"), "");
    kept += line + '\n';
  }
  parts["text"] = kept;
  return parts;
}

// Two folders: where the output was made (with its scene file) and somewhere else; the command runs
// in one of them (the test's working directory, put back after).
class Rerun : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    root_ = fs::temp_directory_path() / ("spinfold_rerun_" + std::to_string(getpid()) + "_" + name);
    fs::remove_all(root_);
    fs::create_directories(made());
    fs::create_directories(elsewhere());
    back_ = fs::current_path();
    nlohmann::json scene = nlohmann::json::parse(find_preset("spin_vs_geodesic_torus")->json);
    scene["initial"]["spin"] = 0.45;  // not a preset's scene
    write(made() / "lesson.json", scene.dump(2));
  }
  void TearDown() override {
    fs::current_path(back_);
    fs::remove_all(root_);
  }
  fs::path made() const { return root_ / "made"; }
  fs::path elsewhere() const { return root_ / "elsewhere"; }
  cli_test::Result in(const fs::path& folder, const std::string& args) {
    fs::current_path(folder);
    return run_spinfold(args);
  }
  // The scene file changed after the output was made: a re-run must not read it.
  void change_the_scene_file() { write(made() / "lesson.json", R"({"surface": {"kind": "plane"}})"); }

 private:
  fs::path root_, back_;
};

TEST_F(Rerun, ASceneFilesSamplesAndCrossingsAreMadeAgainElsewhereToTheByte) {
  for (const std::string ext : {"csv", "jsonl", "npz"}) {
    const auto first = in(made(),
                          "simulate lesson.json --t-end 3 --every 0.25 --event phi:any:0:record "
                          "--crossings crossings." +
                              ext + " --out samples." + ext);
    ASSERT_EQ(first.exit_code, 0) << first.err;
    change_the_scene_file();
    const auto again = in(elsewhere(), "rerun ../made/samples." + ext + " --out again." + ext +
                                           " --crossings crossings_again." + ext);
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(read(elsewhere() / ("again." + ext)), read(made() / ("samples." + ext))) << ext;
    EXPECT_EQ(read(elsewhere() / ("crossings_again." + ext)), read(made() / ("crossings." + ext))) << ext;
    EXPECT_GT(read(made() / ("samples." + ext)).size(), 1000u);
    // every output the command wrote is given anew
    const auto samples_only = in(elsewhere(), "rerun ../made/samples." + ext + " --out only." + ext);
    EXPECT_EQ(samples_only.exit_code, 2);
    EXPECT_NE(samples_only.err.find("wrote --crossings crossings." + ext + "; give rerun --crossings FILE"),
              std::string::npos)
        << samples_only.err;
    EXPECT_FALSE(fs::exists(elsewhere() / ("only." + ext)));
  }
  // printed samples re-run to standard output
  const auto printed = in(made(), "simulate lesson.json --t-end 1 --every 0.5");
  ASSERT_EQ(printed.exit_code, 0);
  write(made() / "printed.jsonl", printed.out);
  const auto again = in(elsewhere(), "rerun ../made/printed.jsonl");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(again.out, printed.out);
}

TEST_F(Rerun, APresetsPicturesAreMadeAgainToTheByte) {
  for (const std::string ext : {"png", "svg", "pdf"}) {
    const auto first = in(made(),
                          "render --scene spin_vs_geodesic_torus --t 2 --width 160 --height 120 "
                          "--out picture." +
                              ext);
    ASSERT_EQ(first.exit_code, 0) << first.err;
    const auto again = in(elsewhere(), "rerun ../made/picture." + ext + " --out again." + ext);
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(read(elsewhere() / ("again." + ext)), read(made() / ("picture." + ext))) << ext;
  }
}

TEST_F(Rerun, AFigureIsMadeAgainToTheByte) {
  for (const std::string ext : {"svg", "pdf"}) {
    const auto first =
        in(made(), "plot lesson.json --fields t,energy_error,u --t-end 2 --every 0.05 --out figure." + ext);
    ASSERT_EQ(first.exit_code, 0) << first.err;
    change_the_scene_file();
    const auto again =
        in(elsewhere(), "rerun " + (made() / ("figure." + ext)).string() + " --out again." + ext);
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(read(elsewhere() / ("again." + ext)), read(made() / ("figure." + ext))) << ext;
  }
}

TEST_F(Rerun, ASweepShardIsMadeAgainToTheByte) {
  for (const std::string ext : {"csv", "jsonl", "npz"}) {
    const auto first = in(made(),
                          "sweep lesson.json --set initial.spin=0:1:5 --t-end 1 --shard 1/2 --jobs 1 "
                          "--fields t,phi,energy,det_L --out shard." +
                              ext);
    ASSERT_EQ(first.exit_code, 0) << first.err;
    change_the_scene_file();
    const auto again = in(elsewhere(), "rerun ../made/shard." + ext + " --out again." + ext);
    ASSERT_EQ(again.exit_code, 0) << again.err;
    const auto made_again = without_seconds(read(elsewhere() / ("again." + ext)), ext);
    EXPECT_EQ(made_again, without_seconds(read(made() / ("shard." + ext)), ext)) << ext;
    EXPECT_GE(made_again.size(), ext == "npz" ? 9u : 1u);
  }
}

TEST_F(Rerun, RefusesWhatItCannotRerunSayingWhy) {
  write(made() / "notes.csv", "a,b\n1,2\n");
  auto r = in(made(), "rerun notes.csv --out x.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'notes.csv' carries no spinfold provenance"), std::string::npos) << r.err;
  r = in(made(), "rerun missing.csv --out x.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cannot read 'missing.csv'"), std::string::npos) << r.err;

  ASSERT_EQ(in(made(), "simulate lesson.json --t-end 0.5 --out samples.csv").exit_code, 0);
  r = in(made(), "rerun samples.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("wrote --out samples.csv; give rerun --out FILE"), std::string::npos) << r.err;
  r = in(made(), "rerun samples.csv --out ./samples.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("is the file re-run"), std::string::npos) << r.err;
  r = in(made(), "rerun samples.csv --out x.csv --crossings c.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("the recorded command wrote no --crossings"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(made() / "x.csv"));
}

}  // namespace
}  // namespace spinfold
