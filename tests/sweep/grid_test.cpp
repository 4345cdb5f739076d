// The sweep's grid: the one a:b:n formula, the field paths, axes from a spec, values or a table,
// and the run limit, each refused with the label and the field named.
#include "sweep/grid.h"

#include <gtest/gtest.h>

#include <string>

#include "tests/error_of.h"

namespace spinfold::sweep {
namespace {

std::string error_of(const auto& call) {
  return test::error_of<SweepError>(call);
}

// NumPy's linspace formula (its check against numpy itself, for many a, b, n: tests/python/test_sweep.py).
TEST(SweepGrid, ValuesAreNumpysLinspaceWithTheLastExactlyB) {
  const auto v = grid_values(0.0, 2.0, 31);
  ASSERT_EQ(v.size(), 31u);
  for (std::size_t k = 0; k + 1 < v.size(); ++k) EXPECT_EQ(v[k], static_cast<double>(k) * (2.0 / 30.0) + 0.0);
  EXPECT_EQ(v.back(), 2.0);
  // The last bit where the old formula a + (b − a)·k/(n − 1) differs (issue 51: index 23 of 0:2:31).
  EXPECT_NE(v[23], 0.0 + 2.0 * 23.0 / 30.0);
  EXPECT_EQ(grid_values(0.1, 0.7, 1), std::vector<double>{0.1});
  // b exactly even where a + (b − a) rounds off.
  EXPECT_NE(0.7 + (0.1 - 0.7), 0.1);
  EXPECT_EQ(grid_values(0.7, 0.1, 3).back(), 0.1);
  // A step that underflows: (k/(n − 1))·(b − a) + a, as NumPy does.
  const auto tiny = grid_values(0.0, 1e-320, 4);
  EXPECT_EQ(tiny[1], (1.0 / 3.0) * 1e-320);
}

TEST(SweepGrid, AxesFromASpecValuesOrATable) {
  const Axis range = axis_from_spec("initial.r", "1:2:3", "--set initial.r");
  ASSERT_EQ(range.values.size(), 3u);
  EXPECT_EQ(range.values[1][0], 1.5);
  const Axis names = axis_from_assignment("integrator.name=auto,dop853");
  EXPECT_EQ(names.label, "--set integrator.name");
  EXPECT_EQ(names.values[1][0], "dop853");
  const Axis listed = axis_from_values("initial.r", nlohmann::json::array({1, 1.5}), "vary['initial.r']");
  EXPECT_TRUE(listed.values[0][0].is_number_float());
  const Axis table = axis_from_table("# cases\ninitial.r,initial.phi\n1,0\n2,0.5\n", "--table t.csv");
  ASSERT_EQ(table.fields.size(), 2u);
  EXPECT_EQ(table.values[1][1], 0.5);
}

TEST(SweepGrid, AFormulasParameterIsAFieldOfItsOwnName) {
  const Axis a = axis_from_spec("surface.parameters.a", "1:3:9", "--set surface.parameters.a");
  ASSERT_EQ(a.values.size(), 9u);
  EXPECT_EQ(a.values[4][0], 2.0);
  EXPECT_EQ(a.fields[0]->path, "surface.parameters.a");
  // A name the formula language cannot have is no field.
  EXPECT_NE(error_of([] {
              axis_from_assignment("surface.parameters.2a=1");
            }).find("no scene field 'surface.parameters.2a'"),
            std::string::npos);
}

TEST(SweepGrid, BadInputNamesTheLabelAndTheField) {
  EXPECT_NE(
      error_of([] { axis_from_assignment("initial.nope=1"); }).find("--set: no scene field 'initial.nope'"),
      std::string::npos);
  EXPECT_EQ(error_of([] { axis_from_spec("initial.lambda", "-1,1", "L"); }),
            "L: initial.lambda: must be > 0 (got '-1')");
  EXPECT_NE(
      error_of([] { axis_from_spec("initial.r", "-1:1:3", "L"); }).find("initial.r: must be >= 0 (got -1 in"),
      std::string::npos);
  EXPECT_NE(error_of([] { axis_from_spec("initial.r", "1:2:x", "L"); }).find("a:b:n"), std::string::npos);
  EXPECT_NE(error_of([] { axis_from_spec("initial.r", "0:1:10000001", "L"); }).find("1..10000000"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              axis_from_values("integrator.name", nlohmann::json::array({1}), "vary['integrator.name']");
            }).find("vary['integrator.name']: integrator.name: not a text"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              axis_from_values("initial.r", nlohmann::json::array({"x"}), "V");
            }).find("not a finite number"),
            std::string::npos);
  EXPECT_NE(error_of([] { axis_from_table("initial.r\n1,2\n", "--table t"); }).find("--table t line 2"),
            std::string::npos);
}

TEST(SweepGrid, TheRunLimitNamesTheAxisThatPassesIt) {
  std::vector<Axis> axes = {axis_from_spec("initial.r", "1:2:10000", "--set initial.r"),
                            axis_from_spec("initial.phi", "0:1:10000", "--set initial.phi")};
  EXPECT_NE(error_of([&] {
              run_count(axes, false);
            }).find("--set initial.phi: the sweep would be more than 10000000 runs"),
            std::string::npos);
  axes[1] = axis_from_spec("initial.phi", "0:1:3", "--set initial.phi");
  EXPECT_EQ(run_count(axes, false), 30000u);
  EXPECT_NE(error_of([&] { run_count(axes, true, "zip"); }).find("zip: every varied field"),
            std::string::npos);
  // The last axis varies fastest.
  EXPECT_EQ(axis_steps(axes, false, 4), (std::vector<std::size_t>{1, 1}));
  EXPECT_EQ(axis_steps(axes, true, 2), (std::vector<std::size_t>{2, 2}));
}

}  // namespace
}  // namespace spinfold::sweep
