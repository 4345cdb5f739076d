// Every field of every table of engine/scene_fields.h is read, written and in the schema with the
// table's unit, range, default and description. The tests walk the tables, so they cannot drift.
#include <gtest/gtest.h>

#include <algorithm>

#include "codec/scene_json.h"
#include "codec/scene_schema.h"
#include "engine/integrator.h"
#include "engine/scene_fields.h"
#include "tests/engine/scene_field_paths.h"

namespace spinfold {
namespace {

using nlohmann::json;
using testing_support::for_each_scene_field;
using testing_support::other_number;

std::vector<std::string> split(const std::string& path) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t dot; (dot = path.find('.', start)) != std::string::npos; start = dot + 1)
    parts.push_back(path.substr(start, dot - start));
  parts.push_back(path.substr(start));
  return parts;
}

// A base in which every field may take a test value alone: λ ≠ μ (for the barriers at λ = μ), except
// for a rigid body, which needs μ = λ; on a surface the field belongs to (`surfaces`).
template <typename T>
Scene base_scene(const T& value, unsigned surfaces) {
  Scene s;
  s.surface.kind = testing_support::home_surface(surfaces);
  if constexpr (!std::is_same_v<T, BodyModel>) s.initial.mu = 0.5;
  (void)value;
  return s;
}

// The path of the section that holds `path` ("potential.height" for "potential.height.g").
std::string section_of(const std::string& path) {
  return path.substr(0, path.rfind('.'));
}

// A document holding `value` at `path` (with its section's kind) over base_scene.
template <typename T>
json document(const std::string& path, std::string_view kind, const T& value, const json& text,
              unsigned surfaces) {
  const Scene base = base_scene(value, surfaces);
  json doc = {{"initial", {{"mu", base.initial.mu}}}};
  if (!offers(base.surface, Offer::positive_curvature)) doc["surface"]["kind"] = enum_name(base.surface.kind);
  json* at = &doc;
  for (const std::string& part : split(path)) at = &(*at)[part];
  *at = text;
  if (!kind.empty()) {
    json* section = &doc;
    for (const std::string& part : split(section_of(path))) section = &(*section)[part];
    (*section)["kind"] = kind;
  }
  return doc;
}

// The JSON at `path` of a written scene (null when absent).
json at_path(const json& j, const std::string& path) {
  const json* at = &j;
  for (const std::string& part : split(path)) {
    if (!at->is_object() || !at->contains(part)) return nullptr;
    at = &(*at)[part];
  }
  return *at;
}

// The schema of the field at `path`; within the deformation, that of its kind.
nlohmann::ordered_json schema_property(const std::string& path, std::string_view kind) {
  const nlohmann::ordered_json schema = scene_schema();
  const nlohmann::ordered_json* at = &schema;
  for (const std::string& part : split(path)) {
    if (at->contains("oneOf"))
      for (const auto& alternative : (*at)["oneOf"])
        if (alternative["properties"]["kind"]["const"] == kind) at = &alternative;
    if (!at->contains("properties") || !(*at)["properties"].contains(part)) return nullptr;
    at = &(*at)["properties"][part];
  }
  return *at;
}

// The value the tests put into a field, as JSON and as the field's type.
template <typename Field>
typename Field::Value test_value(const Field& field) {
  using T = typename Field::Value;
  if constexpr (std::is_same_v<T, double> || OptionalNumber<T>) {
    return other_number(field);
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (field.text_rule == TextRule::any) return "some text";
    if (field.text_rule == TextRule::formula) return "x^2 + y^2 - 2";  // a formula in x, y: any form reads it
    for (const std::string_view name : integrator_names())             // one that every scene can use
      if (name != field.fallback() && name != exact_info.name) return std::string(name);
    return "";
  } else {
    return enum_names(std::type_identity<T>{}).back().value;  // not the default (the first)
  }
}
template <typename T>
json as_json(const T& value) {
  if constexpr (Enumerated<T>)
    return std::string(enum_name(value));
  else if constexpr (OptionalNumber<T>)
    return value ? json(*value) : json(nullptr);
  else
    return value;
}

// An optional number comes with its partner (speed with heading): the partner's value in a test.
constexpr double kPartnerValue = 0.25;

// `doc` with the partner of the field at `path`, if it has one, beside it.
template <typename Field>
json with_partner(json doc, const std::string& path, const Field& field) {
  if constexpr (OptionalNumber<typename Field::Value>) {
    if (field.partner.empty()) return doc;
    json* at = &doc;
    const std::vector<std::string> parts = split(path);
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) at = &(*at)[parts[i]];
    (*at)[std::string(field.partner)] = kPartnerValue;
  }
  return doc;
}

TEST(SceneFieldsCodec, EveryFieldIsRead) {
  for_each_scene_field([&](const std::string& path, std::string_view kind, const auto& field, auto place) {
    const auto value = test_value(field);
    const SceneParse parsed =
        parse_scene(with_partner(document(path, kind, value, as_json(value), field.surfaces), path, field));
    ASSERT_TRUE(parsed.errors.empty()) << path << ": " << describe_errors(parsed.errors);
    Scene scene = *parsed.scene;
    EXPECT_EQ(place(scene), value) << path;
    EXPECT_NE(field.fallback(), value) << path << ": the test value must differ from the default";
  });
}

TEST(SceneFieldsCodec, EveryFieldWithAWrongTypeIsNamed) {
  for_each_scene_field([&](const std::string& path, std::string_view kind, const auto& field, auto) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    const SceneParse parsed =
        parse_scene(document(path, kind, field.fallback(), json::array(), field.surfaces));
    ASSERT_FALSE(parsed.errors.empty()) << path;
    EXPECT_EQ(parsed.errors[0].field, path);
    EXPECT_EQ(parsed.errors[0].value, "[]");
    if constexpr (std::is_same_v<T, double> || OptionalNumber<T>) {
      if (path == "body.inertia")  // a number or a 2x2 matrix (physics.md §13)
        EXPECT_EQ(parsed.errors[0].reason,
                  "must be a number (isotropic) or a 2x2 matrix [[J11, J12], [J21, J22]] of numbers");
      else
        EXPECT_EQ(parsed.errors[0].reason, "must be a number");
    } else if constexpr (std::is_same_v<T, std::string>) {
      EXPECT_EQ(parsed.errors[0].reason, "must be a string");
    } else {
      std::string names;
      for (const EnumName<T>& n : enum_names(std::type_identity<T>{}))
        names += (names.empty() ? "" : ", ") + std::string(n.name);
      EXPECT_EQ(parsed.errors[0].reason, "must be one of: " + names);
    }
  });
}

TEST(SceneFieldsCodec, EveryFieldIsWrittenAndReadBack) {
  for_each_scene_field([&](const std::string& path, std::string_view kind, const auto& field, auto place) {
    const auto value = test_value(field);
    Scene scene = base_scene(value, field.surfaces);
    place(scene) = value;
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    if constexpr (OptionalNumber<T>) testing_support::set_partner(scene, field, kPartnerValue);
    const json written = scene_to_json(scene);
    EXPECT_EQ(at_path(written, path), as_json(value)) << path;
    if (!kind.empty()) {
      EXPECT_EQ(at_path(written, section_of(path) + ".kind"), kind) << path;
    }
    const SceneParse again = parse_scene(written);
    ASSERT_TRUE(again.errors.empty()) << path << ": " << describe_errors(again.errors);
    EXPECT_EQ(scene_to_json(*again.scene), written) << path;
    // Defaults are written too (informational text only when set; an optional number is absent).
    Scene defaults;
    defaults.surface.kind = testing_support::home_surface(field.surfaces);
    place(defaults);  // the field present, at its default
    if constexpr (std::is_same_v<T, std::string>)
      if (field.text_rule == TextRule::any) return;
    EXPECT_EQ(at_path(scene_to_json(defaults), path), as_json(field.fallback())) << path;
  });
}

TEST(SceneFieldsCodec, EveryFieldIsInTheSchemaAsInItsTable) {
  const nlohmann::ordered_json schema = scene_schema();
  int described = 0;
  for_each_scene_field([&](const std::string& path, std::string_view kind, const auto& field, auto) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    nlohmann::ordered_json p = schema_property(path, kind);
    ASSERT_FALSE(p.is_null()) << path;
    if (path == "body.inertia") {  // {oneOf: [the number, the 2x2 matrix]} (physics.md §13)
      ASSERT_EQ(p["oneOf"].size(), 2u);
      p = p["oneOf"][0];
    }
    ++described;
    if constexpr (std::is_same_v<T, double> || OptionalNumber<T>) {
      EXPECT_EQ(p["type"], "number") << path;
      if constexpr (OptionalNumber<T>) {
        EXPECT_FALSE(p.contains("default")) << path;  // absent unless given
      } else {
        EXPECT_EQ(p["default"], field.fallback()) << path;
      }
      EXPECT_EQ(p["x-unit"], std::string(field.unit)) << path;
      EXPECT_EQ(p["description"], std::string(field.description)) << path;
      EXPECT_EQ(p["title"], std::string(field.label)) << path;
      const Range& r = field.range;
      const char* min_key = r.min_open ? "exclusiveMinimum" : "minimum";
      const char* max_key = r.max_open ? "exclusiveMaximum" : "maximum";
      EXPECT_EQ(p.contains(min_key), r.has_min()) << path;
      EXPECT_EQ(p.contains(max_key), r.has_max()) << path;
      if (r.has_min()) {
        EXPECT_EQ(p[min_key].get<double>(), r.min) << path;
      }
      if (r.has_max()) {
        EXPECT_EQ(p[max_key].get<double>(), r.max) << path;
      }
      EXPECT_FALSE(p.contains(r.min_open ? "minimum" : "exclusiveMinimum")) << path;
      EXPECT_FALSE(p.contains(r.max_open ? "maximum" : "exclusiveMaximum")) << path;
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (field.text_rule == TextRule::integrator_name) {
        EXPECT_EQ(p["enum"], nlohmann::ordered_json(integrator_names())) << path;
        EXPECT_EQ(p["default"], field.fallback()) << path;
      } else {
        EXPECT_EQ(p["type"], "string") << path;
      }
    } else {
      nlohmann::ordered_json names = nlohmann::ordered_json::array();
      for (const EnumName<T>& n : enum_names(std::type_identity<T>{})) names.push_back(n.name);
      EXPECT_EQ(p["enum"], names) << path;
      EXPECT_EQ(p["default"], std::string(enum_name(field.fallback()))) << path;
    }
  });

  // And the schema describes nothing else: count its leaf properties (the companions and fans,
  // which are patches of these same tables, aside: SchemaCompanionsPatchTheSameBlocks).
  int leaves = 0;
  const auto count = [&](const auto& self, const nlohmann::ordered_json& node) -> void {
    if (node.contains("oneOf"))
      for (const auto& alternative : node["oneOf"]) self(self, alternative);
    if (!node.contains("properties")) return;
    for (const auto& [key, property] : node["properties"].items()) {
      if (&node == &schema && (key == "companions" || key == "vary")) continue;
      if (property.contains("const")) continue;  // a deformation's kind
      // A oneOf of sections (the deformation) is walked; a oneOf of plain values (body.inertia: a
      // number or a matrix) is one leaf.
      const bool sections =
          property.contains("oneOf") && std::any_of(property["oneOf"].begin(), property["oneOf"].end(),
                                                    [](const auto& a) { return a.contains("properties"); });
      if (property.contains("properties") || sections)
        self(self, property);
      else
        ++leaves;
    }
  };
  count(count, schema);
  // The formula surfaces' fields that are not one leaf of the walk (a point, named numbers, a box;
  // engine/scene_paths.h): each in the schema with its shape.
  for (const auto& [path, type] :
       {std::pair{"surface.parameters", "object"}, {"surface.bounds", "array"}, {"initial.X", "array"}}) {
    EXPECT_EQ(schema_property(path, "")["type"], type) << path;
    ++described;
  }
  EXPECT_EQ(leaves, described);
}

TEST(SceneFieldsCodec, SchemaCompanionsPatchTheSameBlocks) {
  const nlohmann::ordered_json schema = scene_schema();
  const nlohmann::ordered_json& companion = schema["properties"]["companions"]["items"]["properties"];
  for (const char* block : {"body", "initial", "integrator"})
    EXPECT_EQ(companion[block], schema["properties"][block]) << block;
  EXPECT_EQ(schema["properties"]["companions"]["maxItems"], kMaxCompanions);
  EXPECT_EQ(schema["properties"]["vary"]["required"], nlohmann::ordered_json({"field", "values"}));
}

}  // namespace
}  // namespace spinfold
