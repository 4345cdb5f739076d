// The field tables and the validator: every field of every table is validated against its own
// range, the tables are consistent, and numbers in messages print in their shortest form.
#include "engine/scene_fields.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <string_view>
#include <utility>

#include "engine/integrator.h"
#include "engine/validation.h"
#include "tests/engine/scene_field_paths.h"

namespace spinfold {
namespace {

using testing_support::for_each_scene_field;
using testing_support::other_number;

// A valid scene in which every field can take other_number alone: λ ≠ μ, so that the barriers at
// λ = μ (A, ĝ) may be switched on; on a surface the field belongs to (`surfaces`).
Scene base_scene(unsigned surfaces = surface_bit(SurfaceKind::sphere)) {
  Scene s;
  s.surface.kind = testing_support::home_surface(surfaces);
  s.initial.mu = 0.5;
  return s;
}

std::vector<FieldError> errors_for(const std::vector<FieldError>& errors, const std::string& field) {
  std::vector<FieldError> named;
  for (const FieldError& e : errors)
    if (e.field == field) named.push_back(e);
  return named;
}

bool has_reason(const std::vector<FieldError>& errors, const std::string& field, const std::string& reason) {
  for (const FieldError& e : errors_for(errors, field))
    if (e.reason == reason) return true;
  return false;
}

TEST(SceneFields, EveryTableNamesEachFieldOnceAndDescribesIt) {
  std::set<std::string> paths;
  int count = 0;
  for_each_scene_field([&](const std::string& path, std::string_view kind, const auto& field, auto) {
    EXPECT_TRUE(paths.insert(std::string(kind) + ":" + path).second) << path;
    EXPECT_FALSE(field.description.empty()) << path;
    ++count;
  });
  // surface 2 + 1 optional (curvature) + 7 of the surfaces of revolution + 2 formulas (F, z), body 3,
  // radial 1, abc 3, polar 3, gravity 1, spring 1, friction 2, initial 12 + 2 (u, u_dot) + 3 optional
  // (spin, speed, heading), integrator 5 (name, dt, tolerance, stepping, projection), name,
  // description, on_degenerate. (surface.parameters, surface.bounds and initial.X are not one leaf:
  // scene_paths_test.) A field added to a struct of engine/scene.h goes into its table and this count.
  EXPECT_EQ(count, 51);
}

// ---- Units: the table's units obey the formulas of physics.md, checked by dimension.

// Exponents of mass, length and time.
using Dim = std::array<int, 3>;
constexpr Dim kEnergy{1, 2, -2};

Dim times(Dim a, Dim b, int power = 1) {
  for (int i = 0; i < 3; ++i) a[i] += power * b[i];
  return a;
}

// "mass·length²/time" → {1, 2, -1}. The vocabulary: mass, length, time, energy, rad and 1 (pure
// numbers), with ² and ³, multiplied by · and divided by one /.
Dim parse_unit(std::string_view unit) {
  Dim d{0, 0, 0};
  int sign = 1;
  while (!unit.empty()) {
    if (unit.starts_with("/")) {
      sign = -1;
      unit.remove_prefix(1);
    } else if (unit.starts_with("·")) {
      unit.remove_prefix(std::string_view("·").size());
    }
    Dim base{0, 0, 0};
    bool known = false;
    for (const auto& [name, dim] : {std::pair<std::string_view, Dim>{"mass", {1, 0, 0}},
                                    {"length", {0, 1, 0}},
                                    {"time", {0, 0, 1}},
                                    {"energy", kEnergy},
                                    {"rad", {0, 0, 0}},
                                    {"1", {0, 0, 0}}})
      if (unit.starts_with(name)) {
        base = dim;
        unit.remove_prefix(name.size());
        known = true;
        break;
      }
    if (!known) ADD_FAILURE() << "unknown unit at: " << unit;
    if (!known) return d;
    int power = 1;
    if (unit.starts_with("²")) power = 2, unit.remove_prefix(std::string_view("²").size());
    if (unit.starts_with("³")) power = 3, unit.remove_prefix(std::string_view("³").size());
    d = times(d, base, sign * power);
  }
  return d;
}

// The unit of a number field of a table, by key.
template <typename Table>
Dim unit_of(const Table& table, std::string_view key) {
  std::string_view unit;
  for_each_field(table, [&](const auto& field) {
    if (field.name == key) unit = field.unit;
  });
  EXPECT_FALSE(unit.empty()) << key;
  return parse_unit(unit);
}

TEST(SceneFields, EveryNumberHasALabelAndAUnitOfTheVocabulary) {
  for_each_scene_field([&](const std::string& path, std::string_view, const auto& field, auto) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    if constexpr (std::is_same_v<T, double> || OptionalNumber<T>) {
      EXPECT_FALSE(field.label.empty()) << path;
      if (path == "initial.u" || path == "initial.u_dot") {  // "rad (torus, spheroid); length (bump, …)"
        const std::string_view unit = field.unit;
        const std::size_t split = unit.find("; ");
        ASSERT_NE(split, std::string_view::npos) << path;
        const std::string_view first = unit.substr(0, split), second = unit.substr(split + 2);
        parse_unit(first.substr(0, first.find(" (")));
        parse_unit(second.substr(0, second.find(" (")));
      } else if (path != "potential.radial.gamma") {
        parse_unit(field.unit);  // fails on a word outside it
      }
    }
  });
}

TEST(SceneFields, UnitsAgreeWithThePhysics) {
  const auto& initial = kInitialStateFields;
  const Dim lambda = unit_of(initial, "lambda"), time = unit_of(kIntegratorSettingsFields, "dt");
  const Dim length = unit_of(kSurfaceFields, "radius"), mass = unit_of(kBodyFields, "mass");
  const Dim J = unit_of(kBodyFields, "inertia");
  EXPECT_EQ(length, (Dim{0, 1, 0}));
  EXPECT_EQ(time, (Dim{0, 0, 1}));
  EXPECT_EQ(mass, (Dim{1, 0, 0}));
  // §1: K = ±1/R².
  EXPECT_EQ(unit_of(kSurfaceFields, "curvature"), times({0, 0, 0}, length, -2));
  // Rates are their coordinate per time.
  for (const auto& [rate, coordinate] :
       {std::pair{"r_dot", "r"}, std::pair{"phi_dot", "phi"}, std::pair{"alpha_dot", "alpha"},
        std::pair{"beta_dot", "beta"}, std::pair{"lambda_dot", "lambda"}, std::pair{"mu_dot", "mu"}})
    EXPECT_EQ(unit_of(initial, rate), times(unit_of(initial, coordinate), time, -1)) << rate;
  EXPECT_EQ(unit_of(initial, "lambda"), unit_of(initial, "mu"));
  // §3: T = m/2 ṙ² + J/2 ‖L̇‖²: both energies.
  EXPECT_EQ(times(mass, unit_of(initial, "speed"), 2), kEnergy);
  EXPECT_EQ(times(J, unit_of(initial, "lambda_dot"), 2), kEnergy);
  // §3: s = J (λ² + μ²) χ, χ = α̇ + C φ̇.
  EXPECT_EQ(unit_of(initial, "spin"), times(times(J, lambda, 2), unit_of(initial, "alpha_dot")));
  // §4: the spin–curvature force K s j(v) is a force, m Dv/Dt.
  EXPECT_EQ(
      times(times(unit_of(kSurfaceFields, "curvature"), unit_of(initial, "spin")), unit_of(initial, "speed")),
      times(mass, times(length, time, -2)));
  // §5: V = A/x² + B/y² + C(x² + y²) with x, y of the unit of λ; V = g̃/ς + W(ε)/ς², ς² = x² + y².
  EXPECT_EQ(times(unit_of(kAbcPotentialFields, "A"), lambda, -2), kEnergy);
  EXPECT_EQ(times(unit_of(kAbcPotentialFields, "B"), lambda, -2), kEnergy);
  EXPECT_EQ(times(unit_of(kAbcPotentialFields, "C"), lambda, 2), kEnergy);
  EXPECT_EQ(times(unit_of(kPolarPotentialFields, "gtilde"), lambda, -1), kEnergy);
  EXPECT_EQ(times(unit_of(kPolarPotentialFields, "ghat"), lambda, -2), kEnergy);
  // §5: V_r = g/sin²(r/R) on S² (sin² a pure number); g/(R² sinh²(r/R)) on H², g/r² on the plane.
  const std::string_view gamma = std::get<0>(kRadialPotentialFields).unit;
  const std::size_t split = gamma.find("; ");
  ASSERT_NE(split, std::string_view::npos) << gamma;
  const std::string_view sphere = gamma.substr(0, split), others = gamma.substr(split + 2);
  EXPECT_EQ(sphere.substr(sphere.find(" (")), " (sphere)");
  EXPECT_EQ(others.substr(others.find(" (")), " (pseudosphere, plane)");
  EXPECT_EQ(parse_unit(sphere.substr(0, sphere.find(" ("))), kEnergy);
  EXPECT_EQ(times(parse_unit(others.substr(0, others.find(" ("))), length, -2), kEnergy);
}

TEST(SceneFields, EveryDefaultIsAllowedByItsOwnRange) {
  for_each_scene_field([&](const std::string& path, std::string_view, const auto& field, auto) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    if constexpr (std::is_same_v<T, double>) {
      EXPECT_FALSE(field.unit.empty()) << path;
      EXPECT_TRUE(field.range.contains(field.fallback())) << path;
      EXPECT_TRUE(field.range.contains(other_number(field))) << path;
      EXPECT_NE(other_number(field), field.fallback()) << path;
    } else if constexpr (OptionalNumber<T>) {
      EXPECT_FALSE(field.unit.empty()) << path;
      EXPECT_FALSE(field.fallback().has_value()) << path;  // absent unless given
      EXPECT_TRUE(field.range.contains(other_number(field))) << path;
      EXPECT_FALSE(field.replaces[0].empty()) << path << ": stands in for no field";
    } else if constexpr (Enumerated<T>) {
      EXPECT_FALSE(enum_name(field.fallback()).empty()) << path;
    }
  });
  EXPECT_TRUE(validate_scene(Scene{}).empty());
  EXPECT_TRUE(validate_scene(base_scene()).empty());
}

template <typename Enum>
void expect_names_round_trip() {
  std::set<std::string_view> names;
  for (const EnumName<Enum>& n : enum_names(std::type_identity<Enum>{})) {
    EXPECT_TRUE(names.insert(n.name).second) << n.name;
    EXPECT_EQ(enum_name(n.value), n.name);
    EXPECT_EQ(enum_value<Enum>(n.name), n.value);
    EXPECT_FALSE(n.description.empty()) << n.name;
  }
  EXPECT_FALSE(enum_value<Enum>("no such name").has_value());
}

TEST(SceneFields, EveryEnumeratedNameRoundTrips) {
  expect_names_round_trip<SurfaceKind>();
  expect_names_round_trip<BodyModel>();
  expect_names_round_trip<PolarForm>();
  expect_names_round_trip<OnDegenerate>();
  EXPECT_EQ(integrator_names().front(), "auto");
}

TEST(SceneFields, EveryFieldIsValidatedAgainstItsTable) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for_each_scene_field([&](const std::string& path, std::string_view, const auto& field, auto place) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    const auto with = [&](const T& value) {
      Scene s = base_scene(field.surfaces);
      place(s) = value;
      return validate_scene(s);
    };
    if constexpr (std::is_same_v<T, double> || OptionalNumber<T>) {
      EXPECT_TRUE(errors_for(with(other_number(field)), path).empty()) << path;
      EXPECT_TRUE(has_reason(with(nan), path, "must be a finite number")) << path;
      EXPECT_TRUE(has_reason(with(-std::numeric_limits<double>::infinity()), path, "must be a finite number"))
          << path;
      EXPECT_TRUE(has_reason(with(1e101), path, "must be at most 1e100 in magnitude")) << path;
      const Range& r = field.range;
      const std::string reason = range_reason(r, field.range_note);
      if (r.has_min()) {
        EXPECT_TRUE(has_reason(with(r.min - std::max(1.0, std::abs(r.min))), path, reason)) << path;
        if (!r.min_open) {
          EXPECT_TRUE(errors_for(with(r.min), path).empty()) << path;
        }
        if (r.min_open) {
          EXPECT_TRUE(has_reason(with(r.min), path, reason)) << path;
        }
        if (r.min == 0.0 && r.min_open) {
          EXPECT_TRUE(has_reason(with(1e-101), path, "must be at least 1e-100")) << path;
        }
      }
      if (r.has_max()) {
        EXPECT_TRUE(has_reason(with(r.max + std::max(1.0, std::abs(r.max))), path, reason)) << path;
        if (!r.max_open) {
          EXPECT_TRUE(errors_for(with(r.max), path).empty()) << path;
        }
      }
      if (!r.has_min() && !r.has_max()) {
        EXPECT_TRUE(errors_for(with(-1e100), path).empty()) << path;
        EXPECT_TRUE(errors_for(with(1e100), path).empty()) << path;
      }
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (field.text_rule == TextRule::integrator_name) {
        const auto errors = with("no-such-integrator");
        ASSERT_EQ(errors_for(errors, path).size(), 1u) << path;
        EXPECT_EQ(errors_for(errors, path)[0].value, "no-such-integrator");
        for (const std::string_view name : integrator_names())
          if (name != exact_info.name) {
            EXPECT_TRUE(errors_for(with(std::string(name)), path).empty()) << name;
          }
      } else if (field.text_rule == TextRule::formula) {
        // A formula is read as the engine reads it: text that is none is refused at its position.
        const auto errors = errors_for(with("any text at all"), path);
        ASSERT_EQ(errors.size(), 1u) << path;
        EXPECT_NE(errors[0].reason.find("at position 0"), std::string::npos) << errors[0].reason;
        EXPECT_TRUE(errors_for(with(std::string("x^2 + y^2 - 2")), path).empty()) << path;
      } else {
        EXPECT_TRUE(errors_for(with("any text at all"), path).empty()) << path;
      }
    } else {
      static_assert(Enumerated<T>);
      EXPECT_EQ(errors_for(with(static_cast<T>(99)), path).size(), 1u) << path;
      for (const EnumName<T>& n : enum_names(std::type_identity<T>{})) {
        Scene s = base_scene();
        place(s) = n.value;
        if (s.body.model == BodyModel::rigid) s.initial.mu = s.initial.lambda;  // rigid needs μ = λ
        EXPECT_TRUE(errors_for(validate_scene(s), path).empty()) << path << " = " << n.name;
      }
    }
  });
}

TEST(SceneFields, RangeReasonsReadAsBefore) {
  EXPECT_EQ(range_reason(kPositive), "must be > 0");
  EXPECT_EQ(range_reason(kNonNegative, "why"), "must be >= 0 (why)");
  EXPECT_EQ(range_reason(Range{.min = 1e-15, .max = 1e-2}), "must be between 1e-15 and 1e-2");
  EXPECT_EQ(range_reason(Range{.min = 0, .min_open = true, .max = 1}), "must be in (0, 1]");
  EXPECT_EQ(range_reason(Range{.max = 2.5, .max_open = true}), "must be < 2.5");
  EXPECT_EQ(range_reason(kAnyNumber), "");
  EXPECT_EQ(bound_text(1e100), "1e100");
  EXPECT_EQ(bound_text(1e-100), "1e-100");
  EXPECT_EQ(bound_text(0.01), "1e-2");
  EXPECT_EQ(bound_text(0.1), "0.1");
  EXPECT_EQ(bound_text(10), "10");
  EXPECT_EQ(bound_text(250), "250");
}

// Values in messages are the shortest text that reads back to the same double: never 0.000000
// for a tiny number nor 9.9999999999999997e+199 for a huge one.
TEST(SceneFields, MessagesPrintTinyAndHugeNumbersShortest) {
  Scene tiny_mass;
  tiny_mass.body.mass = -1e-10;
  auto errors = validate_scene(tiny_mass);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].field, "body.mass");
  EXPECT_EQ(errors[0].value, "-1e-10");
  EXPECT_EQ(errors[0].reason, "must be > 0");

  Scene below;
  below.body.inertia = 1e-101;
  errors = validate_scene(below);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].value, "1e-101");
  EXPECT_EQ(errors[0].reason, "must be at least 1e-100");

  Scene huge;
  huge.potential.deformation = AbcPotential{.C = -1e200};
  errors = validate_scene(huge);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].field, "potential.deformation.C");
  EXPECT_EQ(errors[0].value, "-1e+200");

  Scene tolerance;
  tolerance.integrator.tolerance = 1e-20;
  errors = validate_scene(tolerance);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].value, "1e-20");
  EXPECT_EQ(errors[0].reason, "must be between 1e-15 and 1e-2");

  Scene tenth;
  tenth.initial.r = -0.1;
  errors = validate_scene(tenth);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].value, "-0.1");  // not -0.10000000000000001

  // Every value of every error of every field: shortest, never fixed-point noise.
  for_each_scene_field([&](const std::string& path, std::string_view, const auto& field, auto place) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    if constexpr (std::is_same_v<T, double> || OptionalNumber<T>) {
      for (const double v : {-3e-300, 1e-200, -7e250}) {
        Scene s = base_scene(field.surfaces);
        place(s) = v;
        for (const FieldError& e : errors_for(validate_scene(s), path)) {
          EXPECT_EQ(std::stod(e.value), v) << path << ": " << e.value;
          EXPECT_LE(e.value.size(), 8u) << path << ": " << e.value;
        }
      }
    }
  });
}

}  // namespace
}  // namespace spinfold
