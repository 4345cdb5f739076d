#include "engine/validation.h"

#include <charconv>
#include <cmath>
#include <numbers>

#include "engine/chart.h"
#include "engine/embedded_run.h"
#include "engine/exact_solution.h"
#include "engine/formula_surface.h"
#include "engine/integrator.h"
#include "engine/invariants.h"
#include "engine/number_text.h"
#include "engine/potentials.h"
#include "engine/scene_fields.h"

namespace spinfold {

std::string bound_text(double bound) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, bound, std::chars_format::scientific);
  const std::string_view scientific(text, static_cast<std::size_t>(result.ptr - text));  // "1e-02"
  if (scientific.starts_with("1e")) {
    int exponent = 0;
    std::string_view digits = scientific.substr(2);
    if (digits.starts_with('+')) digits.remove_prefix(1);
    std::from_chars(digits.data(), digits.data() + digits.size(), exponent);
    if (std::abs(exponent) >= 2) return "1e" + std::to_string(exponent);
  }
  return shortest(bound);
}

std::string range_reason(const Range& range, std::string_view note) {
  std::string reason;
  if (range.has_min() && range.has_max()) {
    if (!range.min_open && !range.max_open)
      reason = "must be between " + bound_text(range.min) + " and " + bound_text(range.max);
    else
      reason = std::string("must be in ") + (range.min_open ? "(" : "[") + bound_text(range.min) + ", " +
               bound_text(range.max) + (range.max_open ? ")" : "]");
  } else if (range.has_min()) {
    reason = std::string("must be ") + (range.min_open ? "> " : ">= ") + bound_text(range.min);
  } else if (range.has_max()) {
    reason = std::string("must be ") + (range.max_open ? "< " : "<= ") + bound_text(range.max);
  }
  if (!reason.empty() && !note.empty()) reason += " (" + std::string(note) + ")";
  return reason;
}

namespace {

std::string join(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

class Checker {
 public:
  // Records a non-finite value or one beyond the supported magnitudes; true when it is usable.
  bool finite(const std::string& field, double v) {
    if (!std::isfinite(v)) {
      add(field, v, "must be a finite number");
      return false;
    }
    if (std::abs(v) > kMaxSceneMagnitude) {
      add(field, v, "must be at most " + bound_text(kMaxSceneMagnitude) + " in magnitude");
      return false;
    }
    return true;
  }
  // Records a number that is not finite or outside its range; a number that must be > 0 must also
  // be at least kMinScenePositive.
  void number(const std::string& field, double v, const Range& range, std::string_view note) {
    if (!finite(field, v)) return;
    if (!range.contains(v))
      add(field, v, range_reason(range, note));
    else if (range.has_min() && range.min == 0.0 && range.min_open && v < kMinScenePositive)
      add(field, v, "must be at least " + bound_text(kMinScenePositive));
  }
  void add(const std::string& field, double v, const std::string& reason) {
    errors.push_back({field, shortest(v), reason});
  }
  void add_text(const std::string& field, const std::string& value, const std::string& reason) {
    errors.push_back({field, value, reason});
  }
  std::vector<FieldError> errors;
};

bool is_integrator_name(std::string_view name) {
  return name == kAutoIntegrator || find_integrator(name) != nullptr;
}

// Checks every field of a struct as its table says, nested sections included.
template <typename S>
void check_fields(Checker& c, const std::string& path, const S& value) {
  for_each_field(fields_of(std::type_identity<S>{}), [&](const auto& field) {
    using T = typename std::remove_cvref_t<decltype(field)>::Value;
    const std::string name = join(path, field.name);
    const T& v = value.*field.member;
    if constexpr (std::is_same_v<T, double>) {
      c.number(name, v, field.range, field.range_note);
    } else if constexpr (OptionalNumber<T>) {
      if (v) c.number(name, *v, field.range, field.range_note);
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (field.text_rule == TextRule::integrator_name && !is_integrator_name(v))
        c.add_text(name, v, "is not in the integrator catalog (see `spinfold integrators`) nor \"auto\"");
    } else if constexpr (Enumerated<T>) {
      if (enum_name(v).empty())
        c.add_text(name, std::to_string(static_cast<int>(v)), "is not a known " + std::string(field.name));
    } else if constexpr (Point3<T>) {
      for (int k = 0; k < 3; ++k) c.finite(name + "[" + std::to_string(k) + "]", v[k]);
    } else if constexpr (NamedNumbers<T>) {
      if (v.size() > kMaxFormulaParameters)
        c.add_text(name, std::to_string(v.size()) + " names",
                   "at most " + std::to_string(kMaxFormulaParameters) + " parameters");
      for (const auto& [key, number] : v) {
        if (const auto problem = parameter_name_problem(key))
          c.add_text(join(name, key), key, "cannot name a parameter: " + *problem);
        else
          c.finite(join(name, key), number);
      }
    } else if constexpr (OptionalBox<T>) {
      if (v)
        for (int k = 0; k < 3; ++k) {
          const std::string axis = name + "[" + std::to_string(k) + "]";
          if (c.finite(axis + "[0]", (*v)[k][0]) && c.finite(axis + "[1]", (*v)[k][1]) &&
              !((*v)[k][0] < (*v)[k][1]))
            c.add_text(axis, "[" + shortest((*v)[k][0]) + ", " + shortest((*v)[k][1]) + "]",
                       "must be an interval [low, high] with low < high");
        }
    } else if constexpr (HasFields<T>) {
      check_fields(c, name, v);
    } else if constexpr (OptionalSection<T>) {
      if (v) check_fields(c, name, *v);
    } else {
      static_assert(KindVariant<T>, "a field type the validator does not know");
      std::visit(
          [&](const auto& alternative) {
            if constexpr (HasFields<std::remove_cvref_t<decltype(alternative)>>)
              check_fields(c, name, alternative);
          },
          v);
    }
  });
}

// The rules that tie fields together (the fields' own ranges are in scene_fields.h).

// A surface whose curvature varies (physics-surfaces.md §1): its parameters together (the kind's own
// rule), u on the profile's domain, and what runs only where the curvature is constant.
void check_profile_parameters(const Surface& surface, Checker& c) {
  if (!offers(surface, Offer::profile_chart)) return;
  const RevolutionSurface s = revolution_surface(surface);
  if (const auto rule = revolution_entry(s.kind).parameter_problem)
    if (const std::optional<ParameterProblem> problem = rule(s))
      c.add("surface." + std::string(problem->field), problem->value, problem->reason);
}

// A formula surface's text, read as the engine reads it: refused naming the position and why.
// True when it parses.
bool check_formula(const Surface& surface, Checker& c) {
  if (!offers(surface, Offer::formula)) return true;
  for (const auto& [key, number] : surface.parameters)
    if (parameter_name_problem(key) || !std::isfinite(number)) return false;  // named by check_fields
  const FormulaSurfaceParse parsed = parse_scene_formula(surface);
  if (parsed.surface) return true;
  c.add_text("surface." + std::string(formula_key(surface)), formula_text(surface),
             "at position " + std::to_string(parsed.error.position) + ": " + parsed.error.reason);
  return false;
}

// The start on a formula surface: initial.X must have a foot on F = 0 (physics-anysurface.md §6).
void check_formula_start(const Scene& scene, Checker& c) {
  const std::array<double, 3>& X = scene.initial.X;
  for (const double v : X)
    if (!std::isfinite(v) || std::abs(v) > kMaxSceneMagnitude) return;  // named by check_fields
  const SurfaceFoot foot = start_foot(*formula_surface_of(scene.surface), X);
  if (!foot.X)
    c.add_text("initial.X", "[" + shortest(X[0]) + ", " + shortest(X[1]) + ", " + shortest(X[2]) + "]",
               foot.refusal);
}

void check_varying_surface(const Scene& scene, Checker& c) {
  const Surface& surface = scene.surface;
  const std::string kind =
      std::string(enum_name(surface.kind)) + (offers(surface, Offer::formula) ? " surface" : "");
  check_profile_parameters(surface, c);
  const double u = scene.initial.u;
  if (offers(surface, Offer::formula)) {
    if (check_formula(surface, c)) check_formula_start(scene, c);
  } else if (std::isfinite(u) && std::abs(u) <= kMaxSceneMagnitude) {
    const RevolutionSurface s = revolution_surface(surface);
    const RevolutionEntry& entry = revolution_entry(s.kind);
    const ProfileDomain d = entry.domain(s);
    if (!d.periodic && (u < d.u_min || u > d.u_max))
      c.add("initial.u", u,
            "must be in [" + shortest(d.u_min) + ", " + (std::isfinite(d.u_max) ? shortest(d.u_max) : "inf") +
                "] on the " + kind + std::string(entry.u_meaning));
  }
  if (scene.body.model == BodyModel::incompressible)
    c.add_text(
        "body.model", "incompressible",
        "runs only under split4/split6 (RATTLE on det L), which compose the constant-curvature chart's "
        "flows: on the " +
            kind + " use affine or rigid");
  if (scene.potential.radial)
    c.add_text("potential.radial", "present",
               "is defined about the pole of a constant-curvature surface, not on the " + kind +
                   ": use potential.height (gravity or spring)");
  const std::string& name = scene.integrator.name;
  if (const CatalogEntry* entry = find_integrator(name); entry && entry->info.chart_flows_only)
    c.add_text("integrator.name", name,
               "composes the constant-curvature chart's exact flows; on the " + kind +
                   " use dop853, rk4, gauss4, gauss6, implicit_midpoint or auto");
}

// Friction is not a Hamiltonian flow: the splitting methods, which compose exact flows, cannot carry
// it, and the incompressible body runs only under them (physics.md §15). Where the curvature varies
// neither runs at all (check_varying_surface says so).
void check_friction(const Scene& scene, Checker& c) {
  if (!scene.friction || !scene.friction->any() || chart_free(scene.surface)) return;
  if (scene.body.model == BodyModel::incompressible) {
    c.add_text("friction", "present",
               "the incompressible body runs only under split4/split6 (RATTLE on det L), which compose "
               "Hamiltonian flows: friction is not one; use affine or rigid");
    return;
  }
  const std::string& name = scene.integrator.name;
  if (name == split4_info.name || name == split6_info.name)
    c.add_text("integrator.name", name,
               "composes exact Hamiltonian flows and friction is not one: use dop853, rk4, gauss4, gauss6, "
               "implicit_midpoint or auto");
}

void check_initial(const Scene& scene, Checker& c) {
  const InitialState& q = scene.initial;
  const Surface& surface = scene.surface;
  if (chart_free(surface)) {
    check_varying_surface(scene, c);
    return;
  }
  if (!offers(surface, Offer::positive_curvature) &&
      !std::holds_alternative<std::monostate>(scene.potential.height))
    c.add_text(
        "potential.height", "present",
        offers(surface, Offer::zero_curvature)
            ? "is constant on the plane (z = 0 there): only on the sphere, torus, spheroid, bump and catenoid"
            : "needs a height in ℝ³, which the pseudosphere has not: only on the sphere, torus, spheroid, "
              "bump and catenoid");
  if (!std::isfinite(q.r) || std::abs(q.r) > kMaxSceneMagnitude || !std::isfinite(surface.radius) ||
      !(surface.radius > 0.0))
    return;
  if (offers(surface, Offer::positive_curvature) && q.r > std::numbers::pi * surface.radius)
    c.add("initial.r", q.r, "must be <= pi * radius on the sphere (the south pole)");
  if (offers(surface, Offer::negative_curvature) && q.r > kMaxHyperbolicDistance * surface.radius)
    c.add("initial.r", q.r,
          "must be <= " + shortest(kMaxHyperbolicDistance) +
              " * radius on the pseudosphere (farther out its global coordinates overflow)");
}

// body.inertia as a matrix: finite, symmetric and positive definite (physics.md §13).
void check_inertia_matrix(const Scene& scene, Checker& c) {
  if (!scene.body.inertia_matrix) return;
  const InertiaMatrix& J = *scene.body.inertia_matrix;
  const std::string field = "body." + std::string(kInertiaKey);
  const std::string text = "[[" + shortest(J.J11) + ", " + shortest(J.J12) + "], [" + shortest(J.J21) + ", " +
                           shortest(J.J22) + "]]";
  for (const double v : {J.J11, J.J12, J.J21, J.J22})
    if (!std::isfinite(v) || std::abs(v) > kMaxSceneMagnitude) {
      c.add_text(
          field, text,
          "every entry must be a finite number of magnitude at most " + bound_text(kMaxSceneMagnitude));
      return;
    }
  if (J.J12 != J.J21) {
    c.add_text(field, text, "must be symmetric (J12 = J21)");
    return;
  }
  // Positive definite: J11 > 0 and det J > 0; the diagonal at least kMinScenePositive like a number J.
  const double det = J.J11 * J.J22 - J.J12 * J.J21;
  if (!(J.J11 > 0.0 && J.J22 > 0.0 && det > 0.0))
    c.add_text(field, text,
               "must be positive definite (J11 > 0 and J11 J22 - J12^2 > 0; det = " + shortest(det) + ")");
  else if (J.J11 < kMinScenePositive || J.J22 < kMinScenePositive || !std::isfinite(det))
    c.add_text(
        field, text,
        "its diagonal must be at least " + bound_text(kMinScenePositive) + " and its determinant finite");
}

// det L = λμ > 0 held fixed: the start must lie on the level set with a tangent velocity, and the
// integrator must keep the constraint (physics.md §15).
void check_incompressible(const Scene& scene, Checker& c) {
  if (scene.body.model != BodyModel::incompressible) return;
  const InitialState& q = scene.initial;
  if (!(q.lambda * q.mu > 0.0))
    c.add("initial.mu", q.mu, "an incompressible body needs det L = lambda*mu > 0 at the start");
  // d(det L)/dt = λ̇μ + λμ̇ must vanish (α̇, β̇ only rotate L).
  const double rate = q.lambda_dot * q.mu + q.lambda * q.mu_dot;
  if (std::isfinite(rate) &&
      std::abs(rate) > 1e-12 * (std::abs(q.lambda_dot * q.mu) + std::abs(q.lambda * q.mu_dot)))
    c.add(
        "initial.mu_dot", q.mu_dot,
        "an incompressible body keeps det L = lambda*mu: needs lambda_dot*mu + lambda*mu_dot = 0 (mu_dot = " +
            shortest(-q.lambda_dot * q.mu / q.lambda) + ")");
  const std::string& name = scene.integrator.name;
  if (name != kAutoIntegrator && name != split4_info.name && name != split6_info.name &&
      find_integrator(name))
    c.add_text(
        "integrator.name", name,
        "does not keep det L fixed for an incompressible body: use split4 or split6 (RATTLE on det L = "
        "lambda*mu, composed to order 4 or 6) or auto");
}

void check_rigid(const Scene& scene, Checker& c) {
  if (scene.body.model != BodyModel::rigid) return;
  const InitialState& q = scene.initial;
  if (q.mu != q.lambda) c.add("initial.mu", q.mu, "a rigid body needs mu = lambda (it cannot deform)");
  if (q.lambda_dot != 0.0) c.add("initial.lambda_dot", q.lambda_dot, "a rigid body cannot deform: must be 0");
  if (q.mu_dot != 0.0) c.add("initial.mu_dot", q.mu_dot, "a rigid body cannot deform: must be 0");
}

void check_potentials(const Scene& scene, Checker& c) {
  const Potentials& pot = scene.potential;
  const InitialState& q = scene.initial;
  const bool isotropic = q.lambda == q.mu;
  if (pot.radial && !chart_free(scene.surface)) {
    const bool at_pole = q.r == 0.0 || (offers(scene.surface, Offer::positive_curvature) &&
                                        q.r == std::numbers::pi * scene.surface.radius);
    if (pot.radial->gamma > 0.0 && at_pole)
      c.add("initial.r", q.r, "the radial potential is infinite at a pole: start away from it");
  }
  if (const auto* abc = std::get_if<AbcPotential>(&pot.deformation))
    if (abc->A > 0.0 && isotropic)
      c.add("initial.mu", q.mu, "A/x^2 is infinite at lambda = mu: start with lambda != mu or set A = 0");
  if (const auto* polar = std::get_if<PolarPotential>(&pot.deformation))
    if (polar->ghat != 0.0 && isotropic)
      c.add(
          "initial.mu", q.mu,
          "the polar potential's cot^2(2 epsilon) term is infinite at lambda = mu: start with lambda != mu");
  if (scene.body.model == BodyModel::rigid && has_deformation_potential(pot))
    c.add_text("potential.deformation", "present",
               "a rigid body has no deformation degrees of freedom: remove the deformation potential");
}

bool finite_start(const Scene& scene) {
  if (chart_free(scene.surface)) {
    const EmbeddedScene model(scene);
    const Coords y = embedded_start(model, scene.initial);
    const EnergyParts e = embedded_energy_parts(model, y);
    return y.allFinite() && std::isfinite(e.kinetic + e.potential);
  }
  const State start = initial_state(scene);
  return start.y.allFinite() && std::isfinite(energy(scene, start));
}

// Finite inputs can still overflow in the state they make (a rate of 1e300, squared). Names the
// fields whose value alone does it: those for which a neutral value gives a finite start.
void check_finite_start(const Scene& scene, Checker& c) {
  if (finite_start(scene)) return;
  struct Candidate {
    const char* field;
    double& (*slot)(Scene&);
    double neutral;
  };
  const Candidate candidates[] = {
      {"initial.r_dot", [](Scene& s) -> double& { return s.initial.r_dot; }, 0.0},
      {"initial.u_dot", [](Scene& s) -> double& { return s.initial.u_dot; }, 0.0},
      {"initial.phi_dot", [](Scene& s) -> double& { return s.initial.phi_dot; }, 0.0},
      {"initial.alpha_dot", [](Scene& s) -> double& { return s.initial.alpha_dot; }, 0.0},
      {"initial.beta_dot", [](Scene& s) -> double& { return s.initial.beta_dot; }, 0.0},
      {"initial.lambda_dot", [](Scene& s) -> double& { return s.initial.lambda_dot; }, 0.0},
      {"initial.mu_dot", [](Scene& s) -> double& { return s.initial.mu_dot; }, 0.0},
      {"initial.lambda", [](Scene& s) -> double& { return s.initial.lambda; }, 1.0},
      {"initial.mu", [](Scene& s) -> double& { return s.initial.mu; }, 1.0},
      {"body.mass", [](Scene& s) -> double& { return s.body.mass; }, 1.0},
      {"body.inertia", [](Scene& s) -> double& { return s.body.inertia; }, 1.0},
  };
  bool named = false;
  Scene probe = scene;
  for (const Candidate& k : candidates) {
    const double value = k.slot(probe);
    k.slot(probe) = k.neutral;
    const bool culprit = finite_start(probe);
    k.slot(probe) = value;
    if (!culprit) continue;
    c.add(k.field, value,
          "makes the initial state overflow (its energy is not a finite number): use a value of smaller "
          "magnitude");
    named = true;
  }
  if (!named)
    c.add_text("initial", "(state)",
               "the initial state overflows (its energy is not a finite number): use values of smaller "
               "magnitude");
}

}  // namespace

std::vector<FieldError> validate_surface(const Scene& scene) {
  Checker c;
  check_fields(c, "surface", scene.surface);
  check_profile_parameters(scene.surface, c);
  if (c.errors.empty()) check_formula(scene.surface, c);
  return c.errors;
}

std::vector<FieldError> validate_scene(const Scene& scene) {
  Checker c;
  check_fields(c, "", scene);
  check_initial(scene, c);
  check_inertia_matrix(scene, c);
  check_rigid(scene, c);
  check_incompressible(scene, c);
  check_potentials(scene, c);
  check_friction(scene, c);
  const IntegratorSettings& in = scene.integrator;
  if (in.name == exact_info.name && scene.body.model != BodyModel::incompressible)
    if (const auto why = exact_unsupported_reason(scene)) c.add_text("integrator.name", in.name, *why);
  if (c.errors.empty()) check_finite_start(scene, c);
  // Each companion as the scene it runs (its errors named under companions[i]).
  if (scene.companions.size() > kMaxCompanions)
    c.errors.push_back({"companions", std::to_string(scene.companions.size()) + " bodies",
                        "at most " + std::to_string(kMaxCompanions) + " companions (after expanding vary)"});
  for (std::size_t i = 0; i < scene.companions.size() && i < kMaxCompanions; ++i) {
    const std::string prefix = "companions[" + std::to_string(i) + "].";
    for (FieldError& e : validate_scene(companion_scene(scene, i))) {
      e.field = prefix + e.field;
      c.errors.push_back(std::move(e));
    }
    for (std::size_t k = 0; k < 3; ++k) {
      const auto& color = scene.companions[i].color;
      if (color && !((*color)[k] >= 0.0 && (*color)[k] <= 1.0))
        c.errors.push_back({prefix + "color", shortest((*color)[k]), "each component must be from 0 to 1"});
    }
  }
  return c.errors;
}

}  // namespace spinfold
