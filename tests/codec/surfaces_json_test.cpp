// The scene format on the surfaces whose curvature varies: their kinds and parameters, initial.u,
// potential.height and friction are read and written back; fields of the other family are refused
// naming the field and the kinds it belongs to; a sphere scene is written as before (no new keys).
#include <gtest/gtest.h>

#include "codec/scene_json.h"

namespace spinfold {
namespace {

const char* kTorus = R"({
  "surface": {"kind": "torus", "tube_radius": 0.6, "center_radius": 2.0},
  "body": {"mass": 2, "inertia": [[0.6, 0.1], [0.1, 0.4]]},
  "potential": {"height": {"kind": "gravity", "g": 0.5},
                "deformation": {"kind": "abc", "A": 0.01, "B": 0.02, "C": 0.2}},
  "friction": {"translational": 0.1, "internal": 0.05},
  "initial": {"u": 0.7, "phi": 0.3, "lambda": 1.2, "mu": 0.9, "u_dot": 0.4, "phi_dot": -0.2, "spin": 0.3},
  "integrator": {"name": "dop853"}})";

// The first error's field and reason of a scene text ("" when it is accepted).
FieldError first_error(const std::string& text) {
  const SceneParse p = parse_scene_text(text);
  return p.errors.empty() ? FieldError{} : p.errors.front();
}

TEST(SurfacesJson, TorusSceneReadsAndWritesBack) {
  const SceneParse p = parse_scene_text(kTorus);
  ASSERT_TRUE(p.errors.empty()) << describe_errors(p.errors);
  const Scene& s = *p.scene;
  EXPECT_EQ(s.surface.kind, SurfaceKind::torus);
  EXPECT_EQ(s.surface.tube_radius, 0.6);
  EXPECT_EQ(s.surface.center_radius, 2.0);
  ASSERT_TRUE(std::holds_alternative<GravityPotential>(s.potential.height));
  EXPECT_EQ(std::get<GravityPotential>(s.potential.height).g, 0.5);
  ASSERT_TRUE(s.friction.has_value());
  EXPECT_EQ(s.friction->internal, 0.05);
  EXPECT_EQ(s.initial.u, 0.7);
  EXPECT_EQ(s.initial.u_dot, 0.4);
  const nlohmann::json written = scene_to_json(s);
  // Only the torus's own fields: no radius, r or r_dot; the spin as given instead of alpha_dot.
  EXPECT_FALSE(written["surface"].contains("radius"));
  EXPECT_FALSE(written["surface"].contains("polar_radius"));
  EXPECT_FALSE(written["initial"].contains("r"));
  EXPECT_FALSE(written["initial"].contains("r_dot"));
  EXPECT_FALSE(written["initial"].contains("alpha_dot"));
  EXPECT_EQ(written["potential"]["height"]["kind"], "gravity");
  const SceneParse again = parse_scene(written);
  ASSERT_TRUE(again.errors.empty()) << describe_errors(again.errors);
  EXPECT_EQ(scene_to_json(*again.scene), written);
}

TEST(SurfacesJson, EveryKindAndHeightPotentialReads) {
  for (const char* surface :
       {R"({"kind": "spheroid", "equatorial_radius": 1.5, "polar_radius": 0.8})",
        R"({"kind": "bump", "height": -0.5, "width": 0.7})", R"({"kind": "catenoid", "neck_radius": 0.9})"}) {
    const std::string text =
        std::string(R"({"surface": )") + surface +
        R"(, "potential": {"height": {"kind": "spring", "k": 0.7}}, "initial": {"u": 0.4}})";
    const SceneParse p = parse_scene_text(text);
    EXPECT_TRUE(p.errors.empty()) << surface << ": " << describe_errors(p.errors);
  }
}

TEST(SurfacesJson, FieldsOfTheOtherFamilyAreRefusedNamingThem) {
  FieldError e = first_error(R"({"surface": {"kind": "torus"}, "initial": {"r": 1}})");
  EXPECT_EQ(e.field, "initial.r");
  EXPECT_NE(e.reason.find("not defined on the torus"), std::string::npos) << e.reason;
  EXPECT_NE(e.reason.find("initial.u"), std::string::npos) << e.reason;
  e = first_error(R"({"surface": {"kind": "torus", "radius": 2}})");
  EXPECT_EQ(e.field, "surface.radius");
  EXPECT_NE(e.reason.find("sphere, pseudosphere or plane"), std::string::npos) << e.reason;
  e = first_error(R"({"initial": {"u": 0.3}})");
  EXPECT_EQ(e.field, "initial.u");
  EXPECT_NE(e.reason.find("initial.r"), std::string::npos) << e.reason;
  e = first_error(R"({"surface": {"kind": "sphere", "tube_radius": 0.3}})");
  EXPECT_EQ(e.field, "surface.tube_radius");
  EXPECT_NE(e.reason.find("only on the torus"), std::string::npos) << e.reason;
  e = first_error(R"({"surface": {"kind": "spheroid", "neck_radius": 1}})");
  EXPECT_EQ(e.field, "surface.neck_radius");
  // The height potential: not on the plane (z = 0) nor the pseudosphere; friction acts everywhere.
  e = first_error(R"({"surface": {"kind": "plane"}, "potential": {"height": {"kind": "gravity", "g": 1}}})");
  EXPECT_EQ(e.field, "potential.height");
  EXPECT_NE(e.reason.find("only on the sphere"), std::string::npos) << e.reason;
  e = first_error(
      R"({"surface": {"kind": "pseudosphere"}, "potential": {"height": {"kind": "spring", "k": 1}}})");
  EXPECT_EQ(e.field, "potential.height");
  for (const char* kind : {"sphere", "pseudosphere", "plane"})
    EXPECT_TRUE(parse_scene_text(std::string(R"({"surface": {"kind": ")") + kind +
                                 R"("}, "initial": {"r": 0.5}, "friction": {"translational": 1}})")
                    .errors.empty())
        << kind;
  e = first_error(R"({"surface": {"kind": "bump"}, "potential": {"radial": {"gamma": 1}}})");
  EXPECT_EQ(e.field, "potential.radial");
  e = first_error(R"({"surface": {"kind": "bump"}, "potential": {"height": {"kind": "magnetic"}}})");
  EXPECT_EQ(e.field, "potential.height.kind");
  EXPECT_NE(e.reason.find("gravity, spring"), std::string::npos) << e.reason;
  e = first_error(R"({"surface": {"kind": "torus", "tube_radius": 1, "center_radius": 0.5}})");
  EXPECT_EQ(e.field, "surface.center_radius");
  e = first_error(R"({"surface": {"kind": "torus"}, "friction": {"internal": -1}})");
  EXPECT_EQ(e.field, "friction.internal");
  // A companion's initial block likewise.
  e = first_error(R"({"surface": {"kind": "torus"}, "companions": [{"initial": {"r_dot": 1}}]})");
  EXPECT_EQ(e.field, "companions[0].initial.r_dot");
}

// A sphere scene is written as it was before the new surfaces: none of their keys appear.
TEST(SurfacesJson, ASphereSceneGainsNoKeys) {
  const nlohmann::json j = scene_to_json(*parse_scene_text("{}").scene);
  for (const char* key : {"tube_radius", "center_radius", "equatorial_radius", "polar_radius", "height",
                          "width", "neck_radius"})
    EXPECT_FALSE(j["surface"].contains(key)) << key;
  EXPECT_FALSE(j["initial"].contains("u"));
  EXPECT_FALSE(j["initial"].contains("u_dot"));
  EXPECT_FALSE(j.contains("friction"));
  EXPECT_FALSE(j["potential"].contains("height"));
  EXPECT_EQ(j["surface"].dump(), R"({"kind":"sphere","radius":1.0})");
}

// Speed and heading on the torus: V = v(cos h E₁ + sin h E₂) with E₁ = X_u/f, so u̇ = v cos h/a and
// φ̇ = v sin h/ρ (ρ = c + a cos u).
TEST(SurfacesJson, SpeedAndHeadingUseTheProfileFrame) {
  const SceneParse p = parse_scene_text(
      R"({"surface": {"kind": "torus", "tube_radius": 0.5, "center_radius": 2},
          "initial": {"u": 1.0, "speed": 2, "heading": 0.6}})");
  ASSERT_TRUE(p.errors.empty()) << describe_errors(p.errors);
  EXPECT_NEAR(p.scene->initial.u_dot, 2 * std::cos(0.6) / 0.5, 1e-15);
  EXPECT_NEAR(p.scene->initial.phi_dot, 2 * std::sin(0.6) / (2 + 0.5 * std::cos(1.0)), 1e-15);
  // At the spheroid's pole only heading 0 or π converts.
  const FieldError e =
      first_error(R"({"surface": {"kind": "spheroid"}, "initial": {"u": 0, "speed": 1, "heading": 1}})");
  EXPECT_EQ(e.field, "initial.heading");
  EXPECT_NE(e.reason.find("axis"), std::string::npos) << e.reason;
}

// A wrong surface is named alone: its parameters make every rate conversion fail too (a catenoid
// of neck 0 gives an infinite u_dot for any speed), and those follow-on errors once came first.
TEST(SurfacesJson, AWrongSurfaceIsNamedAloneNotTheRatesItSpoils) {
  const SceneParse p = parse_scene_text(R"({"surface": {"kind": "catenoid", "neck_radius": 0},
    "initial": {"u": 0, "speed": 1, "heading": 1.5, "spin": 0.5}})");
  ASSERT_EQ(p.errors.size(), 1u) << describe_errors(p.errors);
  EXPECT_EQ(p.errors.front().field, "surface.neck_radius");
  const SceneParse bump = parse_scene_text(R"({"surface": {"kind": "bump", "height": 1, "width": 0},
    "initial": {"u": 0.5, "spin": 2}})");
  ASSERT_EQ(bump.errors.size(), 1u) << describe_errors(bump.errors);
  EXPECT_EQ(bump.errors.front().field, "surface.width");
}

// The missing heading's reason names the frame the heading is measured in on this surface.
TEST(SurfacesJson, AMissingHeadingNamesTheSurfacesOwnE1) {
  const FieldError torus =
      first_error(R"({"surface": {"kind": "torus"}, "initial": {"u": 0.3, "speed": 1}})");
  EXPECT_EQ(torus.field, "initial.heading");
  EXPECT_NE(torus.reason.find("E1 = X_u/f"), std::string::npos) << torus.reason;
  const FieldError sphere = first_error(R"({"initial": {"r": 0.3, "speed": 1}})");
  EXPECT_EQ(sphere.field, "initial.heading");
  EXPECT_NE(sphere.reason.find("E1 = d/dr"), std::string::npos) << sphere.reason;
}

// A merge patch of surface.curvature on a spheroid ({"curvature": K, "kind": null, "radius": null})
// leaves K beside the spheroid's fields: the refusal names curvature, the field the patch gave (it
// named equatorial_radius and polar_radius, which the patch did not touch).
TEST(SurfacesJson, CurvatureBesideAnotherKindsFieldsIsRefusedNamingCurvature) {
  for (const char* surface : {R"({"curvature": 1, "equatorial_radius": 1, "polar_radius": 0.6})",
                              R"({"curvature": -0.5, "tube_radius": 0.6, "center_radius": 2})",
                              R"({"curvature": 0, "neck_radius": 1})"}) {
    const SceneParse p = parse_scene_text(std::string(R"({"surface": )") + surface + "}");
    ASSERT_EQ(p.errors.size(), 1u) << surface << ": " << describe_errors(p.errors);
    EXPECT_EQ(p.errors[0].field, "surface.curvature") << surface;
    EXPECT_NE(p.errors[0].reason.find("set surface.kind first"), std::string::npos) << p.errors[0].reason;
  }
  // The other kind's fields elsewhere (initial.u, integrator.stepping) are the same error: one.
  const SceneParse p = parse_scene_text(
      R"({"surface": {"curvature": 1, "neck_radius": 1}, "initial": {"u": 0.5}, "integrator": {"stepping": "auto"}})");
  ASSERT_EQ(p.errors.size(), 1u) << describe_errors(p.errors);
  EXPECT_EQ(p.errors[0].field, "surface.curvature");
  // Without K, each field of the other kind is named, as before.
  EXPECT_EQ(parse_scene_text(R"({"surface": {"kind": "sphere", "neck_radius": 1}, "initial": {"u": 0.5}})")
                .errors.size(),
            2u);
}

}  // namespace
}  // namespace spinfold
