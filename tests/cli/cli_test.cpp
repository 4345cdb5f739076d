// The spinfold binary as a user runs it: JSON Lines out, exit code 2 and nothing on stdout for bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "codec/presets.h"
#include "tests/cli/run_spinfold.h"

namespace {

using spinfold::cli_test::Result;
Result spinfold(const std::string& args) {
  return spinfold::cli_test::run_spinfold(args);
}

// The samples `simulate` printed, after its first record: the provenance.
std::vector<nlohmann::json> lines(const std::string& out) {
  std::vector<nlohmann::json> rows;
  std::istringstream in(out);
  std::string line;
  if (!std::getline(in, line) || !nlohmann::json::parse(line).contains("provenance")) {
    ADD_FAILURE() << "no provenance record first: " << line;
    return rows;
  }
  for (; std::getline(in, line);) rows.push_back(nlohmann::json::parse(line));
  return rows;
}

TEST(Cli, SimulatePrintsOneSampleEveryDeltaUpToT) {
  const Result r = spinfold("simulate --scene spinning_rigid_sphere --t-end 2 --every 0.5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 5u);
  for (size_t k = 0; k < rows.size(); ++k) EXPECT_DOUBLE_EQ(rows[k]["t"].get<double>(), 0.5 * k);
  for (const char* key :
       {"t",       "r",         "phi",      "alpha",      "beta",   "lambda", "mu",        "r_dot",
        "phi_dot", "alpha_dot", "beta_dot", "lambda_dot", "mu_dot", "p_r",    "p_phi",     "p_alpha",
        "p_beta",  "X",         "L",        "det_L",      "energy", "status", "integrator"})
    EXPECT_TRUE(rows.back().contains(key)) << key;
  EXPECT_EQ(rows.back()["status"], "ok");
  EXPECT_EQ(rows.back()["X"].size(), 3u);
  EXPECT_EQ(rows.back()["L"].size(), 2u);
  // λ = μ: α and β are undefined, said so, and never NaN.
  EXPECT_TRUE(rows.back()["alpha"].is_null());
  EXPECT_TRUE(rows.back()["undefined"].contains("alpha"));
  EXPECT_NEAR(rows.back()["energy_error"].get<double>(), 0.0, 1e-9);
}

TEST(Cli, LastSampleLandsOnTEvenWhenDeltaDoesNotDivideIt) {
  const Result r = spinfold("simulate --scene geodesic_rigid_sphere --t-end 1 --every 0.3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 5u);  // 0, 0.3, 0.6, 0.9, 1
  EXPECT_DOUBLE_EQ(rows.back()["t"].get<double>(), 1.0);
}

TEST(Cli, DefaultSceneRunsWithoutArguments) {
  const Result r = spinfold("simulate --t-end 1 --every 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(lines(r.out).size(), 2u);
}

TEST(Cli, SceneFileAndOverrides) {
  const Result r = spinfold(std::string("simulate ") + SPINFOLD_SCENES_DIR +
                            "/separable_radial_abc.json --t-end 2 --every 2 --integrator rk4 --dt 0.001");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  EXPECT_EQ(rows.back()["integrator"], "rk4");
  EXPECT_NEAR(rows.back()["r"].get<double>(), 1.650073264590784, 1e-9);  // physics.md W5
}

TEST(Cli, DegenerateCrossingIsReportedInTheSample) {
  const Result r = spinfold("simulate --scene degenerate_crossing --t-end 1 --every 0.25");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 5u);
  // Exactly one crossing, at t = 0.5, reported with the first sample at or after it.
  int reported = 0;
  for (const auto& row : rows)
    for (const auto& event : row["events"]) {
      ++reported;
      EXPECT_NEAR(event["t"].get<double>(), 0.5, 1e-9);
      EXPECT_GE(row["t"].get<double>(), event["t"].get<double>());
      EXPECT_LT(row["t"].get<double>() - event["t"].get<double>(), 0.25);
    }
  EXPECT_EQ(reported, 1);
  EXPECT_LT(rows[4]["det_L"].get<double>(), 0.0);
}

TEST(Cli, SameSceneSameBytes) {
  const std::string args = "simulate --scene breathing_ellipse_sphere --t-end 5 --every 0.5";
  EXPECT_EQ(spinfold(args).out, spinfold(args).out);
}

TEST(Cli, ScenesListsEveryPreset) {
  const Result r = spinfold("scenes");
  ASSERT_EQ(r.exit_code, 0);
  for (const auto& entry : std::filesystem::directory_iterator(SPINFOLD_SCENES_DIR))
    EXPECT_NE(r.out.find(entry.path().stem().string()), std::string::npos) << entry.path();
}

TEST(Cli, IntegratorsPrintsTheCatalog) {
  const Result r = spinfold("integrators");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("dop853"), std::string::npos);
  EXPECT_NE(r.out.find("rk4"), std::string::npos);
}

struct BadArgs {
  const char* args;
  const char* message;  // a fragment the stderr message must contain
};

void PrintTo(const BadArgs& b, std::ostream* os) {
  *os << "spinfold " << b.args;
}

class CliBadInput : public ::testing::TestWithParam<BadArgs> {};

TEST_P(CliBadInput, ExitsTwoWithAMessageAndNoOutput) {
  const Result r = spinfold(GetParam().args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find(GetParam().message), std::string::npos) << r.err;
}

INSTANTIATE_TEST_SUITE_P(
    Table, CliBadInput,
    ::testing::Values(BadArgs{"simulate --scene no_such_scene", "no preset named"},
                      BadArgs{"simulate /nonexistent/scene.json", "cannot read"},
                      BadArgs{"simulate --scene spinning_rigid_sphere --t-end -1", "--t-end"},
                      BadArgs{"simulate --scene spinning_rigid_sphere --every 0", "--every"},
                      BadArgs{"simulate --scene spinning_rigid_sphere --integrator euler", "integrator.name"},
                      BadArgs{"simulate --scene spinning_rigid_sphere --dt -0.1", "integrator.dt"},
                      BadArgs{"simulate --scene spinning_rigid_sphere --tolerance 5", "integrator.tolerance"},
                      BadArgs{"simulate --scene spinning_rigid_sphere --t-end abc", "t-end"},
                      BadArgs{"simulate --t-end 1e9 --every 1e-9", "samples"}, BadArgs{"explode", ""},
                      // A rate whose Retry-After would not fit an integer is bounded; these are refused.
                      BadArgs{"serve --port 0 --no-store --requests-per-second -1", "--requests-per-second"},
                      BadArgs{"serve --port 0 --no-store --requests-per-second 1e400",
                              "--requests-per-second"},
                      BadArgs{"", "subcommand"}));

TEST(Cli, BadSceneFileNamesTheField) {
  const std::string path =
      std::filesystem::temp_directory_path() / ("spinfold_bad_scene_" + std::to_string(getpid()) + ".json");
  std::ofstream(path) << R"({"body": {"mass": -1}, "surface": {"kind": "klein_bottle"}})";
  const Result r = spinfold("simulate " + path);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find("body.mass: must be > 0 (got -1)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("surface.kind"), std::string::npos) << r.err;
}

}  // namespace

namespace {

TEST(CliRender, WritesAPngOfTheRequestedSize) {
  const std::string out =
      std::filesystem::temp_directory_path() / ("spinfold_frame_" + std::to_string(getpid()) + ".png");
  const Result r =
      spinfold("render --scene spinning_rigid_sphere --t 2 --width 320 --height 200 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(out, std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 24u);
  EXPECT_EQ(std::string(bytes.begin() + 1, bytes.begin() + 4), "PNG");
  const auto be32 = [&](int at) {
    return (bytes[at] << 24) | (bytes[at + 1] << 16) | (bytes[at + 2] << 8) | bytes[at + 3];
  };
  EXPECT_EQ(be32(16), 320);  // IHDR width
  EXPECT_EQ(be32(20), 200);  // IHDR height
  std::filesystem::remove(out);
}

// --camera is --yaw, --pitch and --distance at once: the same picture to the byte; one of them alone
// replaces that part of the camera aimed at the body.
TEST(CliRender, CameraIsTheThreeCameraOptionsAtOnce) {
  const std::string base =
      std::filesystem::temp_directory_path() / ("spinfold_cam_" + std::to_string(getpid()));
  const auto render = [&](const std::string& name, const std::string& camera) {
    const Result r = spinfold("render --scene spinning_rigid_sphere --t 1 --width 96 --height 72 " + camera +
                              " --out " + base + name);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::ifstream in(base + name, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::filesystem::remove(base + name);
    // The image data only: the text chunks hold the command line (provenance).
    const std::size_t idat = bytes.find("IDAT");
    return idat == std::string::npos ? std::string() : bytes.substr(idat);
  };
  const std::string whole = render("a.png", "--camera 0.3,0.2,4");
  EXPECT_GT(whole.size(), 100u);
  EXPECT_EQ(render("b.png", "--yaw 0.3 --pitch 0.2 --distance 4"), whole);
  const std::string aimed = render("c.png", "");
  EXPECT_NE(render("d.png", "--distance 8"), aimed);  // farther away than aimed
}

class CliRenderBadInput : public ::testing::TestWithParam<BadArgs> {};

TEST_P(CliRenderBadInput, ExitsTwoWithAMessageAndNoOutput) {
  const Result r = spinfold(GetParam().args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find(GetParam().message), std::string::npos) << r.err;
}

INSTANTIATE_TEST_SUITE_P(
    Table, CliRenderBadInput,
    ::testing::Values(
        BadArgs{"render --scene spinning_rigid_sphere --view hyperboloid --out /tmp/x.png", "--view"},
        BadArgs{"render --scene spinning_rigid_sphere --view cube --out /tmp/x.png", "--view"},
        BadArgs{"render --scene spinning_rigid_sphere --width 5000 --out /tmp/x.png", "--width"},
        BadArgs{"render --scene spinning_rigid_sphere --layers body,glitter --out /tmp/x.png", "glitter"},
        BadArgs{"render --scene spinning_rigid_sphere --camera 1,2 --out /tmp/x.png", "--camera"},
        // The table's words, every layer listed (actions included), the ranges the API has.
        BadArgs{"render --scene spinning_rigid_sphere --layers body,glitter --out /tmp/x.png",
                "--layers: 'glitter' is not one of surface, grid, body, frame, trail, hud, actions, "
                "curvature, bending, drift, plain (got "
                "'body,glitter')"},
        BadArgs{"render --scene spinning_rigid_sphere --pitch 2 --out /tmp/x.png",
                "--pitch: must be a number from -1.55 to 1.55 [rad] (got '2')"},
        BadArgs{"render --scene spinning_rigid_sphere --camera 0.5,0.2,0.5 --out /tmp/x.png",
                "--camera: distance must be a number from 1.2 to 100 [radii]"},
        BadArgs{"render --scene spinning_rigid_sphere --scale 11 --out /tmp/x.png", "(0, 10]"},
        BadArgs{"record --t-end 1 --format gif --trail -1 --out /tmp/x.gif",
                "--trail: must be a number >= 0"},
        BadArgs{"render --scene spinning_rigid_sphere --t -1 --out /tmp/x.png", "--t"},
        BadArgs{"render --scene spinning_rigid_sphere", "--out"},
        BadArgs{"render --scene spinning_rigid_sphere --gl nonsense --out /tmp/x.png", "--gl"},
        BadArgs{"record --scene spinning_rigid_sphere --t-end 1 --format gif --out /tmp/x.gif --gl nonsense",
                "--gl"},
        BadArgs{"serve --port 0 --gl nonsense", "--gl"},
        BadArgs{"render --scene spinning_rigid_sphere --gl --out /tmp/x.png", "--gl"}));

// SPINFOLD_GL picks the backend as --gl does: each backend draws the still; a bad value is refused
// with exit 2 naming the variable.
Result with_gl_environment(const std::string& value, const std::string& args) {
  setenv("SPINFOLD_GL", value.c_str(), 1);
  const Result r = spinfold(args);
  unsetenv("SPINFOLD_GL");
  return r;
}

TEST(CliRender, EachGlBackendDrawsTheStillThroughTheEnvironment) {
  const std::string out =
      std::filesystem::temp_directory_path() / ("spinfold_gl_" + std::to_string(getpid()) + ".png");
  const std::string version = spinfold("--version").out;
  const std::string built_in = version.substr(version.find("GL backends built in:"));
  for (const char* backend : {"osmesa", "egl"}) {
    if (built_in.substr(0, built_in.find('\n')).find(backend) == std::string::npos)
      continue;  // not in this build
    const Result r = with_gl_environment(backend,
                                         "render --scene spinning_rigid_sphere --t 2 --width 160 "
                                         "--height 120 --out " +
                                             out);
    ASSERT_EQ(r.exit_code, 0) << backend << ": " << r.err;
    EXPECT_GT(std::filesystem::file_size(out), 1000u) << backend;
    std::filesystem::remove(out);
  }
  const Result bad = with_gl_environment("nonsense", "render --scene spinning_rigid_sphere --out " + out);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("SPINFOLD_GL"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Cli, VersionNamesTheGlBackendsBuiltInAndTheOneInUse) {
  const Result r = spinfold("--version");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("GL backends built in:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("GL in use:"), std::string::npos) << r.out;
}

// Not a terminal: no progress bar, nothing on stderr; the zip holds one PNG per frame (its
// central directory lists them: "frame-000000.png" … at 10 frames/s over [0.5, 0.8) = 3 frames).
TEST(CliRecord, WritesTheFramesQuietlyWhenStderrIsNoTerminal) {
  const std::string out =
      std::filesystem::temp_directory_path() / ("spinfold_clip_" + std::to_string(getpid()) + ".zip");
  const Result r = spinfold(
      "record --scene spin_vs_geodesic_sphere --t-start 0.5 --t-end 0.8 --fps 10 "
      "--width 64 --height 48 --format png-zip --out " +
      out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out, "");
  std::ifstream in(out, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bytes.substr(0, 2), "PK");
  EXPECT_NE(bytes.find("frame-000002.png"), std::string::npos);
  EXPECT_EQ(bytes.find("frame-000003.png"), std::string::npos);
  std::filesystem::remove(out);
}

INSTANTIATE_TEST_SUITE_P(
    Record, CliRenderBadInput,
    ::testing::Values(BadArgs{"record --t-end 1 --format avi --out /tmp/x.avi", "--format"},
                      BadArgs{"record --t-end 1 --fps 0 --format gif --out /tmp/x.gif", "--fps"},
                      BadArgs{"record --t-start 2 --t-end 1 --format gif --out /tmp/x.gif", "--t-end"},
                      BadArgs{"record --t-end 1 --width 65 --format webm --out /tmp/x.webm", "even"},
                      BadArgs{"record --t-end 1 --format gif --out /nonexistent/x.gif", "--out"},
                      BadArgs{"record --format gif --out /tmp/x.gif", "--t-end"}));

// Windows whose frame count does not fit an integer (or the 1e7 frames of one clip): exit 2 naming
// the option, before any file is made.
class CliRecordOutOfRange : public ::testing::TestWithParam<BadArgs> {};

TEST_P(CliRecordOutOfRange, ExitsTwoNamingTheOptionAndLeavesNoFile) {
  const std::string out =
      std::filesystem::temp_directory_path() / ("spinfold_out_of_range_" + std::to_string(getpid()) + ".gif");
  std::filesystem::remove(out);
  const Result r = spinfold(std::string("record --scene spinning_rigid_sphere ") + GetParam().args +
                            " --width 64 --height 48 --format gif --out " + out);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find(GetParam().message), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out)) << "a file was left";
}

INSTANTIATE_TEST_SUITE_P(Table, CliRecordOutOfRange,
                         ::testing::Values(BadArgs{"--t-end 1e19", "--t-end"},
                                           BadArgs{"--t-end 1e308", "--t-end"},
                                           BadArgs{"--t-end 1 --speed 1e-300", "--speed"},
                                           BadArgs{"--t-end 400000", "--t-end"},  // 1.2e7 frames at 30/s
                                           BadArgs{"--t-end 1 --fps 1e-300", "--fps"},
                                           BadArgs{"--t-end 1 --fps 1e300", "--fps"},
                                           BadArgs{"--t-end 1 --width 1e19", "--width"}));

// A scene file that is not exactly one JSON value: a NUL byte and what follows it (nlohmann-json
// alone would stop reading at the NUL), trailing text, a second value.
TEST(Cli, SceneFileOfMoreThanOneJsonValueIsRefused) {
  const std::string path =
      std::filesystem::temp_directory_path() / ("spinfold_two_values_" + std::to_string(getpid()) + ".json");
  for (const std::string& text : {std::string(R"({"body": {"mass": 2.5}})") + '\0' + "garbage",
                                  std::string(R"({"body": {"mass": 2.5}} x)"),
                                  std::string(R"({"body": {"mass": 2.5}} {"body": {"mass": 3}})")}) {
    std::ofstream(path, std::ios::binary) << text;
    const Result r = spinfold("simulate " + path + " --t-end 0.5");
    EXPECT_EQ(r.exit_code, 2) << text;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find("malformed JSON"), std::string::npos) << r.err;
  }
  std::filesystem::remove(path);
}

}  // namespace
