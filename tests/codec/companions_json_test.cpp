// The scene format's companions: merge patches over the main body's blocks, the geodesic
// shorthand, fans (vary), errors named by path, and writing back what was given.
#include <gtest/gtest.h>

#include "codec/scene_json.h"
#include "engine/initial_rates.h"

namespace spinfold {
namespace {

using nlohmann::json;

const json kMain = {
    {"surface", {{"kind", "sphere"}, {"radius", 1.0}}},
    {"body", {{"mass", 2.0}, {"inertia", 0.5}}},
    {"potential", {{"deformation", {{"kind", "abc"}, {"C", 0.3}}}}},
    {"initial", {{"r", 1.0}, {"lambda", 1.5}, {"mu", 0.5}, {"speed", 0.4}, {"heading", 1.0}, {"spin", 0.7}}}};

SceneParse with(const json& extra) {
  json document = kMain;
  document.merge_patch(extra);
  return parse_scene(document);
}
SceneParse with(const char* extra) {
  return with(json::parse(extra));
}

TEST(CompanionsJson, AnEntryPatchesTheMainBodysBlocks) {
  const SceneParse p =
      with(R"({"companions": [{"label": "lighter", "body": {"mass": 1.0}, "color": "#ff8000"}]})");
  ASSERT_TRUE(p.scene) << describe_errors(p.errors);
  const Companion& c = p.scene->companions.at(0);
  EXPECT_EQ(c.label, "lighter");
  EXPECT_EQ(c.body.mass, 1.0);
  EXPECT_EQ(c.body.inertia, 0.5);                                    // inherited
  EXPECT_TRUE(std::holds_alternative<AbcPotential>(c.deformation));  // inherited
  EXPECT_EQ(c.initial.lambda, 1.5);
  EXPECT_NEAR((*c.color)[0], 1.0, 0.0);
  EXPECT_NEAR((*c.color)[1], 128.0 / 255.0, 1e-15);
  // Its spin is its own body's: the same s = 0.7 with the other mass gives the same alpha_dot
  // (spin does not involve m) and the same speed and heading.
  const Scene companion = companion_scene(*p.scene, 0);
  EXPECT_NEAR(spin_of(companion), 0.7, 1e-14);
  EXPECT_NEAR(speed_of(companion), 0.4, 1e-15);
}

TEST(CompanionsJson, TheGeodesicShorthandIsAPointParticleFromTheSameStart) {
  const SceneParse p = with(R"({"companions": [{"geodesic": true}]})");
  ASSERT_TRUE(p.scene) << describe_errors(p.errors);
  const Companion& c = p.scene->companions.at(0);
  EXPECT_TRUE(c.geodesic);
  EXPECT_EQ(c.body.model, BodyModel::rigid);
  EXPECT_EQ(c.body.mass, 2.0);
  EXPECT_TRUE(std::holds_alternative<std::monostate>(c.deformation));
  EXPECT_EQ(c.initial.r, p.scene->initial.r);
  EXPECT_EQ(c.initial.r_dot, p.scene->initial.r_dot);
  EXPECT_EQ(c.initial.phi_dot, p.scene->initial.phi_dot);
  EXPECT_EQ(c.initial.lambda, c.initial.mu);
  EXPECT_EQ(spin_of(companion_scene(*p.scene, 0)), 0.0);
}

TEST(CompanionsJson, AFanExpandsIntoLabelledCompanions) {
  const SceneParse p = with(R"({"vary": {"field": "potential.deformation.C", "values": [0.1, 0.25]},
                                  "companions": [{"geodesic": true}]})");
  ASSERT_TRUE(p.scene) << describe_errors(p.errors);
  ASSERT_EQ(p.scene->companions.size(), 3u);  // the listed one first, then the fan
  EXPECT_EQ(p.scene->companions[1].label, "C = 0.1");
  EXPECT_EQ(std::get<AbcPotential>(p.scene->companions[2].deformation).C, 0.25);
  EXPECT_EQ(companion_label(*p.scene, 0), "body 2");
  // The main body is named as the fan names the others, by its own value (issue 34: the spin fan's
  // legend said "body 1" beside "spin = 0.25"); without a fan it is body 1.
  EXPECT_EQ(main_body_label(*p.scene), "C = 0.3");
  EXPECT_EQ(main_body_label(*with(R"({"vary": {"field": "initial.spin", "values": [1]}})").scene),
            "spin = 0.7");
  EXPECT_EQ(main_body_label(*with(R"({"companions": [{"geodesic": true}]})").scene), "body 1");
}

TEST(CompanionsJson, WritesBackWhatWasGivenAndReadsItToTheSameScene) {
  const json extra =
      json::parse(R"({"companions": [{"geodesic": true, "label": "g"}, {"initial": {"spin": -0.7}}],
                                     "vary": {"field": "body.mass", "values": [1.0]}})");
  const SceneParse p = with(extra);
  ASSERT_TRUE(p.scene) << describe_errors(p.errors);
  const json written = scene_to_json(*p.scene);
  EXPECT_EQ(written["companions"], extra["companions"]);
  EXPECT_EQ(written["vary"], extra["vary"]);
  const SceneParse again = parse_scene(written);
  ASSERT_TRUE(again.scene);
  EXPECT_EQ(scene_to_json(*again.scene), written);
}

TEST(CompanionsJson, AChangeOfTheMainBodyReachesTheCompanionsThatDoNotSetIt) {
  const SceneParse p = with(R"({"companions": [{"initial": {"spin": -0.7}}]})");
  ASSERT_TRUE(p.scene);
  json document = scene_to_json(*p.scene);
  merge_scene_patch(document, json::parse(R"({"body": {"inertia": 0.9}})"));
  const SceneParse changed = parse_scene(document);
  ASSERT_TRUE(changed.scene);
  EXPECT_EQ(changed.scene->companions[0].body.inertia, 0.9);
  EXPECT_NEAR(spin_of(companion_scene(*changed.scene, 0)), -0.7, 1e-14);
}

struct BadCompanion {
  const char* extra;
  std::string field;
  std::string reason_part;
};

class CompanionErrors : public ::testing::TestWithParam<BadCompanion> {};

TEST_P(CompanionErrors, NameThePathValueAndReason) {
  const SceneParse p = with(GetParam().extra);
  EXPECT_FALSE(p.scene);
  ASSERT_FALSE(p.errors.empty());
  bool found = false;
  for (const FieldError& e : p.errors)
    if (e.field == GetParam().field) {
      found = true;
      EXPECT_NE(e.reason.find(GetParam().reason_part), std::string::npos) << e.reason;
      EXPECT_FALSE(e.value.empty());
    }
  EXPECT_TRUE(found) << describe_errors(p.errors);
}

INSTANTIATE_TEST_SUITE_P(
    Table, CompanionErrors,
    ::testing::Values(
        BadCompanion{R"({"companions": [{"wings": 2}]})", "companions[0].wings", "not a known field"},
        BadCompanion{R"({"companions": [{}, {}, {"body": {"mass": -1}}]})", "companions[2].body.mass", "> 0"},
        BadCompanion{R"({"companions": [{"initial": {"spin": 1, "alpha_dot": 2}}]})",
                     "companions[0].initial.spin", "not both"},
        BadCompanion{R"({"companions": [{"body": {"model": "rigid"}}]})",
                     "companions[0].potential.deformation", "rigid"},
        BadCompanion{
            R"({"companions": [{}, {}, {}, {}, {}, {}], "vary": {"field": "initial.spin", "values": [1, 2, 3]}})",
            "companions", "at most 8"},
        BadCompanion{R"({"vary": {"field": "surface.radius", "values": [1]}})", "vary.field",
                     "numeric field"},
        BadCompanion{R"({"vary": {"field": "initial.spin", "values": []}})", "vary.values", "non-empty"},
        BadCompanion{R"({"companions": [{"color": "orange"}]})", "companions[0].color", "#rrggbb"},
        BadCompanion{R"({"companions": [{"geodesic": "yes"}]})", "companions[0].geodesic", "true or false"}));

}  // namespace
}  // namespace spinfold
