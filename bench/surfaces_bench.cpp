#include "bench/surfaces_bench.h"

#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "bench/timing.h"
#include "engine/constraint_projection.h"
#include "engine/embedded_dynamics.h"
#include "engine/embedded_run.h"
#include "engine/field_stepping.h"
#include "engine/formula_surface.h"
#include "engine/integrator.h"
#include "engine/revolution_chart.h"

namespace spinfold::bench {
namespace {

namespace odeint = boost::numeric::odeint;
using OdeState = std::vector<double>;

// physics-surfaces.md §11 WS1's torus, gravity and abc, with an isotropic body (J = 0.5): a regular
// internal motion, so that the error at T measures the methods and not a Lyapunov exponent.
RevolutionModel torus_model() {
  RevolutionModel model;
  model.surface.kind = SurfaceKind::torus;
  model.surface.tube_radius = 1.0;
  model.surface.center_radius = 3.0;
  model.body.mass = 2.0;
  Body body;
  body.inertia = 0.5;
  model.body.inertia = inertia_of(body);
  model.body.height = GravityPotential{0.5};
  model.body.deformation = AbcPotential{0.01, 0.02, 0.2};
  return model;
}

// The same model as a scene (the orbit-only stepping is chosen from a scene: engine/embedded_run.h).
Scene torus_scene(Stepping stepping) {
  Scene scene;
  scene.surface.kind = SurfaceKind::torus;
  scene.surface.tube_radius = 1.0;
  scene.surface.center_radius = 3.0;
  scene.body.mass = 2.0;
  scene.body.inertia = 0.5;
  scene.potential.height = GravityPotential{0.5};
  scene.potential.deformation = AbcPotential{0.01, 0.02, 0.2};
  scene.integrator.stepping = stepping;
  return scene;
}

Embedded torus_start(const RevolutionModel& model) {
  RevolutionRates r;
  r.u = 0.7;
  r.phi = 0.3;
  r.L << 1.2, 0.1, -0.2, 0.9;
  r.u_dot = 0.4;
  r.phi_dot = -0.2;
  r.L_dot << 0.05, 0.3, -0.1, 0.2;
  return embed(model, revolution_coords(model, r));
}

struct Point {
  double tolerance, error, ms;
  long evaluations;
};

struct Method {
  std::string name;
  std::vector<Point> points;
};

double distance(const Coords& a, const Embedded& b) {
  double worst = 0.0;
  for (int i = 0; i < 18; ++i) worst = std::max(worst, std::abs(a(i) - b(i)) / (1.0 + std::abs(b(i))));
  return worst;
}

}  // namespace

int run_surfaces_bench(const SurfacesBenchOptions& options) {
  const RevolutionModel model = torus_model();
  const RevolutionImplicit torus(model.surface);
  const EmbeddedModel em{torus, model.body};
  const Embedded start = torus_start(model);
  long evaluations = 0;
  const VectorField field = [&](const Coords& y, Coords& dy) {
    Embedded d;
    embedded_vector_field(em, y, d);
    dy = d;
    ++evaluations;
  };
  const Scene unused_scene;
  const Chart unused_chart;
  const StepProblem problem{unused_scene, unused_chart, &field};
  const auto engine_run = [&](const char* name, double tolerance) {
    std::unique_ptr<Integrator> integrator = find_integrator(name)->make();
    return step_field(*integrator, problem, start, options.t_end, 1e-3, tolerance).y;
  };
  // The orbit alone (10 of its 18 numbers move), the internal motion in closed form at T.
  const auto orbit_model = std::make_shared<const EmbeddedScene>(torus_scene(Stepping::automatic));
  const EmbeddedScene full_model(torus_scene(Stepping::full));
  const Coords orbit_start = embedded_layout(*orbit_model, full_model, Coords(start));
  const VectorField orbit_field_raw = embedded_field(orbit_model);
  const VectorField orbit_field = [&](const Coords& y, Coords& dy) {
    orbit_field_raw(y, dy);
    ++evaluations;
  };
  const StepProblem orbit_problem{unused_scene, unused_chart, &orbit_field};
  const auto orbit_run = [&](double tolerance) {
    std::unique_ptr<Integrator> integrator = find_integrator("dop853")->make();
    const Coords end = step_field(*integrator, orbit_problem, orbit_start, options.t_end, 1e-3, tolerance).y;
    return Coords(embedded_full_state(*orbit_model, end));
  };
  // Odeint's steppers on the same field (all 18 numbers, or the orbit alone: the name's suffix)
  const auto odeint_run = [&](const std::string& method, double tolerance) {
    const bool orbit = method.ends_with("_orbit_only");
    const std::string stepper = orbit ? method.substr(0, method.size() - 11) : method;
    const VectorField& f = orbit ? orbit_field : field;
    const Coords& y0 = orbit ? orbit_start : Coords(start);
    OdeState x(y0.data(), y0.data() + 18);
    const auto system = [&](const OdeState& in, OdeState& out, double) {
      Coords y = Eigen::Map<const Eigen::VectorXd>(in.data(), 18), d;
      f(y, d);
      out.assign(d.data(), d.data() + 18);
    };
    if (stepper == "odeint_dopri5")
      odeint::integrate_adaptive(
          odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_dopri5<OdeState>()), system, x,
          0.0, options.t_end, 1e-3);
    else if (stepper == "odeint_fehlberg78")
      odeint::integrate_adaptive(
          odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_fehlberg78<OdeState>()), system,
          x, 0.0, options.t_end, 1e-3);
    else
      odeint::integrate_adaptive(odeint::bulirsch_stoer<OdeState>(tolerance, tolerance), system, x, 0.0,
                                 options.t_end, 1e-3);
    const Coords y = Eigen::Map<const Eigen::VectorXd>(x.data(), 18);
    return orbit ? Coords(embedded_full_state(*orbit_model, y)) : y;
  };

  // The reference: dop853 at 1e-15, checked against Odeint's Bulirsch–Stoer at 1e-15.
  const Coords dop_ref = engine_run("dop853", 1e-15);
  Embedded reference = dop_ref;
  const double reference_spread = distance(odeint_run("odeint_bulirsch_stoer", 1e-15), reference);
  std::printf("torus (a = 1, c = 3), WS1's body with J = 0.5, gravity, abc; T = %g\n", options.t_end);
  std::printf(
      "reference: dop853 at 1e-15; Odeint's Bulirsch-Stoer at 1e-15 differs by %.2g (relative, max)\n\n",
      reference_spread);

  std::vector<Method> methods;
  for (const std::string name :
       {"dop853", "dop853_orbit_only", "odeint_dopri5", "odeint_fehlberg78", "odeint_bulirsch_stoer",
        "odeint_dopri5_orbit_only", "odeint_fehlberg78_orbit_only", "odeint_bulirsch_stoer_orbit_only"}) {
    Method method{name, {}};
    for (double exponent = 5.0; exponent <= 14.0; exponent += 0.5) {
      const double tolerance = std::pow(10.0, -exponent);
      Coords end;
      evaluations = 0;
      const double ms = median_ms(options.repeats, [&] {
        end = name == "dop853"              ? engine_run("dop853", tolerance)
              : name == "dop853_orbit_only" ? orbit_run(tolerance)
                                            : odeint_run(name, tolerance);
      });
      const long evals = evaluations / options.repeats;
      method.points.push_back({tolerance, distance(end, reference), ms, evals});
    }
    methods.push_back(method);
  }

  std::printf("| method | tolerance | error at T | ms | evaluations |\n| --- | --- | --- | --- | --- |\n");
  double engine_best = std::numeric_limits<double>::infinity(), odeint_best = engine_best,
         orbit_best = engine_best, odeint_orbit_best = engine_best, engine_tolerance = 1e-10,
         orbit_tolerance = 1e-10;
  std::string odeint_best_name, odeint_orbit_best_name;
  for (const Method& m : methods) {
    const Point* best = nullptr;
    for (const Point& p : m.points)
      if (p.error <= options.target_error && (!best || p.ms < best->ms)) best = &p;
    for (const Point& p : m.points)
      std::printf("| %s | %.1e | %.2e | %.3f | %ld |%s\n", m.name.c_str(), p.tolerance, p.error, p.ms,
                  p.evaluations, &p == best ? " (cheapest within the target)" : "");
    if (!best) continue;
    if (m.name == "dop853")
      engine_best = best->ms, engine_tolerance = best->tolerance;
    else if (m.name == "dop853_orbit_only")
      orbit_best = best->ms, orbit_tolerance = best->tolerance;
    else if (m.name.ends_with("_orbit_only")) {
      if (best->ms < odeint_orbit_best) odeint_orbit_best = best->ms, odeint_orbit_best_name = m.name;
    } else if (best->ms < odeint_best) {
      odeint_best = best->ms;
      odeint_best_name = m.name;
    }
  }
  std::printf("\nat error <= %.0e: engine dop853 %.3f ms, Odeint's best (%s) %.3f ms: ratio %.2f\n",
              options.target_error, engine_best, odeint_best_name.c_str(), odeint_best,
              odeint_best / engine_best);
  std::printf(
      "at error <= %.0e: orbit-only dop853 %.3f ms: %.2f x faster than stepping all 18, %.2f x Odeint's best "
      "on "
      "all 18; Odeint's best on the orbit alone (%s) %.3f ms: ratio %.2f\n",
      options.target_error, orbit_best, engine_best / orbit_best, odeint_best / orbit_best,
      odeint_orbit_best_name.c_str(), odeint_orbit_best, odeint_orbit_best / orbit_best);
  // The same answer: orbit-only against stepping all 18, each at its cheapest tolerance within the target.
  std::printf("orbit-only (tolerance %.1e) against stepping all 18 (%.1e): %.2g (relative, max)\n",
              orbit_tolerance, engine_tolerance,
              distance(orbit_run(orbit_tolerance), Embedded(engine_run("dop853", engine_tolerance))));

  // The same torus written as a formula (engine/formula_surface.h): its F, ∇F and Hess F from the
  // formula's jet, the same dop853 at the same tolerance (issue 49's target: at most 2× the time).
  const FormulaSurfaceParse parsed = parse_formula_surface(
      FormulaSurfaceForm::implicit, "(x^2 + y^2 + z^2 + c^2 - a^2)^2 - 4*c^2*(x^2 + y^2)",
      {{"a", model.surface.tube_radius}, {"c", model.surface.center_radius}});
  const EmbeddedModel formula_model{*parsed.surface, model.body};
  const VectorField formula_field = [&](const Coords& y, Coords& dy) {
    Embedded d;
    embedded_vector_field(formula_model, y, d);
    dy = d;
  };
  const StepProblem formula_problem{unused_scene, unused_chart, &formula_field};
  Coords built_in_end, formula_end;
  const int repeats = std::max(5, options.repeats);
  // Interleaved, so that the machine's noise falls on both alike.
  double built_in_ms = 0.0, formula_ms = 0.0;
  for (int round = 0; round < 3; ++round) {
    built_in_ms += median_ms(repeats, [&] {
      std::unique_ptr<Integrator> integrator = find_integrator("dop853")->make();
      built_in_end = step_field(*integrator, problem, start, options.t_end, 1e-3, 1e-10).y;
    });
    formula_ms += median_ms(repeats, [&] {
      std::unique_ptr<Integrator> integrator = find_integrator("dop853")->make();
      formula_end = step_field(*integrator, formula_problem, start, options.t_end, 1e-3, 1e-10).y;
    });
  }
  // Projection onto the constraints after each accepted step (engine/constraint_projection.h) on the
  // built-in torus: should it be the default on the surfaces of revolution too? The error at T against
  // the reference, the evaluations, the residuals.
  for (const double tolerance : {1e-8, 1e-10, 1e-12}) {
    ConstraintResidual off{}, on{};
    const auto track = [&torus](ConstraintResidual& worst, bool project) {
      return [&worst, project, &torus](Coords& y) {
        Embedded Y = y;
        if (project) project_onto_constraints(torus, Y);
        const ConstraintResidual r = constraint_residual(torus, Y);
        worst.distance = std::max(worst.distance, r.distance);
        worst.tangency = std::max(worst.tangency, r.tangency);
        y = Y;
      };
    };
    std::unique_ptr<Integrator> a = find_integrator("dop853")->make(), b = find_integrator("dop853")->make();
    evaluations = 0;
    const Coords plain = step_field(*a, problem, start, options.t_end, 1e-3, tolerance, track(off, false)).y;
    const long plain_evaluations = evaluations;
    evaluations = 0;
    const Coords projected =
        step_field(*b, problem, start, options.t_end, 1e-3, tolerance, track(on, true)).y;
    std::printf(
        "projection after each step, dop853 at %.0e: error at T %.2g -> %.2g, distance %.2g -> %.2g, "
        "tangency %.2g -> "
        "%.2g, evaluations %ld -> %ld (the projection's Newton steps not counted)\n",
        tolerance, distance(plain, reference), distance(projected, reference), off.distance, on.distance,
        off.tangency, on.tangency, plain_evaluations, evaluations);
  }
  std::printf(
      "formula torus against the built-in torus, dop853 at 1e-10 to T = %g: %.3f ms against %.3f ms, ratio "
      "%.2f; "
      "the two paths differ by %.2g (relative, max)\n",
      options.t_end, formula_ms / 3, built_in_ms / 3, formula_ms / built_in_ms,
      distance(formula_end, Embedded(built_in_end)));
  return 0;
}

}  // namespace spinfold::bench
