// Validation of a scene (engine/validation.h), called directly: every bad field named with its
// value, all of them at once, and the reasons' wording of ranges and bounds. (The scene format's
// table of bad scenes, tests/codec/scene_json_test.cpp, reaches the same function through JSON.)
#include "engine/validation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace spinfold {
namespace {

const FieldError* error_at(const std::vector<FieldError>& errors, const std::string& field) {
  const auto it =
      std::find_if(errors.begin(), errors.end(), [&](const FieldError& e) { return e.field == field; });
  return it == errors.end() ? nullptr : &*it;
}

TEST(Validation, DefaultSceneIsValid) {
  EXPECT_TRUE(validate_scene(Scene{}).empty());
}

// Every bad field is reported in one pass, each with its path, its value as text and a reason.
TEST(Validation, EveryBadFieldIsNamedWithItsValue) {
  Scene s;
  s.body.mass = -1.0;
  s.surface.radius = 0.0;
  s.integrator.dt = std::numeric_limits<double>::quiet_NaN();
  const std::vector<FieldError> errors = validate_scene(s);
  for (const char* field : {"body.mass", "surface.radius", "integrator.dt"}) {
    const FieldError* e = error_at(errors, field);
    ASSERT_NE(e, nullptr) << field;
    EXPECT_FALSE(e->reason.empty()) << field;
  }
  EXPECT_EQ(error_at(errors, "body.mass")->value, "-1");
  EXPECT_EQ(error_at(errors, "surface.radius")->value, "0");
}

// Friction on a constant-curvature surface runs under the stepping methods and `auto`; the splitting
// methods (exact Hamiltonian flows), the closed form and the incompressible body (RATTLE only) refuse
// it with the reason.
TEST(Validation, FrictionIsRefusedOnlyWhereTheMethodComposesHamiltonianFlows) {
  for (const SurfaceKind kind : {SurfaceKind::sphere, SurfaceKind::pseudosphere, SurfaceKind::plane}) {
    Scene s;
    s.surface = Surface(kind, 1.0);
    s.initial.r = 0.5;
    s.friction = Friction{0.1, 0.05};
    for (const char* name : {"auto", "dop853", "rk4", "gauss4", "gauss6", "implicit_midpoint"}) {
      s.integrator.name = name;
      EXPECT_TRUE(validate_scene(s).empty()) << name;
    }
    for (const char* name : {"split4", "split6", "exact"}) {
      s.integrator.name = name;
      const std::vector<FieldError> errors = validate_scene(s);
      const FieldError* e = error_at(errors, "integrator.name");
      ASSERT_NE(e, nullptr) << name;
      EXPECT_NE(e->reason.find("friction"), std::string::npos) << e->reason;
    }
    s.integrator.name = "auto";
    s.body.model = BodyModel::incompressible;
    const std::vector<FieldError> errors = validate_scene(s);
    const FieldError* e = error_at(errors, "friction");
    ASSERT_NE(e, nullptr);
    EXPECT_NE(e->reason.find("split4/split6"), std::string::npos) << e->reason;
    s.friction = Friction{};  // zero coefficients: no friction
    EXPECT_EQ(error_at(validate_scene(s), "friction"), nullptr);
  }
}

// The sphere's height potential runs under every method but the closed form.
TEST(Validation, TheSpheresHeightPotentialRunsUnderEveryMethodButTheClosedForm) {
  Scene s;
  s.initial.r = 0.5;
  s.potential.height = GravityPotential{1.0};
  for (const char* name : {"auto", "dop853", "split4", "split6", "gauss6"}) {
    s.integrator.name = name;
    EXPECT_TRUE(validate_scene(s).empty()) << name;
  }
  s.integrator.name = "exact";
  const std::vector<FieldError> errors = validate_scene(s);
  const FieldError* e = error_at(errors, "integrator.name");
  ASSERT_NE(e, nullptr);
  EXPECT_NE(e->reason.find("height"), std::string::npos) << e->reason;
}

// Beyond the supported magnitudes is refused even where the sign is right.
TEST(Validation, MagnitudesBeyondTheSupportedRangeAreRefused) {
  Scene s;
  s.body.mass = 1e101;
  EXPECT_NE(error_at(validate_scene(s), "body.mass"), nullptr);
  s.body.mass = kMaxSceneMagnitude;
  EXPECT_EQ(error_at(validate_scene(s), "body.mass"), nullptr);
}

// Powers of ten as 1eN from |N| ≥ 2, everything else in its shortest form.
TEST(Validation, BoundText) {
  EXPECT_EQ(bound_text(1e-2), "1e-2");
  EXPECT_EQ(bound_text(1e100), "1e100");
  EXPECT_EQ(bound_text(1e-15), "1e-15");
  EXPECT_EQ(bound_text(10.0), "10");
  EXPECT_EQ(bound_text(0.0), "0");
  EXPECT_EQ(bound_text(0.5), "0.5");
  EXPECT_EQ(bound_text(2e-5), "2e-05");
}

TEST(Validation, RangeReasonWordsEachKindOfRange) {
  EXPECT_EQ(range_reason(kPositive), "must be > 0");
  EXPECT_EQ(range_reason(Range{.min = 1e-15, .max = 1e-2}), "must be between 1e-15 and 1e-2");
  EXPECT_EQ(range_reason(Range{.min = 0.0, .max = 1.0, .max_open = true}), "must be in [0, 1)");
  EXPECT_EQ(range_reason(Range{.min = 0.0}), "must be >= 0");
  EXPECT_EQ(range_reason(Range{.max = 4.0, .max_open = true}), "must be < 4");
  EXPECT_EQ(range_reason(Range{.max = 4.0}), "must be <= 4");
  EXPECT_EQ(range_reason(kPositive, "a length"), "must be > 0 (a length)");
  EXPECT_EQ(range_reason(kAnyNumber, "ignored"), "");
}

}  // namespace
}  // namespace spinfold
