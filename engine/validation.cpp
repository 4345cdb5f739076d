#include "engine/validation.h"

#include <cmath>
#include <numbers>
#include <sstream>

#include "engine/chart.h"
#include "engine/exact_solution.h"
#include "engine/integrator.h"
#include "engine/invariants.h"
#include "engine/potentials.h"

namespace spinfold {

namespace {

std::string number_text(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
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
      add(field, v, "must be at most 1e100 in magnitude");
      return false;
    }
    return true;
  }
  void positive(const std::string& field, double v) {
    if (!finite(field, v)) return;
    if (!(v > 0.0))
      add(field, v, "must be > 0");
    else if (v < kMinScenePositive)
      add(field, v, "must be at least 1e-100");
  }
  void non_negative(const std::string& field, double v) {
    if (finite(field, v) && v < 0.0) add(field, v, "must be >= 0");
  }
  void add(const std::string& field, double v, const std::string& reason) {
    errors.push_back({field, number_text(v), reason});
  }
  void add_text(const std::string& field, const std::string& value, const std::string& reason) {
    errors.push_back({field, value, reason});
  }
  std::vector<FieldError> errors;
};

void check_initial(const Scene& scene, Checker& c) {
  const InitialState& q = scene.initial;
  const Surface& surface = scene.surface;
  for (const auto& [name, value] : {std::pair{"phi", q.phi},
                                    {"alpha", q.alpha},
                                    {"beta", q.beta},
                                    {"r_dot", q.r_dot},
                                    {"phi_dot", q.phi_dot},
                                    {"alpha_dot", q.alpha_dot},
                                    {"beta_dot", q.beta_dot},
                                    {"lambda_dot", q.lambda_dot},
                                    {"mu_dot", q.mu_dot}})
    c.finite(std::string("initial.") + name, value);
  c.positive("initial.lambda", q.lambda);
  c.positive("initial.mu", q.mu);
  if (c.finite("initial.r", q.r)) {
    if (q.r < 0.0) c.add("initial.r", q.r, "must be >= 0 (geodesic distance from the pole)");
    if (surface.kind == SurfaceKind::sphere && std::isfinite(surface.radius) && surface.radius > 0.0 &&
        q.r > std::numbers::pi * surface.radius)
      c.add("initial.r", q.r, "must be <= pi * radius on the sphere (the south pole)");
    if (surface.kind == SurfaceKind::pseudosphere && std::isfinite(surface.radius) && surface.radius > 0.0 &&
        q.r > kMaxHyperbolicDistance * surface.radius)
      c.add("initial.r", q.r,
            "must be <= 250 * radius on the pseudosphere (farther out its global coordinates overflow)");
  }
}

void check_potentials(const Scene& scene, Checker& c) {
  const Potentials& pot = scene.potential;
  const InitialState& q = scene.initial;
  const bool isotropic = q.lambda == q.mu;
  if (pot.radial) {
    if (c.finite("potential.radial.gamma", pot.radial->gamma) && pot.radial->gamma < 0.0)
      c.add("potential.radial.gamma", pot.radial->gamma,
            "must be >= 0 (a negative g lets the body fall into a pole, which is not supported)");
    const bool at_pole = q.r == 0.0 || (scene.surface.kind == SurfaceKind::sphere &&
                                        q.r == std::numbers::pi * scene.surface.radius);
    if (pot.radial->gamma > 0.0 && at_pole)
      c.add("initial.r", q.r, "the radial potential is infinite at a pole: start away from it");
  }
  if (const auto* abc = std::get_if<AbcPotential>(&pot.deformation)) {
    c.non_negative("potential.deformation.A", abc->A);
    c.non_negative("potential.deformation.B", abc->B);
    c.finite("potential.deformation.C", abc->C);
    if (abc->A > 0.0 && isotropic)
      c.add("initial.mu", q.mu, "A/x^2 is infinite at lambda = mu: start with lambda != mu or set A = 0");
  }
  if (const auto* polar = std::get_if<PolarPotential>(&pot.deformation)) {
    c.finite("potential.deformation.ghat", polar->ghat);
    c.finite("potential.deformation.gtilde", polar->gtilde);
    if (polar->ghat != 0.0 && isotropic)
      c.add(
          "initial.mu", q.mu,
          "the polar potential's cot^2(2 epsilon) term is infinite at lambda = mu: start with lambda != mu");
  }
  if (scene.body.model == BodyModel::rigid && has_deformation_potential(pot))
    c.add_text("potential.deformation", "present",
               "a rigid body has no deformation degrees of freedom: remove the deformation potential");
}

bool finite_start(const Scene& scene) {
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

std::vector<FieldError> validate_scene(const Scene& scene) {
  Checker c;
  c.positive("surface.radius", scene.surface.radius);
  c.positive("body.mass", scene.body.mass);
  c.positive("body.inertia", scene.body.inertia);
  check_initial(scene, c);
  if (scene.body.model == BodyModel::rigid) {
    const InitialState& q = scene.initial;
    if (q.mu != q.lambda) c.add("initial.mu", q.mu, "a rigid body needs mu = lambda (it cannot deform)");
    if (q.lambda_dot != 0.0)
      c.add("initial.lambda_dot", q.lambda_dot, "a rigid body cannot deform: must be 0");
    if (q.mu_dot != 0.0) c.add("initial.mu_dot", q.mu_dot, "a rigid body cannot deform: must be 0");
  }
  check_potentials(scene, c);

  const IntegratorSettings& in = scene.integrator;
  if (in.name != kAutoIntegrator && !find_integrator(in.name))
    c.add_text("integrator.name", in.name,
               "is not in the integrator catalog (see `spinfold integrators`) nor \"auto\"");
  if (in.name == exact_info.name)
    if (const auto why = exact_unsupported_reason(scene)) c.add_text("integrator.name", in.name, *why);
  c.positive("integrator.dt", in.dt);
  if (c.finite("integrator.tolerance", in.tolerance) && !(in.tolerance >= 1e-15 && in.tolerance <= 1e-2))
    c.add("integrator.tolerance", in.tolerance, "must be between 1e-15 and 1e-2");
  if (c.errors.empty()) check_finite_start(scene, c);
  return c.errors;
}

}  // namespace spinfold
