// The scene format: defaults, round trip, presets, and a table of bad scenes.
#include "codec/scene_json.h"

#include <gtest/gtest.h>

#include <tuple>

#include "codec/presets.h"
#include "codec/scene_schema.h"
#include "engine/initial_rates.h"

namespace spinfold {
namespace {

// One wording of a change that continues the run, for the server, Python and the page (which showed
// "continuing" twice and t = 5.329274332000002).
TEST(SceneJson, AContinuedChangeSaysItsTimeOnceToSixDigits) {
  EXPECT_EQ(continued_reason(5.329274332000002),
            "new parameters from t = 5.32927 on, continuing from the current state");
  EXPECT_EQ(continued_reason(0.0), "new parameters from t = 0, continuing from the start");
}

TEST(SceneJson, EmptyObjectGetsTheDocumentedDefaults) {
  const SceneParse p = parse_scene_text("{}");
  ASSERT_TRUE(p.errors.empty()) << describe_errors(p.errors);
  const Scene& s = *p.scene;
  EXPECT_EQ(s.surface.kind, SurfaceKind::sphere);
  EXPECT_EQ(s.surface.radius, 1.0);
  EXPECT_EQ(s.body.model, BodyModel::affine);
  EXPECT_FALSE(s.potential.radial.has_value());
  EXPECT_TRUE(std::holds_alternative<std::monostate>(s.potential.deformation));
  EXPECT_EQ(s.integrator.name, "auto");
  EXPECT_EQ(s.on_degenerate, OnDegenerate::report);
}

TEST(SceneJson, RoundTripKeepsEveryField) {
  const char* text = R"({
    "surface": {"kind": "pseudosphere", "radius": 2.5},
    "body": {"mass": 2, "inertia": 0.3, "model": "affine"},
    "potential": {"radial": {"gamma": 0.2},
                  "deformation": {"kind": "polar", "ghat": 0.1, "gtilde": -1, "form": "literal"}},
    "initial": {"r": 1.5, "phi": 0.1, "alpha": 0.2, "beta": 0.3, "lambda": 1.2, "mu": 0.7,
                "r_dot": 0.4, "phi_dot": 0.5, "alpha_dot": 0.6, "beta_dot": 0.7,
                "lambda_dot": 0.8, "mu_dot": 0.9},
    "integrator": {"name": "rk4", "dt": 0.002, "tolerance": 1e-8},
    "on_degenerate": "stop"})";
  const SceneParse first = parse_scene_text(text);
  ASSERT_TRUE(first.errors.empty()) << describe_errors(first.errors);
  const nlohmann::json written = scene_to_json(*first.scene);
  const SceneParse second = parse_scene(written);
  ASSERT_TRUE(second.errors.empty()) << describe_errors(second.errors);
  EXPECT_EQ(scene_to_json(*second.scene), written);
  EXPECT_EQ(written["potential"]["deformation"]["form"], "literal");
  EXPECT_EQ(written["initial"]["mu_dot"], 0.9);
  EXPECT_EQ(written["on_degenerate"], "stop");
}

TEST(SceneJson, AFormulaSurfaceReadsWritesAndReadsBackTheSame) {
  const std::string text = R"j({"surface": {"kind": "implicit", "F": "x^2/a^2 + y^2/b^2 + z^2/c^2 - 1",
      "parameters": {"a": 2, "b": 1.5, "c": 1}, "bounds": [[-2.5, 2.5], [-2, 2], [-1.5, 1.5]]},
      "initial": {"X": [1.0, 0.8, 0.5], "speed": 0.5, "heading": 0.3, "spin": 0.2},
      "integrator": {"projection": "off"}})j";
  const SceneParse parsed = parse_scene_text(text);
  ASSERT_TRUE(parsed.errors.empty()) << describe_errors(parsed.errors);
  const Scene& scene = *parsed.scene;
  EXPECT_EQ(scene.surface.kind, SurfaceKind::implicit);
  EXPECT_EQ(scene.surface.parameters.at("b"), 1.5);
  ASSERT_TRUE(scene.surface.bounds);
  EXPECT_EQ((*scene.surface.bounds)[1][0], -2.0);
  EXPECT_EQ(scene.initial.X[1], 0.8);
  EXPECT_EQ(scene.integrator.projection, Projection::off);
  const nlohmann::json written = scene_to_json(scene);
  EXPECT_EQ(written["surface"]["F"], "x^2/a^2 + y^2/b^2 + z^2/c^2 - 1");
  EXPECT_FALSE(written["initial"].contains("phi"));  // no chart on a formula surface
  EXPECT_FALSE(written["surface"].contains("radius"));
  const SceneParse again = parse_scene(written);
  ASSERT_TRUE(again.errors.empty()) << describe_errors(again.errors);
  EXPECT_EQ(scene_to_json(*again.scene), written);
}

// A geodesic companion on every kind of surface starts where the main body does, at its speed and
// heading, with no spin: on a formula surface with X (no chart's r, u, φ).
TEST(SceneJson, AGeodesicCompanionReadsOnEveryKindOfSurface) {
  const char* surfaces[] = {R"j({"kind": "sphere"})j", R"j({"kind": "torus"})j",
                            R"j({"kind": "implicit", "F": "x^2/4 + y^2 + z^2 - 1"})j",
                            R"j({"kind": "graph", "z": "x^3 - 3*x*y^2"})j"};
  for (const char* surface : surfaces) {
    const bool formula = std::string(surface).find("\"F\"") != std::string::npos ||
                         std::string(surface).find("\"z\"") != std::string::npos;
    const std::string start = formula ? R"j("X": [0.4, 0.2, 0.1])j" : R"j("phi": 0.2)j";
    const std::string text = std::string(R"j({"surface": )j") + surface + R"j(, "initial": {)j" + start +
                             R"j(, "speed": 0.5, "heading": 0.4, "spin": 0.8},
        "companions": [{"geodesic": true, "label": "geodesic"}]})j";
    const SceneParse parsed = parse_scene_text(text);
    ASSERT_TRUE(parsed.errors.empty()) << surface << ": " << describe_errors(parsed.errors);
    ASSERT_EQ(parsed.scene->companions.size(), 1u);
    const Companion& c = parsed.scene->companions[0];
    EXPECT_TRUE(c.geodesic);
    EXPECT_EQ(c.initial.spin.value_or(-1.0), 0.0) << surface;
    if (formula) {
      EXPECT_EQ(c.initial.X, parsed.scene->initial.X) << surface;
      EXPECT_EQ(c.initial.speed, parsed.scene->initial.speed) << surface;
      EXPECT_EQ(c.initial.heading, parsed.scene->initial.heading) << surface;
    }
  }
}

TEST(SceneJson, AFormulaSurfacesRefusalsNameTheirFields) {
  const auto first_error = [](const std::string& text) {
    const SceneParse parsed = parse_scene_text(text);
    return parsed.errors.empty() ? FieldError{} : parsed.errors.front();
  };
  FieldError e = first_error(R"j({"surface": {"kind": "graph", "z": "x^2 + floor(y)"}})j");
  EXPECT_EQ(e.field, "surface.z");
  EXPECT_NE(e.reason.find("at position 6"), std::string::npos) << e.reason;
  e = first_error(R"j({"surface": {"kind": "graph", "z": "a*x^2", "parameters": {"a": "2"}}})j");
  EXPECT_EQ(e.field, "surface.parameters.a");
  e = first_error(R"j({"surface": {"kind": "graph", "z": "x"}, "initial": {"X": [1, 2]}})j");
  EXPECT_EQ(e.field, "initial.X");
  e = first_error(R"j({"surface": {"kind": "torus"}, "initial": {"X": [1, 2, 3]}})j");
  EXPECT_EQ(e.field, "initial.X");
  EXPECT_NE(e.reason.find("only on the implicit or graph"), std::string::npos) << e.reason;
  e = first_error(R"j({"surface": {"kind": "implicit", "F": "x^2 + y^2 + z^2 - 1"}, "initial": {"u": 1}})j");
  EXPECT_EQ(e.field, "initial.u");
}

TEST(SceneJson, TheSchemaDescribesTheFormulaSurfaces) {
  const auto schema = scene_schema();
  const auto& surface = schema["properties"]["surface"]["properties"];
  EXPECT_TRUE(surface["F"]["x-formula"].get<bool>());
  EXPECT_EQ(surface["F"]["x-surfaces"], nlohmann::json::array({"implicit"}));
  EXPECT_EQ(surface["parameters"]["type"], "object");
  EXPECT_EQ(surface["bounds"]["minItems"], 3);
  const auto& X = schema["properties"]["initial"]["properties"]["X"];
  EXPECT_EQ(X["maxItems"], 3);
  EXPECT_EQ(X["x-surfaces"], nlohmann::json::array({"implicit", "graph"}));
  // The menu's examples, by kind: each composes a scene the reader takes as it is.
  std::size_t count = 0;
  for (const auto& [key, kind] : {std::pair{"F", "implicit"}, std::pair{"z", "graph"}}) {
    const auto& examples = surface[key]["x-examples"];
    ASSERT_TRUE(examples.is_array()) << key;
    EXPECT_GE(examples.size(), 2u) << key;
    for (const auto& e : examples) {
      const nlohmann::json scene = {
          {"surface", {{"kind", kind}, {key, e["formula"]}, {"parameters", e["parameters"]}}},
          {"initial", {{"X", e["X"]}, {"speed", 0.5}, {"heading", 0.3}, {"spin", 1.0}}}};
      const SceneParse parsed = parse_scene(scene);
      EXPECT_TRUE(parsed.errors.empty()) << e["name"] << ": " << describe_errors(parsed.errors);
      EXPECT_FALSE(e["title"].get<std::string>().empty());
      ++count;
    }
  }
  EXPECT_EQ(count, 5u);
}

TEST(SceneJson, EveryPresetIsValidAndDescribed) {
  ASSERT_FALSE(preset_sources().empty());
  ASSERT_NE(find_preset(kDefaultPreset), nullptr);
  for (const PresetSource& p : preset_sources()) {
    const SceneParse parsed = parse_scene_text(p.json);
    EXPECT_TRUE(parsed.errors.empty()) << p.name << ": " << describe_errors(parsed.errors);
    if (parsed.scene) {
      EXPECT_EQ(parsed.scene->name, p.name);
      EXPECT_FALSE(parsed.scene->description.empty()) << p.name;
    }
  }
}

struct BadScene {
  const char* json;
  const char* field;  // the field the first error must name
};

void PrintTo(const BadScene& b, std::ostream* os) {
  *os << b.json;
}

class BadScenes : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadScenes, RejectedNamingTheField) {
  const SceneParse p = parse_scene_text(GetParam().json);
  ASSERT_FALSE(p.scene.has_value());
  ASSERT_FALSE(p.errors.empty());
  bool named = false;
  for (const FieldError& e : p.errors) {
    named = named || e.field == GetParam().field;
    EXPECT_FALSE(e.reason.empty());
  }
  EXPECT_TRUE(named) << "errors: " << describe_errors(p.errors);
}

INSTANTIATE_TEST_SUITE_P(
    Table, BadScenes,
    ::testing::Values(
        BadScene{R"({"surface": {"kind": "klein_bottle"}})", "surface.kind"},
        BadScene{R"({"surface": {"radius": 0}})", "surface.radius"},
        BadScene{R"({"surface": {"radius": -2}})", "surface.radius"},
        BadScene{R"({"surface": {"radius": "1"}})", "surface.radius"},
        BadScene{R"({"surface": {"radius": 1, "colour": "red"}})", "surface.colour"},
        BadScene{R"({"body": {"mass": 0}})", "body.mass"},
        BadScene{R"({"body": {"inertia": -1}})", "body.inertia"},
        BadScene{R"({"body": {"inertia": [[0.3, 0.1], [0.2, 0.2]]}})", "body.inertia"},  // not symmetric
        BadScene{R"({"body": {"inertia": [[0.1, 0.3], [0.3, 0.1]]}})", "body.inertia"},  // indefinite
        BadScene{R"({"body": {"inertia": [[0.1, 0], [0, -0.1]]}})", "body.inertia"},
        BadScene{R"({"body": {"inertia": [[0.1, 0, 0], [0, 0.1]]}})", "body.inertia"},  // not 2x2
        BadScene{R"({"body": {"inertia": [[0.1, "0"], [0, 0.1]]}})", "body.inertia"},
        BadScene{R"({"body": {"inertia": [0.1, 0.1]}})", "body.inertia"},
        BadScene{R"({"body": {"model": "elastic"}})", "body.model"},
        BadScene{R"({"body": {"mass": true}})", "body.mass"},
        BadScene{R"({"initial": {"lambda": 0}})", "initial.lambda"},
        BadScene{R"({"initial": {"mu": -1}})", "initial.mu"},
        BadScene{R"({"initial": {"r": -0.1}})", "initial.r"},
        BadScene{R"({"initial": {"r": 3.2}})", "initial.r"},  // > πR on the unit sphere
        BadScene{R"({"surface": {"kind": "pseudosphere", "radius": 2}, "initial": {"r": 501}})", "initial.r"},
        BadScene{R"({"initial": {"phi": null}})", "initial.phi"},
        BadScene{R"({"initial": {"omega": 1}})", "initial.omega"},
        // The physical alternatives to the rates (initial.spin, speed, heading).
        BadScene{R"({"initial": {"spin": 1, "alpha_dot": 0.5}})", "initial.spin"},
        BadScene{R"({"initial": {"speed": 1}})", "initial.heading"},
        BadScene{R"({"initial": {"heading": 1}})", "initial.speed"},
        BadScene{R"({"initial": {"speed": 1, "heading": 0, "phi_dot": 1}})", "initial.speed"},
        BadScene{R"({"initial": {"speed": -1, "heading": 0}})", "initial.speed"},
        BadScene{R"({"initial": {"spin": "1"}})", "initial.spin"},
        BadScene{R"({"initial": {"r": 0, "speed": 1, "heading": 1}})", "initial.heading"},
        BadScene{
            R"({"body": {"inertia": 1e-100}, "initial": {"lambda": 1e-100, "mu": 1e-100, "spin": 1e100}})",
            "initial.spin"},
        BadScene{R"({"body": {"inertia": 1e-100}, "initial": {"spin": 1e100}})",
                 "initial.spin"},  // overflows
        BadScene{R"({"body": {"model": "rigid"}, "initial": {"lambda": 1, "mu": 2}})", "initial.mu"},
        BadScene{R"({"body": {"model": "rigid"}, "initial": {"lambda_dot": 0.1}})", "initial.lambda_dot"},
        BadScene{R"({"body": {"model": "rigid"}, "potential": {"deformation": {"kind": "abc", "C": 1}}})",
                 "potential.deformation"},
        BadScene{R"({"potential": {"radial": {"gamma": -1}}})", "potential.radial.gamma"},
        BadScene{R"({"potential": {"radial": {"gamma": 0.1}}, "initial": {"r": 0}})", "initial.r"},
        BadScene{R"({"potential": {"radial": {"g": 0.1}}})", "potential.radial.g"},
        BadScene{R"({"potential": {"deformation": {"kind": "harmonic"}}})", "potential.deformation.kind"},
        BadScene{R"({"potential": {"deformation": {"A": 1}}})", "potential.deformation.kind"},
        BadScene{R"({"potential": {"deformation": {"kind": "abc", "A": -1, "initial": 1}}})",
                 "potential.deformation.A"},
        BadScene{
            R"({"potential": {"deformation": {"kind": "abc", "A": 0.1}}, "initial": {"lambda": 1, "mu": 1}})",
            "initial.mu"},
        BadScene{R"({"potential": {"deformation": {"kind": "polar", "ghat": 0.1, "form": "fancy"}}})",
                 "potential.deformation.form"},
        BadScene{R"({"potential": {"deformation": {"kind": "polar", "ghat": 0.1}}})", "initial.mu"},
        BadScene{R"({"integrator": {"name": "euler"}})", "integrator.name"},
        BadScene{R"({"integrator": {"dt": 0}})", "integrator.dt"},
        BadScene{R"({"integrator": {"tolerance": 1}})", "integrator.tolerance"},
        BadScene{R"({"integrator": {"tolerance": 1e-20}})", "integrator.tolerance"},
        BadScene{R"({"on_degenerate": "explode"})", "on_degenerate"},
        // Beyond the supported magnitudes, and finite inputs whose start overflows.
        BadScene{R"({"initial": {"alpha_dot": 1e101}})", "initial.alpha_dot"},
        BadScene{R"({"body": {"mass": 1e-101}})", "body.mass"},
        BadScene{R"({"surface": {"radius": 1e300}})", "surface.radius"},
        BadScene{R"({"potential": {"deformation": {"kind": "abc", "C": -1e200}}})",
                 "potential.deformation.C"},
        BadScene{R"({"body": {"inertia": 1e100}, "initial": {"lambda_dot": 1e100}})", "initial.lambda_dot"},
        BadScene{
            R"({"surface": {"kind": "plane"}, "body": {"mass": 1e100}, "initial": {"r": 1e10, "phi_dot": 1e100}})",
            "initial.phi_dot"},
        BadScene{R"({"gravity": 9.81})", "gravity"}, BadScene{R"({"": 1})", R"("")"},
        BadScene{R"({"body": {"mass.x": 1}})", R"(body."mass.x")"}, BadScene{R"([1, 2, 3])", ""},
        BadScene{R"({"surface": )", ""}, BadScene{R"({"initial": {"r": 1e400}})", ""}));

TEST(SceneJson, DeepNestingIsRejectedBeforeItIsBuilt) {
  std::string deep(10000, '[');
  deep += std::string(10000, ']');
  const SceneParse p = parse_scene_text(deep);
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_NE(p.errors[0].reason.find("nested"), std::string::npos);
}

// body.inertia as a matrix (physics.md §13): read, written back as a matrix, the reason names the rule.
TEST(SceneJson, InertiaMatrixRoundTripsAndIsValidated) {
  const SceneParse p = parse_scene_text(R"({"body": {"mass": 2, "inertia": [[0.3, 0.05], [0.05, 0.1]]}})");
  ASSERT_TRUE(p.errors.empty()) << describe_errors(p.errors);
  ASSERT_TRUE(p.scene->body.inertia_matrix.has_value());
  EXPECT_EQ(p.scene->body.inertia_matrix->J12, 0.05);
  EXPECT_EQ(p.scene->body.inertia_matrix->J22, 0.1);
  const nlohmann::json written = scene_to_json(*p.scene);
  EXPECT_EQ(written["body"]["inertia"], nlohmann::json::parse("[[0.3, 0.05], [0.05, 0.1]]"));
  const SceneParse again = parse_scene(written);
  ASSERT_TRUE(again.errors.empty()) << describe_errors(again.errors);
  EXPECT_EQ(scene_to_json(*again.scene), written);
  // A number replaces the matrix.
  const SceneParse number = parse_scene_text(R"({"body": {"inertia": 0.2}})");
  ASSERT_TRUE(number.errors.empty());
  EXPECT_FALSE(number.scene->body.inertia_matrix.has_value());
  EXPECT_EQ(scene_to_json(*number.scene)["body"]["inertia"], 0.2);

  const SceneParse bad = parse_scene_text(R"({"body": {"inertia": [[0.1, 0.3], [0.3, 0.1]]}})");
  ASSERT_EQ(bad.errors.size(), 1u) << describe_errors(bad.errors);
  EXPECT_EQ(bad.errors[0].field, "body.inertia");
  EXPECT_EQ(bad.errors[0].value, "[[0.1, 0.3], [0.3, 0.1]]");
  EXPECT_NE(bad.errors[0].reason.find("positive definite"), std::string::npos);
  // A companion's merge patch may give the matrix too.
  const SceneParse fan = parse_scene_text(
      R"({"body": {"inertia": 0.2}, "companions": [{"body": {"inertia": [[0.3, 0], [0, 0.1]]}}]})");
  ASSERT_TRUE(fan.errors.empty()) << describe_errors(fan.errors);
  ASSERT_EQ(fan.scene->companions.size(), 1u);
  EXPECT_TRUE(fan.scene->companions[0].body.inertia_matrix.has_value());
  EXPECT_FALSE(fan.scene->body.inertia_matrix.has_value());
}

TEST(SceneJson, ErrorsNameTheValueAndTheReason) {
  const SceneParse p = parse_scene_text(R"({"body": {"mass": -3}})");
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(p.errors[0].field, "body.mass");
  EXPECT_EQ(p.errors[0].value, "-3");
  EXPECT_EQ(p.errors[0].reason, "must be > 0");
  EXPECT_EQ(describe_errors(p.errors), "body.mass: must be > 0 (got -3)\n");
}

// ---- spin, speed and heading: the physical alternatives to the rates ----------------------------

// The errors naming `field`.
std::vector<FieldError> naming(const SceneParse& p, const std::string& field) {
  std::vector<FieldError> named;
  for (const FieldError& e : p.errors)
    if (e.field == field) named.push_back(e);
  return named;
}

TEST(SceneJson, SpinSpeedAndHeadingFillTheRates) {
  const SceneParse p = parse_scene_text(R"({
    "surface": {"kind": "sphere", "radius": 1},
    "body": {"mass": 2, "inertia": 0.5},
    "initial": {"r": 1, "phi": 0.5, "alpha": 0.25, "beta": -0.5, "lambda": 1.5, "mu": 0.5,
                "speed": 0.5, "heading": 0.7, "spin": 0.3, "beta_dot": 0.1}})");
  ASSERT_TRUE(p.errors.empty()) << describe_errors(p.errors);
  const Scene& s = *p.scene;
  EXPECT_NEAR(s.initial.r_dot, 0.5 * std::cos(0.7), 1e-15);
  EXPECT_NEAR(s.initial.phi_dot, 0.5 * std::sin(0.7) / std::sin(1.0), 1e-15);
  EXPECT_NEAR(spin_of(s), 0.3, 1e-15);
  EXPECT_NEAR(speed_of(s), 0.5, 1e-15);
  EXPECT_NEAR(heading_of(s), 0.7, 1e-15);
  EXPECT_EQ(s.initial.spin, 0.3);
  EXPECT_EQ(s.initial.speed, 0.5);
  EXPECT_EQ(s.initial.heading, 0.7);
}

// W1 of physics.md §10 given by its spin: the rate alpha_dot = 0.4 comes back.
TEST(SceneJson, WorkedExampleW1GivenBySpin) {
  const SceneParse p = parse_scene_text(R"({
    "surface": {"kind": "sphere", "radius": 1},
    "body": {"mass": 2, "inertia": 0.5},
    "initial": {"r": 1, "phi": 0.5, "alpha": 0.25, "beta": -0.5, "lambda": 1.5, "mu": 0.5,
                "r_dot": 0.2, "phi_dot": -0.3, "spin": 0.22238663529944763, "beta_dot": 0.1,
                "lambda_dot": 0.05, "mu_dot": -0.02}})");
  ASSERT_TRUE(p.errors.empty()) << describe_errors(p.errors);
  EXPECT_NEAR(p.scene->initial.alpha_dot, 0.4, 1e-14);
}

TEST(SceneJson, SpinSpeedAndHeadingAreWrittenBackInsteadOfTheRates) {
  const SceneParse first = parse_scene_text(R"({
    "surface": {"kind": "pseudosphere", "radius": 2},
    "body": {"model": "rigid", "inertia": 0.3},
    "initial": {"r": 1.5, "lambda": 1.2, "mu": 1.2, "spin": -0.4, "speed": 0.8, "heading": 2.5}})");
  ASSERT_TRUE(first.errors.empty()) << describe_errors(first.errors);
  const nlohmann::json written = scene_to_json(*first.scene);
  const nlohmann::json& initial = written["initial"];
  EXPECT_EQ(initial["spin"], -0.4);
  EXPECT_EQ(initial["speed"], 0.8);
  EXPECT_EQ(initial["heading"], 2.5);
  for (const char* rate : {"alpha_dot", "r_dot", "phi_dot"}) EXPECT_FALSE(initial.contains(rate)) << rate;
  EXPECT_TRUE(initial.contains("beta_dot"));  // not replaced

  const SceneParse second = parse_scene(written);
  ASSERT_TRUE(second.errors.empty()) << describe_errors(second.errors);
  EXPECT_EQ(scene_to_json(*second.scene), written);
  const InitialState& a = first.scene->initial;
  const InitialState& b = second.scene->initial;
  EXPECT_EQ(a.alpha_dot, b.alpha_dot);
  EXPECT_EQ(a.r_dot, b.r_dot);
  EXPECT_EQ(a.phi_dot, b.phi_dot);
  EXPECT_EQ(a.spin, b.spin);
  EXPECT_EQ(a.speed, b.speed);
  EXPECT_EQ(a.heading, b.heading);

  // Without them the rates are written, as before.
  const SceneParse rates = parse_scene_text(R"({"initial": {"alpha_dot": 0.5}})");
  ASSERT_TRUE(rates.errors.empty());
  const nlohmann::json plain = scene_to_json(*rates.scene)["initial"];
  EXPECT_EQ(plain["alpha_dot"], 0.5);
  EXPECT_FALSE(plain.contains("spin"));
  EXPECT_FALSE(plain.contains("speed"));
  EXPECT_FALSE(plain.contains("heading"));
}

struct BothForms {
  const char* initial;  // the initial block
  const char* field;    // the field named
  const char* value;    // its value as written
  const char* reason;
};

void PrintTo(const BothForms& b, std::ostream* os) {
  *os << b.initial;
}

class PhysicalFieldErrors : public ::testing::TestWithParam<BothForms> {};

TEST_P(PhysicalFieldErrors, NameTheFieldTheValueAndTheReason) {
  const BothForms& c = GetParam();
  const SceneParse p = parse_scene_text(std::string(R"({"initial": )") + c.initial + "}");
  EXPECT_FALSE(p.scene.has_value());
  const std::vector<FieldError> named = naming(p, c.field);
  ASSERT_FALSE(named.empty()) << describe_errors(p.errors);
  bool found = false;
  for (const FieldError& e : named)
    found = found || (e.value == c.value && e.reason.find(c.reason) != std::string::npos);
  EXPECT_TRUE(found) << describe_errors(p.errors);
}

INSTANTIATE_TEST_SUITE_P(
    Table, PhysicalFieldErrors,
    ::testing::Values(
        BothForms{R"({"spin": 1, "alpha_dot": 0.5})", "initial.spin", "1",
                  "give either spin or alpha_dot, not both"},
        BothForms{R"({"speed": 1})", "initial.heading", "null", "is missing: speed comes with heading"},
        BothForms{R"({"heading": 0.5})", "initial.speed", "null", "is missing: heading comes with speed"},
        BothForms{R"({"speed": 1, "heading": 0.5, "r_dot": 0.1})", "initial.heading", "0.5",
                  "give either heading or r_dot, not both"},
        BothForms{R"({"speed": 1, "heading": 0.5, "r_dot": 0.1})", "initial.speed", "1",
                  "give either speed or r_dot, not both"},
        BothForms{R"({"speed": 1, "heading": 0.5, "phi_dot": 0.1})", "initial.speed", "1",
                  "give either speed or phi_dot, not both"},
        BothForms{R"({"r": 0, "speed": 0.5, "heading": 1})", "initial.heading", "1",
                  "cannot be converted at a pole"},
        BothForms{R"({"r": 3.141592653589793, "speed": 0.5, "heading": -2})", "initial.heading", "-2",
                  "cannot be converted at a pole"},
        BothForms{R"({"speed": -0.5, "heading": 1})", "initial.speed", "-0.5", "must be >= 0"}));

// At a pole a heading along E₁ (0 or π) is a radial start; with speed 0 any heading is.
TEST(SceneJson, HeadingAlongE1IsAcceptedAtAPole) {
  for (const char* initial :
       {R"({"r": 0, "speed": 0.5, "heading": 0})", R"({"r": 0, "speed": 0.5, "heading": 3.141592653589793})",
        R"({"r": 0, "speed": 0, "heading": 1})"}) {
    const SceneParse p = parse_scene_text(std::string(R"({"initial": )") + initial + "}");
    ASSERT_TRUE(p.errors.empty()) << initial << ": " << describe_errors(p.errors);
    EXPECT_EQ(p.scene->initial.phi_dot, 0.0) << initial;
  }
}

// The "both given" rule is per block: a merge patch can swap one form for the other by removing it.
TEST(SceneJson, APatchSwapsSpinForAlphaDot) {
  const SceneParse p = parse_scene_text(R"({"initial": {"spin": 0.2}})");
  ASSERT_TRUE(p.errors.empty());
  nlohmann::json document = scene_to_json(*p.scene);
  nlohmann::json refused = document;
  refused.merge_patch(nlohmann::json::parse(R"({"initial": {"alpha_dot": 1}})"));
  EXPECT_FALSE(parse_scene(refused).scene.has_value());
  document.merge_patch(nlohmann::json::parse(R"({"initial": {"alpha_dot": 1, "spin": null}})"));
  const SceneParse swapped = parse_scene(document);
  ASSERT_TRUE(swapped.errors.empty()) << describe_errors(swapped.errors);
  EXPECT_EQ(swapped.scene->initial.alpha_dot, 1.0);
  EXPECT_FALSE(swapped.scene->initial.spin.has_value());
}

// merge_scene_patch applies the tables' stand-in relation (Field::replaces) in every block: the
// patch's form wins, in initial (spin, speed/heading) and in surface (curvature ↔ kind, radius).
TEST(SceneJson, MergeScenePatchDropsTheFormsAValueStandsInFor) {
  const nlohmann::json base = scene_to_json(*parse_scene_text(R"({"initial": {"spin": 0.2}})").scene);
  for (const auto& [patch, gone, kept] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {R"({"initial": {"alpha_dot": 1}})", "/initial/spin", "/initial/alpha_dot"},
           {R"({"initial": {"speed": 1, "heading": 0}})", "/initial/r_dot", "/initial/speed"},
           {R"({"surface": {"curvature": -1}})", "/surface/kind", "/surface/curvature"},
       }) {
    nlohmann::json document = base;
    merge_scene_patch(document, nlohmann::json::parse(patch));
    EXPECT_FALSE(document.contains(nlohmann::json::json_pointer(gone))) << patch;
    EXPECT_TRUE(document.contains(nlohmann::json::json_pointer(kept))) << patch;
    const SceneParse parsed = parse_scene(document);
    EXPECT_TRUE(parsed.errors.empty()) << patch << ": " << describe_errors(parsed.errors);
  }
  nlohmann::json dialled = scene_to_json(*parse_scene_text(R"({"surface": {"curvature": 1}})").scene);
  merge_scene_patch(dialled, nlohmann::json::parse(R"({"surface": {"kind": "pseudosphere"}})"));
  EXPECT_FALSE(dialled["surface"].contains("curvature"));
}

TEST(SceneJson, SchemaDescribesTheRulesOfSpinSpeedAndHeading) {
  const nlohmann::ordered_json initial = scene_schema()["properties"]["initial"];
  for (const char* key : {"spin", "speed", "heading"}) {
    EXPECT_EQ(initial["properties"][key]["type"], "number") << key;
    EXPECT_FALSE(initial["properties"][key].contains("default")) << key;
  }
  EXPECT_EQ(initial["properties"]["speed"]["minimum"], 0);
  EXPECT_EQ(initial["dependentRequired"]["speed"], nlohmann::ordered_json::array({"heading"}));
  EXPECT_EQ(initial["dependentRequired"]["heading"], nlohmann::ordered_json::array({"speed"}));
  EXPECT_EQ(initial["dependentSchemas"]["spin"]["not"]["anyOf"][0]["required"][0], "alpha_dot");
  EXPECT_EQ(initial["dependentSchemas"]["speed"]["not"]["anyOf"].size(), 3u);  // r_dot, u_dot, phi_dot
}

}  // namespace
}  // namespace spinfold
