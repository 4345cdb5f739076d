// The JSON Schema says what parse_scene accepts: every property it names is accepted, every field
// the codec writes is in it, and its defaults are the codec's.
#include "codec/scene_schema.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "codec/presets.h"
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

// A number's usual span (x-usual) at its path, in the branch of a oneOf whose kind it names.
struct Usual {
  std::string path;
  std::string kind;  // "" outside a oneOf branch; else the branch's kind, at `path`'s parent
  double lo, hi;
  json spec;
};

void collect_usual(const json& spec, const std::string& path, const std::string& kind,
                   std::vector<Usual>& out) {
  if (!spec.is_object()) return;
  if (spec.contains("x-usual"))
    out.push_back({path, kind, spec["x-usual"][0].get<double>(), spec["x-usual"][1].get<double>(), spec});
  if (spec.contains("properties"))
    for (const auto& [key, child] : spec["properties"].items())
      collect_usual(child, path.empty() ? key : path + "." + key, kind, out);
  if (spec.contains("oneOf"))
    for (const json& branch : spec["oneOf"])
      if (branch.contains("properties") && branch["properties"].contains("kind") &&
          branch["properties"]["kind"].contains("const"))
        collect_usual(branch, path, branch["properties"]["kind"]["const"].get<std::string>(), out);
}

const json* at_path(const json& doc, const std::string& path) {
  const json* at = &doc;
  std::size_t from = 0;
  while (from <= path.size()) {
    const std::size_t dot = std::min(path.find('.', from), path.size());
    const std::string key = path.substr(from, dot - from);
    if (!at->is_object() || !at->contains(key)) return nullptr;
    at = &(*at)[key];
    from = dot + 1;
  }
  return at;
}

// Every number a person sets by hand (the page's sliders) has the span it usually takes, inside
// what is allowed; and every preset's values lie in it: its slider shows it, and a teacher retyping
// a preset's value is not questioned.
TEST(SceneSchema, UsualSpansLieInTheAllowedRangeAndHoldEveryPreset) {
  std::vector<Usual> usual;
  collect_usual(scene_schema(), "", "", usual);
  EXPECT_GE(usual.size(), 17u);
  for (const Usual& u : usual) {
    EXPECT_LT(u.lo, u.hi) << u.path;
    const auto bound = [&](const char* key, double fallback) { return u.spec.value(key, fallback); };
    constexpr double inf = std::numeric_limits<double>::infinity();
    EXPECT_GE(u.lo, bound("minimum", -inf)) << u.path;
    EXPECT_GT(u.lo, bound("exclusiveMinimum", -inf)) << u.path;
    EXPECT_LE(u.hi, bound("maximum", inf)) << u.path;
    EXPECT_LT(u.hi, bound("exclusiveMaximum", inf)) << u.path;
  }
  int checked = 0;
  for (const PresetSource& preset : preset_sources()) {
    const json scene = scene_to_json(*parse_scene_text(preset.json).scene);
    for (const Usual& u : usual) {
      const json* v = at_path(scene, u.path);
      if (!v || !v->is_number()) continue;
      if (!u.kind.empty()) {
        const json* kind = at_path(scene, u.path.substr(0, u.path.rfind('.')) + ".kind");
        if (!kind || *kind != u.kind) continue;
      }
      ++checked;
      EXPECT_GE(v->get<double>(), u.lo) << preset.name << " " << u.path;
      EXPECT_LE(v->get<double>(), u.hi) << preset.name << " " << u.path;
    }
  }
  EXPECT_GT(checked, 100);
}

}  // namespace
}  // namespace spinfold
