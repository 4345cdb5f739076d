// A sweep's runs: each row is the run `spinfold simulate` makes (the one sampling loop), to the bit;
// rows come back in run order from any number of threads; a refused scene is its row's status.
#include "sweep/run.h"

#include <gtest/gtest.h>

#include "codec/presets.h"
#include "codec/sample_json.h"
#include "codec/sample_table.h"
#include "codec/scene_json.h"
#include "engine/sampling.h"

namespace spinfold::sweep {
namespace {

Plan plan_of(const std::string& spec, const std::string& path = "initial.r") {
  Definition def;
  def.base_text = std::string(find_preset("spinning_rigid_sphere")->json);
  def.axes.push_back(axis_from_spec(path, spec, "--set " + path));
  def.t_end = 2.0;
  def.every = 0.5;
  def.fields = "t,r,phi,drift.energy";
  return make_plan(std::move(def));
}

const nlohmann::ordered_json& cell(const Row& row, const std::string& name) {
  for (const auto& [n, v] : row.cells)
    if (n == name) return v;
  throw std::out_of_range(name);
}

TEST(SweepRun, ARowIsTheRunOfTheSamplingLoopToTheBit) {
  const Plan plan = plan_of("1,1.5");
  const Row row = run_one(plan, 1);
  EXPECT_TRUE(row.ok);
  EXPECT_EQ(cell(row, "initial.r"), 1.5);
  Simulation run = start_simulation(*parse_scene(run_document(plan, 1)).scene);
  nlohmann::ordered_json first, last;
  sample_run(
      run, 2.0, 0.5, [&](double t) { return advance_to(run, t); },
      [&] { (first.is_null() ? first : last) = sample_to_json(run, -1.0); });
  EXPECT_EQ(cell(row, "t"), 2.0);
  EXPECT_EQ(cell(row, "r").get<double>(), last["r"].get<double>());
  EXPECT_EQ(cell(row, "phi").get<double>(), last["phi"].get<double>());
  EXPECT_EQ(cell(row, "drift.energy").get<double>(),
            last["energy"].get<double>() - first["energy"].get<double>());
  EXPECT_EQ(cell(row, "steps").get<std::uint64_t>(), run.steps);
}

TEST(SweepRun, RowsComeInRunOrderFromManyThreads) {
  const Plan plan = plan_of("0.5:1.5:9");
  const std::vector<std::size_t> runs = {0, 2, 4, 6, 8};
  std::vector<std::size_t> order;
  Progress last{};
  run_all(
      plan, runs, 4, [&](Row&& row) { order.push_back(row.index); }, [&](const Progress& p) { last = p; });
  EXPECT_EQ(order, runs);
  EXPECT_EQ(last.done, 5u);
  EXPECT_EQ(last.total, 5u);
  EXPECT_EQ(last.not_ok, 0u);
}

TEST(SweepRun, ARefusedCombinationIsItsRowsStatus) {
  // A rigid body's mu must equal lambda: each value alone is allowed, the run is refused.
  const Plan plan = plan_of("1,2", "initial.mu");
  const Row row = run_one(plan, 1);
  EXPECT_FALSE(row.ok);
  EXPECT_EQ(cell(row, "status"), "invalid_scene");
  EXPECT_NE(cell(row, "detail").get<std::string>().find("initial.mu"), std::string::npos);
  EXPECT_TRUE(cell(row, "r").is_null());
}

}  // namespace
}  // namespace spinfold::sweep
