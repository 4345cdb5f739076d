// The JSON Schema says what parse_scene accepts: every property it names is accepted, every field
// the codec writes is in it, and its defaults are the codec's.
#include "codec/scene_schema.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "codec/scene_json.h"

namespace spinfold {
namespace {

using nlohmann::json;

TEST(SceneSchema, EveryWrittenFieldIsDescribedWithItsDefault) {
  const json schema = scene_schema();
  const json written = scene_to_json(Scene{});
  for (const auto& [section, value] : written.items()) {
    ASSERT_TRUE(schema["properties"].contains(section)) << section;
    if (!value.is_object() || section == "potential") continue;
    for (const auto& [key, v] : value.items()) {
      const json& property = schema["properties"][section]["properties"][key];
      ASSERT_FALSE(property.is_null()) << section << "." << key;
      EXPECT_EQ(property["default"], v) << section << "." << key;
    }
  }
}

TEST(SceneSchema, EveryDescribedPropertyIsAccepted) {
  const json schema = scene_schema();
  for (const auto& [section, property] : schema["properties"].items()) {
    if (!property.contains("properties")) continue;
    for (const auto& [key, sub] : property["properties"].items()) {
      if (!sub.contains("default")) continue;
      json scene = {{section, {{key, sub["default"]}}}};
      const SceneParse parsed = parse_scene(scene);
      for (const FieldError& e : parsed.errors)
        EXPECT_EQ(e.reason.find("not a known field"), std::string::npos) << section << "." << key;
    }
  }
  // Both deformation kinds and their fields.
  for (const json& kind : schema["properties"]["potential"]["properties"]["deformation"]["oneOf"]) {
    json deformation = {{"kind", kind["properties"]["kind"]["const"]}};
    for (const auto& [key, sub] : kind["properties"].items())
      if (sub.contains("default")) deformation[key] = sub["default"];
    const SceneParse parsed =
        parse_scene(json{{"potential", {{"deformation", deformation}}}, {"initial", {{"mu", 0.5}}}});
    EXPECT_TRUE(parsed.errors.empty()) << describe_errors(parsed.errors);
  }
}

// The UI's Surface menu and its "is K one number" test come from surface.kind's schema entry.
// Every kind has a menu title; the kinds said to have a K that varies are exactly those that have
// no radius (read off the radius field's own "x-surfaces", not off chart_free).
TEST(SceneSchema, SurfaceKindsCarryTheirMenuWordsAndWhetherKVaries) {
  const json schema = scene_schema();
  const json& kind = schema["properties"]["surface"]["properties"]["kind"];
  const json& radius_kinds = schema["properties"]["surface"]["properties"]["radius"]["x-surfaces"];
  ASSERT_TRUE(radius_kinds.is_array());
  ASSERT_GE(kind["enum"].size(), 7u);
  for (const json& name : kind["enum"]) {
    EXPECT_FALSE(kind["x-titles"].value(name.get<std::string>(), "").empty()) << name;
    const bool varies = std::ranges::count(kind["x-curvature-varies"], name) == 1;
    const bool has_radius = std::ranges::count(radius_kinds, name) == 1;
    EXPECT_NE(varies, has_radius) << name;
  }
}

TEST(SceneSchema, InertiaIsANumberOrAMatrix) {
  const json schema = scene_schema();
  const json& inertia = schema["properties"]["body"]["properties"]["inertia"];
  ASSERT_EQ(inertia["oneOf"].size(), 2u);
  EXPECT_EQ(inertia["oneOf"][0]["type"], "number");
  EXPECT_EQ(inertia["oneOf"][1]["type"], "array");
  EXPECT_EQ(inertia["oneOf"][1]["items"]["maxItems"], 2);
  EXPECT_EQ(inertia["default"], Body{}.inertia);
  EXPECT_EQ(schema["properties"]["companions"]["items"]["properties"]["body"]["properties"]["inertia"],
            inertia);
}

}  // namespace
}  // namespace spinfold
