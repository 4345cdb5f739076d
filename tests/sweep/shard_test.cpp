// Shards and their merge: the rows of one process, other sweeps' shards and missing runs refused.
#include "sweep/shard.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "codec/presets.h"
#include "sweep/rows.h"
#include "tests/error_of.h"

namespace spinfold::sweep {
namespace {

namespace fs = std::filesystem;

std::string error_of(const auto& call) {
  return test::error_of<SweepError>(call);
}

TEST(SweepShard, ParseAndRuns) {
  EXPECT_EQ(parse_shard("").count, 1u);
  EXPECT_EQ(parse_shard("2/3").index, 2u);
  for (const char* bad : {"3/3", "1", "a/2", "1/0", "-1/2"})
    EXPECT_NE(error_of([&] { parse_shard(bad); }).find("--shard"), std::string::npos) << bad;
  EXPECT_EQ(shard_runs(7, {1, 3}), (std::vector<std::size_t>{1, 4}));
}

TEST(SweepShard, MergedShardsAreTheRowsOfOneOutput) {
  const fs::path dir = fs::temp_directory_path() / ("sweep_shard_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Definition def;
  def.base_text = std::string(find_preset("spinning_rigid_sphere")->json);
  def.axes.push_back(axis_from_spec("initial.r", "1:1.4:5", "--set initial.r"));
  def.fields = "t";
  const Plan plan = make_plan(std::move(def));
  const auto write = [&](Shard shard, const fs::path& path) {
    std::ofstream out(path);
    out << header_text(plan, Format::csv, shard, "shard");
    for (std::size_t i : shard_runs(plan.total, shard)) {
      Row row{.index = i, .cells = {{"t", 1.0 * static_cast<double>(i)}}, .ok = true};
      out << row_text(row, Format::csv);
    }
  };
  write({0, 2}, dir / "a.csv");
  write({1, 2}, dir / "b.csv");
  merge_shards({(dir / "a.csv").string(), (dir / "b.csv").string()}, (dir / "all.csv").string(), "merge");
  std::ifstream in(dir / "all.csv");
  std::stringstream text;
  text << in.rdbuf();
  // The sweep's own command stays (shard 0's), the merge's is added.
  EXPECT_NE(text.str().find("# command: shard\n# merge: merge\n"), std::string::npos) << text.str();
  EXPECT_TRUE(text.str().starts_with("index,initial_r,t,")) << text.str();
  EXPECT_NE(text.str().find("# shard: 0/1\n"), std::string::npos);
  EXPECT_TRUE(text.str().ends_with("\n0,0.0\n1,1.0\n2,2.0\n3,3.0\n4,4.0\n")) << text.str();
  EXPECT_NE(error_of([&] {
              merge_shards({(dir / "a.csv").string()}, (dir / "x.csv").string(), "m");
            }).find("runs missing (1, 3) of 5"),
            std::string::npos);
  EXPECT_NE(
      error_of([&] {
        merge_shards({(dir / "a.csv").string(), (dir / "a.csv").string()}, (dir / "x.csv").string(), "m");
      }).find("given twice"),
      std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace spinfold::sweep
