#include "codec/scene_schema.h"

#include <cmath>
#include <type_traits>

#include "engine/formula.h"
#include "engine/formula_examples.h"
#include "engine/formula_surface.h"
#include "engine/scene_fields.h"

namespace spinfold {

using json = nlohmann::ordered_json;

namespace {

// A bound as JSON: a whole number as an integer (0, not 0.0), else the double.
json bound(double v) {
  if (std::trunc(v) == v && std::abs(v) < 1e15) return static_cast<long long>(v);
  return v;
}

json object(json properties, std::vector<std::string> required = {}) {
  json o{{"type", "object"}, {"additionalProperties", false}, {"properties", std::move(properties)}};
  if (!required.empty()) o["required"] = required;
  return o;
}

template <typename S>
json properties_of(json properties = json::object());

// The object of the table of S, with the rules of its optional numbers: one comes with its partner
// (dependentRequired) and never with a field it stands in for (dependentSchemas).
template <typename S>
json section() {
  json o = object(properties_of<S>());
  json required = json::object(), excluded = json::object();
  for_each_field(fields_of(std::type_identity<S>{}), [&](const auto& field) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    if constexpr (OptionalNumber<T>) {
      const std::string name(field.name);
      if (!field.partner.empty()) required[name] = json::array({field.partner});
      json any = json::array();
      for (const std::string_view replaced : field.replaces)
        if (!replaced.empty()) any.push_back({{"required", json::array({replaced})}});
      if (!any.empty()) excluded[name] = {{"not", {{"anyOf", any}}}};
    }
  });
  if (!required.empty()) o["dependentRequired"] = required;
  if (!excluded.empty()) o["dependentSchemas"] = excluded;
  return o;
}

// The schema of one field, from its table entry.
template <typename Field>
json property_of(const Field& field);

// property_of, with "x-surfaces": the surface kinds a field belongs to when not every kind (the
// reader refuses it on the others; the browser shows it only there).
template <typename Field>
json property(const Field& field) {
  json p = property_of(field);
  if (field.surfaces != ~0u) {
    json kinds = json::array();
    for (const EnumName<SurfaceKind>& n : kSurfaceKindNames)
      if (belongs_to(field, n.value)) kinds.push_back(n.name);
    p["x-surfaces"] = kinds;
  }
  return p;
}

// The examples (engine/formula_examples.h) of the surface kind whose formula field this is (F:
// implicit, z: graph): each its name, title, formula, parameters, start point and note.
json formula_examples_json(std::string_view field) {
  json list = json::array();
  for (const FormulaExample& e : formula_examples()) {
    if (formula_key(example_surface(e)) != field) continue;
    json parameters = json::object();
    for (int i = 0; i < e.count; ++i) parameters[std::string(e.parameters[i].first)] = e.parameters[i].second;
    list.push_back({{"name", e.name},
                    {"title", e.title},
                    {"formula", e.formula},
                    {"parameters", parameters},
                    {"X", json::array({e.start[0], e.start[1], e.start[2]})},
                    {"note", e.note}});
  }
  return list;
}

template <typename Field>
json property_of(const Field& field) {
  using T = typename Field::Value;
  if constexpr (std::is_same_v<T, double> || OptionalNumber<T>) {
    json n{{"type", "number"}, {"title", field.label}};
    if constexpr (std::is_same_v<T, double>) n["default"] = field.fallback();  // an optional one has none
    n["description"] = field.description;
    n["x-unit"] = field.unit;
    const Range& r = field.range;
    if (r.has_min()) n[r.min_open ? "exclusiveMinimum" : "minimum"] = bound(r.min);
    if (r.has_max()) n[r.max_open ? "exclusiveMaximum" : "maximum"] = bound(r.max);
    // The span a person usually sets (the page's slider; beyond it a typed value is questioned).
    if (field.usual.has_min() && field.usual.has_max())
      n["x-usual"] = json::array({field.usual.min, field.usual.max});
    return n;
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (field.text_rule == TextRule::integrator_name)
      return {{"enum", integrator_names()}, {"default", field.fallback()}};
    if (field.text_rule == TextRule::formula)
      return {{"type", "string"},
              {"title", field.name == "z" ? "z = f(x, y)" : "F(x, y, z) = 0"},
              {"maxLength", kMaxFormulaLength},
              {"default", field.fallback()},
              {"description", field.description},
              {"x-formula", true},
              {"x-examples", formula_examples_json(field.name)}};
    return {{"type", "string"}};
  } else if constexpr (Point3<T>) {
    const auto d = field.fallback();
    return {{"type", "array"},
            {"items", {{"type", "number"}}},
            {"minItems", 3},
            {"maxItems", 3},
            {"default", json::array({d[0], d[1], d[2]})},
            {"description", field.description},
            {"x-unit", "length"}};
  } else if constexpr (NamedNumbers<T>) {
    return {{"type", "object"},
            {"additionalProperties", {{"type", "number"}}},
            {"propertyNames", {{"pattern", "^[A-Za-z][A-Za-z0-9_]*$"}, {"maxLength", kMaxFormulaNameLength}}},
            {"maxProperties", kMaxFormulaParameters},
            {"description", field.description}};
  } else if constexpr (OptionalBox<T>) {
    const json pair = {{"type", "array"}, {"items", {{"type", "number"}}}, {"minItems", 2}, {"maxItems", 2}};
    return {{"type", "array"}, {"items", pair},      {"minItems", 3},
            {"maxItems", 3},   {"x-unit", "length"}, {"description", field.description}};
  } else if constexpr (Enumerated<T>) {
    json names = json::array(), titles = json::object();
    for (const EnumName<T>& n : enum_names(std::type_identity<T>{})) {
      names.push_back(n.name);
      if (!n.title.empty()) titles[std::string(n.name)] = n.title;
    }
    json e{{"enum", names}, {"default", enum_name(field.fallback())}};
    if (!titles.empty()) e["x-titles"] = titles;  // a menu's words for each name (the UI's select)
    if constexpr (std::is_same_v<T, SurfaceKind>) {
      json varies = json::array();  // the kinds whose K varies from place to place (no one radius)
      for (const EnumName<T>& n : enum_names(std::type_identity<T>{}))
        if (offers(n.value, Offer::implicit_equation)) varies.push_back(n.name);
      e["x-curvature-varies"] = varies;
    }
    return e;
  } else if constexpr (HasFields<T>) {
    return section<T>();
  } else if constexpr (OptionalSection<T>) {
    return section<typename T::value_type>();
  } else {
    static_assert(KindVariant<T>, "a field type the schema does not know");
    json kinds = json::array();
    for_each_kind<T>([&](auto index, auto alternative) {
      using Alternative = typename decltype(alternative)::type;
      const json kind{{"kind", {{"const", kind_names(std::type_identity<T>{})[index]}}}};
      kinds.push_back(object(properties_of<Alternative>(kind), {"kind"}));
    });
    return {{"oneOf", kinds}};
  }
}

// The properties of every field of the table of S, after those already in `properties`.
template <typename S>
json properties_of(json properties) {
  for_each_field(fields_of(std::type_identity<S>{}),
                 [&](const auto& field) { properties[std::string(field.name)] = property(field); });
  return properties;
}

}  // namespace

json scene_schema() {
  json schema{
      {"$schema", "https://json-schema.org/draft/2020-12/schema"},
      {"title", "Spinfold scene"},
      {"description", "An affinely-rigid body on a surface of constant curvature (docs/physics.md)."},
  };
  json top = section<Scene>();
  // body.inertia: a number (isotropic) or a symmetric positive-definite 2x2 matrix (physics.md §13).
  json& inertia = top["properties"]["body"]["properties"][std::string(kInertiaKey)];
  json number = inertia;
  const json row = {{"type", "array"}, {"items", {{"type", "number"}}}, {"minItems", 2}, {"maxItems", 2}};
  inertia = {{"title", number["title"]},
             {"description", number["description"]},
             {"x-unit", number["x-unit"]},
             {"default", number["default"]},
             {"oneOf",
              {number,
               {{"type", "array"},
                {"items", row},
                {"minItems", 2},
                {"maxItems", 2},
                {"description", "J^{AB} in the body frame: symmetric, positive definite"}}}}};
  for (auto it = top.begin(); it != top.end(); ++it) schema[it.key()] = it.value();
  // Companions (codec/scene_json.h): merge patches over the main body's blocks.
  const json& main = schema["properties"];
  json deformation = main["potential"]["properties"]["deformation"];
  deformation["oneOf"].push_back({{"type", "null"}});
  json companion = object(
      {{"label", {{"type", "string"}, {"description", "legend text (default: body N)"}}},
       {"color",
        {{"description", "\"#rrggbb\" or [r, g, b] in [0, 1] (default: the renderer's palette)"},
         {"oneOf",
          {{{"type", "string"}, {"pattern", "^#[0-9a-fA-F]{6}$"}},
           {{"type", "array"},
            {"items", {{"type", "number"}, {"minimum", 0}, {"maximum", 1}}},
            {"minItems", 3},
            {"maxItems", 3}}}}}},
       {"geodesic",
        {{"type", "boolean"}, {"description", "the point particle from the same start (rigid, zero spin)"}}},
       {"body", main["body"]},
       {"initial", main["initial"]},
       {"integrator", main["integrator"]},
       {"potential", object({{"deformation", deformation}})}});
  schema["properties"]["companions"] = {
      {"type", "array"},
      {"maxItems", kMaxCompanions},
      {"description",
       "more bodies on the same surface: JSON merge patches over the main body's body, "
       "potential.deformation, initial and integrator blocks"},
      {"items", companion}};
  schema["properties"]["vary"] = object(
      {{"field",
        {{"type", "string"},
         {"description", "a numeric field of body, initial or potential.deformation, e.g. initial.spin"}}},
       {"values",
        {{"type", "array"}, {"items", {{"type", "number"}}}, {"minItems", 1}, {"maxItems", kMaxCompanions}}}},
      {"field", "values"});
  schema["properties"]["vary"]["description"] = "a fan: one companion per value of the field";
  return schema;
}

}  // namespace spinfold
