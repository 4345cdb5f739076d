// A sweep's definition made a plan: the rules both front doors share, with each door's names.
#include "sweep/plan.h"

#include <gtest/gtest.h>

#include "codec/presets.h"

namespace spinfold::sweep {
namespace {

Definition definition(Door door = Door::cli) {
  Definition def;
  def.base_text = std::string(find_preset("spinning_rigid_sphere")->json);
  def.axes.push_back(axis_from_spec("initial.r", "1,1.5", "--set initial.r"));
  def.door = door;
  return def;
}

std::string error_of(Definition def) {
  try {
    make_plan(std::move(def));
  } catch (const SweepError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SweepPlan, DefaultColumnsAndRunDocuments) {
  const Plan plan = make_plan(definition());
  EXPECT_EQ(plan.total, 2u);
  ASSERT_EQ(plan.columns.size(), 9u);  // kDefaultFields
  EXPECT_EQ(plan.columns.back().name, "drift.p_phi");
  EXPECT_TRUE(plan.columns.back().drift);
  EXPECT_EQ(run_document(plan, 1)["initial"]["r"], 1.5);
  EXPECT_EQ(varied_values(plan, 0)[0].first, "initial.r");
}

// A vector or group in fields (and after drift.) is its components, in the table's order.
TEST(SweepPlan, AVectorFieldIsItsComponents) {
  Definition def = definition();
  def.fields = "X,drift.L.0,integrator";
  const Plan plan = make_plan(def);
  std::vector<std::string> names;
  for (const Column& c : plan.columns) names.push_back(c.name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"X.0", "X.1", "X.2", "drift.L.0.0", "drift.L.0.1", "integrator"}));
  EXPECT_EQ(plan.columns[3].key, "L.0.0");
  EXPECT_TRUE(plan.columns[3].drift);
  def.fields = "X.";
  EXPECT_NE(error_of(def).find("unknown field 'X.'"), std::string::npos) << error_of(def);
}

// On a torus: the default columns are its chart's (u, and K), a field of the other family is
// refused with its axis before any run, and the torus's own parameters sweep.
TEST(SweepPlan, ATorusBaseSweepsItsOwnFields) {
  Definition def;
  def.base_text = R"({"surface": {"kind": "torus"}, "initial": {"u": 0.3, "phi_dot": 0.5}})";
  def.axes.push_back(axis_from_spec("surface.tube_radius", "0.3:0.9:7", "--set surface.tube_radius"));
  const Plan plan = make_plan(def);
  EXPECT_EQ(plan.total, 7u);
  ASSERT_EQ(plan.columns.size(), 10u);  // kDefaultProfileFields
  EXPECT_EQ(plan.columns[1].name, "u");
  EXPECT_EQ(plan.columns.back().name, "K");
  EXPECT_EQ(run_document(plan, 6)["surface"]["tube_radius"], 0.9);
  Definition wrong = def;
  wrong.axes = {axis_from_spec("initial.r", "1,1.5", "--set initial.r")};
  const std::string error = error_of(wrong);
  EXPECT_NE(error.find("initial.r: is not defined on the torus"), std::string::npos) << error;
}

TEST(SweepPlan, RulesAreRefusedInTheDoorsNames) {
  Definition bad = definition();
  bad.t_end = -1;
  // In the words of simulate's --t-end and Python's simulate (engine/run_limits.h).
  EXPECT_EQ(error_of(bad), "--t-end: must be a number >= 0 [time] (got '-1')");
  bad.door = Door::python;
  EXPECT_EQ(error_of(bad), "t_end: must be a number >= 0 [time] (got -1)");
  Definition steps = definition();
  steps.max_steps = 0;
  EXPECT_EQ(error_of(steps), "--max-steps: must be a whole number from 1 to 9007199254740992 (got '0')");
  Definition fields = definition(Door::python);
  fields.fields = "t,bogus";
  EXPECT_NE(error_of(fields).find("fields: unknown field 'bogus'"), std::string::npos);
  Definition none = definition();
  none.axes.clear();
  EXPECT_NE(error_of(none).find("nothing to vary"), std::string::npos);
  Definition twice = definition();
  twice.axes.push_back(axis_from_spec("initial.r", "2", "--set initial.r"));
  EXPECT_NE(error_of(twice).find("initial.r is varied twice"), std::string::npos);
  Definition many = definition(Door::python);
  many.axes = {axis_from_spec("initial.r", "1:2:5000", "vary['initial.r']"),
               axis_from_spec("initial.phi", "0:1:5000", "vary['initial.phi']")};
  EXPECT_NE(error_of(many).find("vary['initial.phi']: the sweep would be more than 10000000 runs"),
            std::string::npos);
  Definition structural = definition();
  structural.base_text = std::string(find_preset("breathing_ellipse_sphere")->json);
  structural.axes = {axis_from_spec("potential.deformation.ghat", "1", "--set potential.deformation.ghat")};
  EXPECT_NE(error_of(structural).find("is not a known field here"), std::string::npos);
}

TEST(SweepPlan, AFieldThatStandsInForOthersReplacesThem) {
  nlohmann::json document = {{"surface", {{"kind", "sphere"}, {"radius", 1.0}}}};
  apply_values(document, {&scene_field("surface.curvature", "test")}, {-1.0});
  EXPECT_FALSE(document["surface"].contains("kind"));
  EXPECT_EQ(document["surface"]["curvature"], -1.0);
  apply_values(document, {&scene_field("surface.radius", "test")}, {2.0});
  EXPECT_FALSE(document["surface"].contains("curvature"));
}

TEST(SweepPlan, FieldNamesAndDoorNames) {
  const auto names = field_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "drift.casimir"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "integrator"), names.end());
  EXPECT_EQ(option_name(Door::python, "--max-steps"), "max_steps");
  EXPECT_EQ(option_name(Door::cli, "--max-steps"), "--max-steps");
}

}  // namespace
}  // namespace spinfold::sweep
