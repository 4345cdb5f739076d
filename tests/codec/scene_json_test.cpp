// The scene format: defaults, round trip, presets, and a table of bad scenes.
#include "codec/scene_json.h"

#include <gtest/gtest.h>

#include "codec/presets.h"

namespace spinfold {
namespace {

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
        BadScene{R"({"surface": {"kind": "torus"}})", "surface.kind"},
        BadScene{R"({"surface": {"radius": 0}})", "surface.radius"},
        BadScene{R"({"surface": {"radius": -2}})", "surface.radius"},
        BadScene{R"({"surface": {"radius": "1"}})", "surface.radius"},
        BadScene{R"({"surface": {"radius": 1, "colour": "red"}})", "surface.colour"},
        BadScene{R"({"body": {"mass": 0}})", "body.mass"},
        BadScene{R"({"body": {"inertia": -1}})", "body.inertia"},
        BadScene{R"({"body": {"model": "elastic"}})", "body.model"},
        BadScene{R"({"body": {"mass": true}})", "body.mass"},
        BadScene{R"({"initial": {"lambda": 0}})", "initial.lambda"},
        BadScene{R"({"initial": {"mu": -1}})", "initial.mu"},
        BadScene{R"({"initial": {"r": -0.1}})", "initial.r"},
        BadScene{R"({"initial": {"r": 3.2}})", "initial.r"},  // > πR on the unit sphere
        BadScene{R"({"surface": {"kind": "pseudosphere", "radius": 2}, "initial": {"r": 501}})", "initial.r"},
        BadScene{R"({"initial": {"phi": null}})", "initial.phi"},
        BadScene{R"({"initial": {"spin": 1}})", "initial.spin"},
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
        BadScene{R"({"potential": {"deformation": {"kind": "abc", "C": -1e200}}})", "potential.deformation.C"},
        BadScene{R"({"body": {"inertia": 1e100}, "initial": {"lambda_dot": 1e100}})", "initial.lambda_dot"},
        BadScene{R"({"surface": {"kind": "plane"}, "body": {"mass": 1e100}, "initial": {"r": 1e10, "phi_dot": 1e100}})",
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

TEST(SceneJson, ErrorsNameTheValueAndTheReason) {
  const SceneParse p = parse_scene_text(R"({"body": {"mass": -3}})");
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(p.errors[0].field, "body.mass");
  EXPECT_EQ(p.errors[0].value, "-3");
  EXPECT_EQ(p.errors[0].reason, "must be > 0");
  EXPECT_EQ(describe_errors(p.errors), "body.mass: must be > 0 (got -3)\n");
}

}  // namespace
}  // namespace spinfold
