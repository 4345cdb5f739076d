// The scene's vocabulary, named once: for every parameter struct of engine/scene.h one table of its
// fields (JSON key, member, label, unit, allowed range, one-line description; the default is the
// struct's own in-class default), and for every enumerated field one table of its names. The JSON reader and
// writer, the JSON Schema and the validator all iterate these tables, and the browser UI takes its
// labels, units and help text from the schema. Plain data, no JSON.
//
// A table is a std::tuple of Field<Struct, Value>, so that each field keeps its value type; walk
// one with for_each_field. The rules that tie several fields together (a rigid body needs
// mu = lambda, r <= πR on the sphere, ...) are code in engine/validation.cpp, not data here.
#pragma once

#include <array>
#include <iterator>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "engine/number_rule.h"
#include "engine/scene.h"

namespace spinfold {

// ---- enumerated fields: one table of names each ---------------------------------------------

template <typename Enum>
struct EnumName {
  std::string_view name;  // as written in the scene JSON, the CLI and the HUD
  Enum value;
  std::string_view description;  // one line
  std::string_view title = {};   // a menu's words for it, where a person picks it (the UI)
};

inline constexpr EnumName<SurfaceKind> kSurfaceKindNames[] = {
    {"sphere", SurfaceKind::sphere, "S², curvature +1/R²", "sphere (positive curvature)"},
    {"pseudosphere", SurfaceKind::pseudosphere, "H² (Minkowski hyperboloid), curvature -1/R²",
     "hyperbolic plane (negative curvature)"},
    {"plane", SurfaceKind::plane, "the flat plane, the curvature-zero limit", "flat plane (no curvature)"},
    {"torus", SurfaceKind::torus,
     "a torus (tube_radius a, center_radius c > a): K > 0 on the outer band, < 0 on the inner",
     "torus (K > 0 outside, < 0 inside)"},
    {"spheroid", SurfaceKind::spheroid,
     "an ellipsoid of revolution (equatorial_radius a, polar_radius b): oblate a > b, prolate a < b",
     "spheroid (K varies with latitude)"},
    {"bump", SurfaceKind::bump,
     "a Gaussian bump z = h exp(-ρ²/(2w²)) on the plane: K > 0 on top, < 0 round it",
     "bump on the plane (K > 0 on top, < 0 round it)"},
    {"catenoid", SurfaceKind::catenoid,
     "the catenoid ρ = c cosh(z/c) (neck_radius c): a minimal surface, K < 0",
     "catenoid (K < 0, most negative on the neck)"},
    {"implicit", SurfaceKind::implicit,
     "any surface F(x, y, z) = 0 given by a formula F (docs/formula-language.md), with parameters",
     "your own surface F(x, y, z) = 0"},
    {"graph", SurfaceKind::graph, "a graph z = f(x, y) given by a formula z, with parameters",
     "your own graph z = f(x, y)"},
};
inline constexpr EnumName<BodyModel> kBodyModelNames[] = {
    {"affine", BodyModel::affine, "L free: 4 internal degrees of freedom"},
    {"rigid", BodyModel::rigid, "gyroscope L = λ U(θ): needs mu = lambda and no deformation"},
    {"incompressible", BodyModel::incompressible,
     "det L fixed at lambda*mu: 3 internal degrees of freedom (split4, split6: RATTLE on the level set)"},
};
inline constexpr EnumName<PolarForm> kPolarFormNames[] = {
    {"cot2", PolarForm::cot2, "W = ĝ cot²(2ε): the paper's action variable"},
    {"literal", PolarForm::literal, "W = ĝ cot²(2ε)/sin²ε: the potential as printed"},
};
inline constexpr EnumName<OnDegenerate> kOnDegenerateNames[] = {
    {"report", OnDegenerate::report, "follow the frame through det L = 0 and report the event"},
    {"stop", OnDegenerate::stop, "stop with status degenerate_frame at the last state with det L > 0"},
};
inline constexpr EnumName<Stepping> kSteppingNames[] = {
    {"auto", Stepping::automatic,
     "where the curvature varies, step only the orbit when the internal motion has a closed form "
     "(affine body, isotropic inertia, abc or no internal potential, no internal friction)"},
    {"full", Stepping::full, "step every number of the state"},
};
inline constexpr EnumName<Projection> kProjectionNames[] = {
    {"auto", Projection::automatic, "on formula surfaces: after each step, back onto the surface"},
    {"on", Projection::on, "after each step bring X back onto F = 0 and V, e_A, W_A onto its tangent plane"},
    {"off", Projection::off, "never: the state drifts off the surface with the integrator's error"},
};

// The names table of an enumerated type (found by argument-dependent lookup).
constexpr std::span<const EnumName<SurfaceKind>> enum_names(std::type_identity<SurfaceKind>) {
  return kSurfaceKindNames;
}
constexpr std::span<const EnumName<BodyModel>> enum_names(std::type_identity<BodyModel>) {
  return kBodyModelNames;
}
constexpr std::span<const EnumName<PolarForm>> enum_names(std::type_identity<PolarForm>) {
  return kPolarFormNames;
}
constexpr std::span<const EnumName<OnDegenerate>> enum_names(std::type_identity<OnDegenerate>) {
  return kOnDegenerateNames;
}
constexpr std::span<const EnumName<Stepping>> enum_names(std::type_identity<Stepping>) {
  return kSteppingNames;
}
constexpr std::span<const EnumName<Projection>> enum_names(std::type_identity<Projection>) {
  return kProjectionNames;
}

// The name of an enumerated value ("" for a value outside its table).
template <typename Enum>
constexpr std::string_view enum_name(Enum value) {
  for (const EnumName<Enum>& n : enum_names(std::type_identity<Enum>{}))
    if (n.value == value) return n.name;
  return {};
}

// The value a name stands for, if any.
template <typename Enum>
constexpr std::optional<Enum> enum_value(std::string_view name) {
  for (const EnumName<Enum>& n : enum_names(std::type_identity<Enum>{}))
    if (n.name == name) return n.value;
  return std::nullopt;
}

// A section chosen by its "kind" is a std::variant whose first alternative, std::monostate, is
// "absent" (written by omission, so it has no name) and whose others each have a table: its names,
// indexed like the alternatives.
inline constexpr std::string_view kDeformationKindNames[] = {"", "abc", "polar"};
static_assert(std::size(kDeformationKindNames) == std::variant_size_v<DeformationPotential>);
inline constexpr std::string_view kHeightKindNames[] = {"", "gravity", "spring"};
static_assert(std::size(kHeightKindNames) == std::variant_size_v<HeightPotential>);

constexpr std::span<const std::string_view> kind_names(std::type_identity<DeformationPotential>) {
  return kDeformationKindNames;
}
constexpr std::span<const std::string_view> kind_names(std::type_identity<HeightPotential>) {
  return kHeightKindNames;
}

// "auto" followed by the integrator catalog's names (engine/integrator.h): what integrator.name
// may hold.
std::vector<std::string_view> integrator_names();

// ---- numbers: allowed values -------------------------------------------------------------------

// Range, kAnyNumber, kPositive, kNonNegative: engine/number_rule.h (every number given by a person).

// What a text field may hold.
enum class TextRule {
  any,              // free, informational text: written only when not empty
  integrator_name,  // one of integrator_names()
  formula,          // a formula of docs/formula-language.md (engine/formula.h), always written
};

// ---- fields ------------------------------------------------------------------------------------

// One field of the struct S, of type T: a number (double), an optional number (std::optional<double>:
// written only when set, no default), a text (std::string), an enumerated value (an enum with a
// names table), a point (std::array<double, 3>), named numbers (SurfaceParameters: an object of
// numbers), a box (std::optional<SurfaceBounds>: [[x₀, x₁], [y₀, y₁], [z₀, z₁]], written only when
// set), or a nested struct with a table of its own (a section; also std::optional of one and
// DeformationPotential, a section chosen by its "kind").
template <typename S, typename T>
struct Field {
  using Struct = S;
  using Value = T;
  std::string_view name;  // the key in the scene JSON
  T S::*member;           // where the value lives
  // numbers: the unit, the schema's x-unit, in the dimensions mass, length, time ("energy" is
  // mass·length²/time²; "1": a pure number; the stretches λ, μ are pure numbers, so J is a moment
  // of inertia and the deformation potentials' coefficients are energies: physics.md §3, §5)
  std::string_view unit;
  Range range;                   // numbers: the allowed values
  std::string_view description;  // one line: what it does in words, then its formula
  std::string_view range_note;   // numbers: why the range, appended to its message ("" for none)
  TextRule text_rule = TextRule::any;
  // Optional numbers: the fields of S that this one stands in for when set (a scene gives one or
  // the other, never both; the writer writes this one instead), and the field it comes with ("" for
  // none: given alone).
  std::array<std::string_view, 3> replaces{};
  std::string_view partner{};
  std::string_view label{};  // numbers: a short name for people, the schema's title ("Spin s")
  // The surface kinds (bits of SurfaceKind) the field belongs to: a scene on another kind may not
  // give it (the reader names the kinds it belongs to) and the writer leaves it out.
  unsigned surfaces = ~0u;
  // Numbers a person sets by hand (the page's sliders): the values a lesson or a study usually takes,
  // the slider's span; a typed value beyond it is questioned before it is sent (never refused: that
  // is `range`'s job). Unbounded (kAnyNumber) where every value is as usual as another (an angle).
  Range usual{};

  // The default: the struct's own in-class default.
  T fallback() const { return S{}.*member; }
};

// Whether a field belongs to a surface kind (Field::surfaces).
template <typename F>
constexpr bool belongs_to(const F& field, SurfaceKind kind) {
  return (field.surfaces & surface_bit(kind)) != 0;
}

// `field` restricted to the surface kinds `surfaces` (a mask of surface_bit).
template <typename F>
constexpr F only_on(unsigned surfaces, F field) {
  field.surfaces = surfaces;
  return field;
}

// `field` with the span of values it usually takes (Field::usual), [lo, hi].
template <typename F>
constexpr F usually(double lo, double hi, F field) {
  field.usual = Range{.min = lo, .max = hi};
  return field;
}

template <typename S>
constexpr Field<S, double> number_field(std::string_view name, double S::*member, std::string_view label,
                                        std::string_view unit, Range range, std::string_view description,
                                        std::string_view range_note = {}) {
  return {name, member, unit, range, description, range_note, TextRule::any, {}, {}, label, ~0u};
}
// An optional number in place of the fields `replaces` (see Field), given together with `partner`.
template <typename S>
constexpr Field<S, std::optional<double>> optional_number_field(std::string_view name,
                                                                std::optional<double> S::*member,
                                                                std::string_view label, std::string_view unit,
                                                                Range range, std::string_view description,
                                                                std::array<std::string_view, 3> replaces,
                                                                std::string_view partner = {}) {
  return {name, member, unit, range, description, {}, TextRule::any, replaces, partner, label, ~0u};
}
template <typename S, typename T>
constexpr Field<S, T> value_field(std::string_view name, T S::*member, std::string_view description,
                                  TextRule text_rule = TextRule::any) {
  return {name, member, {}, {}, description, {}, text_rule, {}, {}, {}, ~0u};
}

// ---- the tables --------------------------------------------------------------------------------

inline constexpr std::tuple kSurfaceFields{
    value_field(
        "kind", &Surface::kind,
        "the surface: sphere, pseudosphere or plane (constant curvature), or torus, spheroid, bump or "
        "catenoid (curvature that varies)"),
    only_on(
        surfaces_offering(Offer::polar_chart),
        usually(
            0.25, 5.0,
            number_field(
                "radius", &Surface::radius, "Surface radius R", "length", kPositive,
                "the size of the surface: curvature K = +1/R² on the sphere, −1/R² on the pseudosphere; a "
                "larger radius is a flatter surface (on the plane only a length scale)"))),
    only_on(
        surfaces_offering(Offer::polar_chart),
        usually(-2.0, 2.0,
                optional_number_field(
                    "curvature", &Surface::curvature_given, "Curvature K", "1/length²", kAnyNumber,
                    "K instead of kind and radius: K > 0 a sphere of radius 1/√K, 0 the flat plane, K < 0 "
                    "the pseudosphere of radius 1/√−K; changed mid-run it continues through 0",
                    {"kind", "radius"}))),
    only_on(surface_bit(SurfaceKind::torus),
            usually(0.1, 5.0,
                    number_field(
                        "tube_radius", &Surface::tube_radius, "Tube radius a", "length", kPositive,
                        "the torus's tube: the profile circle of radius a about the centre circle (a < c)"))),
    only_on(
        surface_bit(SurfaceKind::torus),
        usually(0.1, 5.0,
                number_field(
                    "center_radius", &Surface::center_radius, "Centre radius c", "length", kPositive,
                    "the torus's centre circle, c > a: K = cos u/(a(c + a cos u)), from (c+a)⁻¹/a outside "
                    "to −(c−a)⁻¹/a inside"))),
    only_on(surface_bit(SurfaceKind::spheroid),
            usually(0.1, 5.0,
                    number_field("equatorial_radius", &Surface::equatorial_radius, "Equatorial radius a",
                                 "length", kPositive,
                                 "the spheroid's equator: oblate when a > b, prolate when a < b"))),
    only_on(surface_bit(SurfaceKind::spheroid),
            usually(0.1, 5.0,
                    number_field("polar_radius", &Surface::polar_radius, "Polar radius b", "length",
                                 kPositive, "the spheroid's half axis along z; a = b is the sphere"))),
    only_on(surface_bit(SurfaceKind::bump),
            usually(-5.0, 5.0,
                    number_field("height", &Surface::height, "Bump height h", "length", kAnyNumber,
                                 "z = h exp(−ρ²/(2w²)): a hill (h > 0) or a dip (h < 0); 0 is the plane"))),
    only_on(surface_bit(SurfaceKind::bump),
            usually(0.1, 5.0,
                    number_field("width", &Surface::width, "Bump width w", "length", kPositive,
                                 "the bump's width: K > 0 inside ρ = w, < 0 outside"))),
    only_on(
        surface_bit(SurfaceKind::catenoid),
        usually(0.1, 5.0,
                number_field("neck_radius", &Surface::neck_radius, "Neck radius c", "length", kPositive,
                             "the catenoid ρ = c cosh(z/c): its narrowest circle; K = −1/(c² cosh⁴(z/c))"))),
    only_on(
        surface_bit(SurfaceKind::implicit),
        value_field("F", &Surface::F,
                    "the surface F(x, y, z) = 0: a formula in x, y, z and the parameters (numbers, + - * / "
                    "^, sqrt exp log sin cos tan sinh cosh tanh atan asinh atan2 pi), of class C²",
                    TextRule::formula)),
    only_on(surface_bit(SurfaceKind::graph),
            value_field("z", &Surface::z, "the graph z = f(x, y): a formula in x, y and the parameters",
                        TextRule::formula)),
    only_on(
        surfaces_offering(Offer::formula),
        value_field("parameters", &Surface::parameters,
                    "the formula's named numbers, {\"a\": 2, \"b\": 1.3}: each a finite number, its name a "
                    "letter then letters, digits or _")),
    only_on(surfaces_offering(Offer::formula),
            value_field("bounds", &Surface::bounds,
                        "the piece drawn, [[x0, x1], [y0, y1], [z0, z1]] (absent: a box chosen from the "
                        "formula, a closed surface whole, an unbounded one about the origin); never where "
                        "the body may go")),
};

// body.inertia: the number below (isotropic J), or a symmetric positive-definite matrix
// [[J11, J12], [J21, J22]] in the body frame held in Body::inertia_matrix. The JSON reader, writer,
// schema and validator handle that second form by this key (physics.md §13).
inline constexpr std::string_view kInertiaKey = "inertia";

inline constexpr std::tuple kBodyFields{
    number_field("mass", &Body::mass, "Mass m", "mass", kPositive, "the body's mass m"),
    number_field(
        kInertiaKey, &Body::inertia, "Inertia J", "mass·length²", kPositive,
        "J: a number (isotropic) or a symmetric positive-definite 2x2 matrix [[J11, J12], [J12, J22]] "
        "in the body frame; the kinetic energy of deformation is J/2 ‖L̇‖² with L a pure number"),
    value_field("model", &Body::model, "affine (L free), rigid (gyroscope) or incompressible (det L fixed)"),
};

// g's unit depends on the surface: the paper's normalisations (physics.md §5, §9.7) divide g by the
// pure number sin²(r/R) on S² but by the area R² sinh²(r/R) on H² and r² on the plane.
inline constexpr std::tuple kRadialPotentialFields{
    usually(0.0, 1.0,
            number_field("gamma", &RadialPotential::gamma, "Push from the pole g",
                         "energy (sphere); energy·length² (pseudosphere, plane)", kNonNegative,
                         "keeps the body away from the pole, 0: none. V_r = g/sin²(r/R) on the sphere, "
                         "g/(R² sinh²(r/R)) on the pseudosphere, g/r² on the plane",
                         "a negative g lets the body fall into a pole, which is not supported")),
};

inline constexpr std::tuple kAbcPotentialFields{
    number_field("A", &AbcPotential::A, "Barrier A", "energy", kNonNegative,
                 "A/x²: a barrier at x = 0, where λ = μ (the body a scaled rotation)"),
    number_field("B", &AbcPotential::B, "Barrier B", "energy", kNonNegative,
                 "B/y²: a barrier at y = 0, where λ = −μ"),
    usually(
        0.0, 5.0,
        number_field("C", &AbcPotential::C, "Shape spring C", "energy", kAnyNumber,
                     "pulls the ellipse back towards its reference size, so the body breathes: C(x² + y²) = "
                     "C(λ² + μ²)")),
};

inline constexpr std::tuple kPolarPotentialFields{
    number_field("ghat", &PolarPotential::ghat, "Angular coefficient ĝ", "energy", kAnyNumber,
                 "the angular part W(ε)/ς² of the polar potential: W = ĝ cot²(2ε) (cot2)"),
    number_field("gtilde", &PolarPotential::gtilde, "Radial coefficient g̃", "energy", kAnyNumber,
                 "the radial part g̃/ς of the polar potential, ς² = λ² + μ²"),
    value_field("form", &PolarPotential::form, "W(epsilon): cot2 (the paper's action variable) or literal"),
};

inline constexpr std::tuple kGravityPotentialFields{
    usually(-2.0, 2.0,
            number_field("g", &GravityPotential::g, "Gravity g", "length/time²", kAnyNumber,
                         "V = m g z: a uniform pull along −z (g > 0), z the embedded height")),
};

inline constexpr std::tuple kSpringPotentialFields{
    number_field("k", &SpringPotential::k, "Height spring k", "energy/length²", kAnyNumber,
                 "V = k z²/2: pulls the body towards the plane z = 0 (k > 0)"),
};

inline constexpr std::tuple kPotentialsFields{
    only_on(surfaces_offering(Offer::polar_chart),
            value_field("radial", &Potentials::radial,
                        "the radial potential V_r (absent: none); only where the curvature is constant")),
    value_field("deformation", &Potentials::deformation,
                "the deformation potential, abc or polar (absent: none)"),
    only_on(surfaces_offering(Offer::implicit_equation) | surfaces_offering(Offer::positive_curvature),
            value_field("height", &Potentials::height,
                        "a potential of the embedded height z, gravity (m g z) or spring (k z²/2) (absent: "
                        "none); not on the plane (z = 0 there) nor the pseudosphere (no height in ℝ³)")),
};

inline constexpr std::tuple kFrictionFields{
    usually(0.0, 1.0,
            number_field("translational", &Friction::translational, "Translational friction γ_t", "mass/time",
                         kNonNegative, "viscous drag on the velocity: −γ_t V")),
    number_field("internal", &Friction::internal, "Internal friction γ_i", "mass·length²/time", kNonNegative,
                 "viscous drag on the frame's rates relative to parallel transport: −γ_i De_A/Dt"),
};

inline constexpr std::tuple kInitialStateFields{
    only_on(surfaces_offering(Offer::polar_chart),
            number_field("r", &InitialState::r, "Distance r", "length", kNonNegative,
                         "geodesic distance from the pole (<= pi R on the sphere)",
                         "geodesic distance from the pole")),
    only_on(surfaces_offering(Offer::formula),
            value_field("X", &InitialState::X,
                        "the start point [x, y, z] [length], brought onto F = 0 along the gradient (a graph "
                        "keeps x, y and takes z = f(x, y)); the frame there: E1 along the world x-axis's "
                        "tangential part (the y-axis's where that is shorter than 0.1), E2 = n x E1")),
    only_on(surfaces_offering(Offer::profile_chart),
            number_field(
                "u", &InitialState::u, "Profile position u", "rad (torus, spheroid); length (bump, catenoid)",
                kAnyNumber,
                "where along the profile: the torus's tube angle (0 the outer equator, −π/2 the top "
                "circle), the spheroid's polar angle from the north pole (0 to π), the distance from the "
                "bump's axis (>= 0), −z on the catenoid")),
    only_on(surfaces_offering(Offer::polar_chart) | surfaces_offering(Offer::profile_chart),
            number_field("phi", &InitialState::phi, "Polar angle φ", "rad", kAnyNumber, "polar angle")),
    number_field("alpha", &InitialState::alpha, "Rotation α", "rad", kAnyNumber,
                 "left rotation angle of L = U(α) diag(λ, μ) U(β)ᵀ"),
    number_field("beta", &InitialState::beta, "Rotation β", "rad", kAnyNumber, "right rotation angle"),
    usually(
        0.2, 3.0,
        number_field("lambda", &InitialState::lambda, "Stretch λ", "1", kPositive,
                     "the ellipse's first axis relative to the reference body (L = U(α) diag(λ, μ) U(β)ᵀ); "
                     "a rigid body's size")),
    usually(0.2, 3.0,
            number_field("mu", &InitialState::mu, "Stretch μ", "1", kPositive,
                         "the ellipse's second axis relative to the reference body (= λ for a rigid body)")),
    only_on(surfaces_offering(Offer::polar_chart),
            number_field("r_dot", &InitialState::r_dot, "Rate ṙ", "length/time", kAnyNumber, "rate of r")),
    only_on(
        surfaces_offering(Offer::profile_chart),
        number_field("u_dot", &InitialState::u_dot, "Rate u̇",
                     "rad/time (torus, spheroid); length/time (bump, catenoid)", kAnyNumber, "rate of u")),
    only_on(surfaces_offering(Offer::polar_chart) | surfaces_offering(Offer::profile_chart),
            number_field("phi_dot", &InitialState::phi_dot, "Rate φ̇", "rad/time", kAnyNumber, "rate of phi")),
    number_field("alpha_dot", &InitialState::alpha_dot, "Rate α̇", "rad/time", kAnyNumber, "rate of alpha"),
    number_field("beta_dot", &InitialState::beta_dot, "Rate β̇", "rad/time", kAnyNumber, "rate of beta"),
    number_field("lambda_dot", &InitialState::lambda_dot, "Rate λ̇", "1/time", kAnyNumber,
                 "rate of lambda (0 for a rigid body)"),
    number_field("mu_dot", &InitialState::mu_dot, "Rate μ̇", "1/time", kAnyNumber,
                 "rate of mu (0 for a rigid body)"),
    usually(-10.0, 10.0,
            optional_number_field(
                "spin", &InitialState::spin, "Spin s", "mass·length²/time", kAnyNumber,
                "how fast the body turns about itself, measured against parallel transport (0: a "
                "geodesic without potentials): s = J[(λ² + μ²)(α̇ + C(r) φ̇) − 2λμ β̇], instead of "
                "alpha_dot",
                {"alpha_dot"})),
    usually(0.0, 3.0,
            optional_number_field(
                "speed", &InitialState::speed, "Speed v", "length/time", kNonNegative,
                "how fast the body moves along the surface at the start: v = √(ṙ² + S² φ̇²) (√(f²u̇² + "
                "ρ²φ̇²) where the curvature varies), with heading instead of r_dot (u_dot) and phi_dot",
                {"r_dot", "u_dot", "phi_dot"}, "heading")),
    optional_number_field(
        "heading", &InitialState::heading, "Heading", "rad", kAnyNumber,
        "the start velocity's direction: 0 straight away from the pole (along increasing u where "
        "the curvature varies), π/2 sideways (increasing φ); with speed",
        {"r_dot", "u_dot", "phi_dot"}, "speed"),
};

inline constexpr std::tuple kIntegratorSettingsFields{
    value_field("name", &IntegratorSettings::name, "a catalog name, or auto: the engine chooses",
                TextRule::integrator_name),
    number_field("dt", &IntegratorSettings::dt, "Step dt", "time", kPositive,
                 "step (fixed-step) or first trial step"),
    number_field("tolerance", &IntegratorSettings::tolerance, "Tolerance", "1",
                 Range{.min = 1e-15, .max = 1e-2}, "error per step (adaptive)"),
    only_on(surfaces_offering(Offer::implicit_equation),
            value_field("stepping", &IntegratorSettings::stepping,
                        "auto: only the orbit where the internal motion has a closed form; full: every "
                        "number")),
    only_on(surfaces_offering(Offer::implicit_equation),
            value_field("projection", &IntegratorSettings::projection,
                        "auto (on), on: bring the state back onto F = 0 after each step; off: let it drift "
                        "with the integrator's error")),
};

inline constexpr std::tuple kSceneFields{
    value_field("name", &Scene::name, "preset name, informational"),
    value_field("description", &Scene::description, "one line, informational"),
    value_field("surface", &Scene::surface, "the surface the body moves on"),
    value_field("body", &Scene::body, "mass, inertia and model of the body"),
    value_field("potential", &Scene::potential, "the potentials acting on the body"),
    value_field("friction", &Scene::friction,
                "Rayleigh friction in translation and internal motion (absent: none): dE/dt = −2R"),
    value_field("initial", &Scene::initial, "the initial state in the paper's coordinates"),
    value_field("integrator", &Scene::integrator, "the integrator and its step and tolerance"),
    value_field("on_degenerate", &Scene::on_degenerate, "what happens when det L reaches 0"),
};

// The table of a struct (found by argument-dependent lookup).
constexpr const auto& fields_of(std::type_identity<Surface>) {
  return kSurfaceFields;
}
constexpr const auto& fields_of(std::type_identity<Body>) {
  return kBodyFields;
}
constexpr const auto& fields_of(std::type_identity<RadialPotential>) {
  return kRadialPotentialFields;
}
constexpr const auto& fields_of(std::type_identity<AbcPotential>) {
  return kAbcPotentialFields;
}
constexpr const auto& fields_of(std::type_identity<PolarPotential>) {
  return kPolarPotentialFields;
}
constexpr const auto& fields_of(std::type_identity<GravityPotential>) {
  return kGravityPotentialFields;
}
constexpr const auto& fields_of(std::type_identity<SpringPotential>) {
  return kSpringPotentialFields;
}
constexpr const auto& fields_of(std::type_identity<Friction>) {
  return kFrictionFields;
}
constexpr const auto& fields_of(std::type_identity<Potentials>) {
  return kPotentialsFields;
}
constexpr const auto& fields_of(std::type_identity<InitialState>) {
  return kInitialStateFields;
}
constexpr const auto& fields_of(std::type_identity<IntegratorSettings>) {
  return kIntegratorSettingsFields;
}
constexpr const auto& fields_of(std::type_identity<Scene>) {
  return kSceneFields;
}

// ---- kinds of field, for the code that walks the tables ----------------------------------------

template <typename T>
concept HasFields = requires {
  fields_of(std::type_identity<T>{});
};

template <typename T>
concept Enumerated = std::is_enum_v<T> && requires {
  enum_names(std::type_identity<T>{});
};

// std::array<double, 3>: a point [x, y, z].
template <typename T>
concept Point3 = std::is_same_v<T, std::array<double, 3>>;
// SurfaceParameters: named numbers, an object {"a": 2}.
template <typename T>
concept NamedNumbers = std::is_same_v<T, SurfaceParameters>;
// std::optional<SurfaceBounds>: a box [[x₀, x₁], [y₀, y₁], [z₀, z₁]], present or absent.
template <typename T>
concept OptionalBox = std::is_same_v<T, std::optional<SurfaceBounds>>;

// std::optional<double>: a number that is present or absent.
template <typename T>
concept OptionalNumber = std::is_same_v<T, std::optional<double>>;

template <typename T>
struct IsOptionalSection : std::false_type {};
template <HasFields T>
struct IsOptionalSection<std::optional<T>> : std::true_type {};
// std::optional<S> with a table: a section that is present or absent.
template <typename T>
concept OptionalSection = IsOptionalSection<T>::value;

// Calls fn(field) for every field of a table, in order.
template <typename Table, typename Fn>
constexpr void for_each_field(const Table& table, Fn&& fn) {
  std::apply([&](const auto&... field) { (fn(field), ...); }, table);
}

// A section chosen by its "kind" (DeformationPotential, HeightPotential): a variant with names.
template <typename T>
concept KindVariant = requires {
  kind_names(std::type_identity<T>{});
};

// Calls fn(std::integral_constant<std::size_t, i>{}, std::type_identity<Alternative>{}) for every
// named kind of the variant V (index 1 on).
template <KindVariant V, typename Fn>
constexpr void for_each_kind(Fn&& fn) {
  [&]<std::size_t... i>(std::index_sequence<i...>) {
    (fn(std::integral_constant<std::size_t, i + 1>{},
        std::type_identity<std::variant_alternative_t<i + 1, V>>{}),
     ...);
  }
  (std::make_index_sequence<std::variant_size_v<V> - 1>{});
}

// The names table that holds `kind` (a deformation's or a height potential's), empty if none does.
constexpr std::span<const std::string_view> kind_family(std::string_view kind) {
  for (const std::span<const std::string_view> names :
       {kind_names(std::type_identity<DeformationPotential>{}),
        kind_names(std::type_identity<HeightPotential>{})})
    for (std::string_view n : names)
      if (!n.empty() && n == kind) return names;
  return {};
}

}  // namespace spinfold
