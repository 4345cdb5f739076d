// The trajectory CSV: a column block per body, empty cells for undefined values, quoted labels.
#include "codec/trajectory_csv.h"

#include <gtest/gtest.h>

#include <sstream>

#include "codec/presets.h"
#include "codec/sample_json.h"
#include "codec/scene_json.h"

namespace spinfold {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(TrajectoryCsv, OneColumnBlockPerBody) {
  nlohmann::json document = nlohmann::json::parse(find_preset("opposite_spins_sphere")->json);
  document["companions"][0]["label"] = "s = -1, mirrored";  // a comma: the header cell is quoted
  Simulation run = start_simulation(*parse_scene(document).scene);
  std::vector<nlohmann::ordered_json> samples = {sample_to_json(run, -1.0)};
  advance_to(run, 1.0);
  samples.push_back(sample_to_json(run, 0.0));
  const std::vector<std::string> lines = lines_of(trajectory_csv(samples));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].rfind(
                "t,r,phi,lambda,mu,det_L,energy,energy_error,X0,X1,X2,status,\"s = -1, mirrored.r\",", 0),
            0u)
      << lines[0];
  // 1 + 11 + 11 cells a row (each of the 11 quoted header cells of the companion holds a comma).
  for (const std::string& line : lines)
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), line == lines[0] ? 33 : 22) << line;
  // The second row: t = 1, then the main body's r, then the companion's block ending in its status.
  EXPECT_EQ(lines[2].rfind("1.0,", 0), 0u);
  EXPECT_EQ(lines[2].substr(lines[2].size() - 3), ",ok");
  EXPECT_NE(lines[2].find(nlohmann::json(samples[1]["companions"][0]["r"]).dump()), std::string::npos);
}

TEST(TrajectoryCsv, ASingleBodyKeepsTheColumnsItHad) {
  Simulation run = start_simulation(*parse_scene_text(find_preset("spinning_rigid_sphere")->json).scene);
  const std::vector<nlohmann::ordered_json> samples = {sample_to_json(run, -1.0)};
  const std::vector<std::string> lines = lines_of(trajectory_csv(samples));
  EXPECT_EQ(lines[0], "t,r,phi,lambda,mu,det_L,energy,energy_error,X0,X1,X2,status");
}

}  // namespace
}  // namespace spinfold
