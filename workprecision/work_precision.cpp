#include "workprecision/work_precision.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>

#include "codec/output_file.h"
#include "codec/provenance.h"
#include "codec/scene_json.h"
#include "engine/chart.h"
#include "engine/exact_solution.h"
#include "engine/integrator.h"
#include "engine/invariants.h"
#include "engine/simulation.h"
#include "engine/validation.h"
#include "oracle/differential.h"
#include "render/curves_plot.h"

namespace spinfold::work_precision {

namespace {

std::string sci(double value, int digits = 2) {
  std::ostringstream out;
  out.precision(digits);
  out << value;
  return out.str();
}

// The main body alone: companions are separate runs that never act on it (scene.h).
Scene main_body_only(Scene scene) {
  scene.companions.clear();
  scene.companions_source.clear();
  return scene;
}

State run_engine(const Scene& base, const std::string& name, double dt, double tolerance, double t_end,
                 long& steps, std::uint64_t max_attempts = kNoStepLimit) {
  Scene scene = base;
  scene.integrator = {name, dt, tolerance};
  Simulation run = start_simulation(scene);
  if (!advance_to(run, t_end, max_attempts)) run.state.status = Status::step_failed;  // budget spent
  steps = static_cast<long>(run.steps);
  return run.state;
}

bool finished(const State& state, double t_end) {
  return state.status == Status::ok && state.t == t_end && state.y.allFinite();
}

// The oracle's comparison of an engine state with a reference body (the oracle's own end, or an
// engine state's mapped the same way).
struct OracleMeasure {
  Scene scene;
  oracle::OracleScene oracle_scene;
  oracle::OracleRun reference;  // its end is the reference body; energy_exact, energy_scale at the start

  Errors operator()(const State& state) const {
    const oracle::EngineBody body = oracle::engine_body(scene, state, oracle_scene);
    const oracle::Difference d = oracle::compare(oracle_scene, reference, body.in_start_frame, body.in_chart);
    const auto reached = [](double x) { return std::isfinite(x) ? x : kNotReached; };
    return {reached(std::max({d.position, d.velocity, d.frame})), reached(d.energy), reached(d.position),
            reached(d.velocity), reached(d.frame)};
  }
};

// Where the oracle cannot read the scene: the embedded vectors' largest component difference,
// relative to max(1, |v|) (the bench's measure before the oracle), and |ΔH| / |H(0)|.
Errors embedded_errors(const Scene& scene, const State& a, const State& reference, double energy0) {
  const double e = embedded_state_error(scene, a, reference);
  const double de = std::abs(energy(scene, a) - energy0) / std::max(std::abs(energy0), 1e-300);
  // The parts as embedded_state_error measures them: each vector's largest component difference.
  const EmbeddedBody x = global_embedding(scene, a), y = global_embedding(scene, reference);
  const auto part = [](const Vec3& u, const Vec3& v) {
    return (u - v).cwiseAbs().maxCoeff() / std::max(1.0, v.norm());
  };
  const auto reached = [](double v) { return std::isfinite(v) ? v : kNotReached; };
  return {reached(e), reached(de), reached(part(x.X, y.X)), reached(part(x.V, y.V)),
          reached(std::max(part(x.e[0], y.e[0]), part(x.e[1], y.e[1])))};
}

}  // namespace

double characteristic_period(const Scene& scene) {
  const State s0 = initial_state(scene);
  const double m = scene.body.mass, R = scene.surface.radius;
  double period = kNotReached;
  if (scene.potential.radial) {
    // Λ = 2KE/m + K²s²/m² (physics.md §8.2): u = C(r) oscillates with ω = √Λ.
    const double K = curvature(scene.surface), E = orbital_energy(scene, s0), s = spin(scene, s0);
    period = 2.0 * std::numbers::pi / std::sqrt(2.0 * K * E / m + K * K * s * s / (m * m));
  } else if (const auto M = momentum_map(scene, s0)) {
    period = 2.0 * std::numbers::pi * m * R * R / std::sqrt(std::abs(casimir(scene.surface, *M)));
  }
  return std::isfinite(period) && period > 0.0 ? period : kNotReached;
}

double default_t_end(const Scene& scene) {
  const double period = characteristic_period(scene);
  return kDefaultPeriods * (std::isfinite(period) ? period : 1.0);
}

Horizon choose_horizon(const Scene& scene_in, std::optional<double> asked, double target,
                       std::uint64_t max_attempts) {
  const Scene scene = main_body_only(scene_in);
  Horizon h;
  h.t_end = asked ? *asked : default_t_end(scene);
  // Over the horizon measured, and never less than kChaosProbe: over a short T (25 on the chaotic
  // example) MEGNO has not yet risen past its threshold, yet an error grows e^{λT}-fold there.
  ChaosMonitor probe(scene, kDefaultChaosInterval);
  probe.advance_to(std::max(h.t_end, kChaosProbe), max_attempts);
  h.chaos = probe.indicators();
  h.chaotic = h.chaos.intervals > 0 && h.chaos.megno_mean > kChaoticMegno && h.chaos.lyapunov > 0.0;
  if (!h.chaotic) {
    h.note = h.chaos.intervals == 0
                 ? "whether the motion is chaotic is not known (" +
                       (h.chaos.stopped.empty() ? std::string("the indicators' runs stopped at once")
                                                : h.chaos.stopped) +
                       ")"
                 : "the motion is not chaotic (MEGNO mean " + sci(h.chaos.megno_mean, 3) +
                       ", Lyapunov exponent " + sci(h.chaos.lyapunov, 3) + " over t = " + sci(h.chaos.t, 3) +
                       (h.chaos.stopped.empty() ? std::string() : ", where " + h.chaos.stopped) +
                       "): an error grows like a power of t, so T measures the integrators";
    return h;
  }
  h.predictable = std::log(target / kRoundingFloor) / h.chaos.lyapunov;
  const std::string exponent = "the motion is chaotic (Lyapunov exponent " + sci(h.chaos.lyapunov, 3) +
                               ", MEGNO mean " + sci(h.chaos.megno_mean, 3) +
                               " over t = " + sci(h.chaos.t, 3) + "): an error of " + sci(kRoundingFloor) +
                               " grows past " + sci(target) + " in " + sci(h.predictable, 3);
  if (h.predictable >= h.t_end) {
    h.note = exponent + ", beyond T";
  } else if (asked) {
    h.beyond = true;
    h.note = exponent + ", so T = " + sci(h.t_end, 4) +
             " (--t-end) measures the chaos, not the integrators: no setting can be recommended there "
             "(give --t-end " +
             sci(h.predictable, 3) + " or less)";
  } else {
    h.shortened = true;
    h.note = exponent + ", so T is that horizon instead of " + sci(h.t_end, 4);
    h.t_end = h.predictable;
  }
  return h;
}

Reference make_reference(const Scene& scene_in, double t_end) {
  const Scene scene = main_body_only(scene_in);
  const bool closed_form = !exact_unsupported_reason(scene);
  const double period = characteristic_period(scene);
  long steps = 0;
  // The engine's most accurate state at T, for a reference or a cross-check.
  const auto engine_best = [&](std::string& what) {
    if (closed_form) {
      what = "the closed form";
      return exact_state(make_exact_solution(scene), t_end);
    }
    what = "gauss6 at dt = " + sci(std::min(period, t_end) / 4096, 3);
    return run_engine(scene, "gauss6", std::min(period, t_end) / 4096, 1e-10, t_end, steps);
  };
  const auto dop853_best = [&] { return run_engine(scene, "dop853", 0.01, 1e-15, t_end, steps); };

  std::unique_ptr<OracleMeasure> measure;
  std::string oracle_trouble;
  try {
    measure = std::make_unique<OracleMeasure>(
        OracleMeasure{scene, oracle::read_scene(scene_to_json(scene).dump()), {}});
  } catch (const std::exception& e) {
    oracle_trouble = std::string("the oracle cannot read the scene (") + e.what() + ")";
  }
  if (measure) {
    measure->reference = oracle::run_oracle(measure->oracle_scene, t_end);
    if (measure->reference.ok) {
      // Its own check: the engine's best independent answer, measured against it.
      std::string what;
      const State check = closed_form ? engine_best(what) : dop853_best();
      if (!closed_form) what = "dop853 at tol 1e-15";
      const Errors agreement = (*measure)(check);
      const auto shared = std::shared_ptr<OracleMeasure>(std::move(measure));
      return {"oracle",
              "the extended-precision oracle (oracle/, __float128 Gragg-Bulirsch-Stoer at tol 1e-20, no "
              "code shared with the engine); " +
                  what + " is within " + sci(agreement.state) + " of it",
              [shared](const State& s) { return (*shared)(s); }};
    }
    oracle_trouble = "the oracle stopped (" + measure->reference.error + ")";
  }

  // The engine's best, cross-checked by dop853 at 1e-15 (by the closed form's own check otherwise).
  std::string what;
  const State reference = engine_best(what);
  const State check = dop853_best();
  const std::string kind = closed_form ? "closed form" : "gauss6";
  if (measure) {  // the oracle read the scene: its comparison still measures against our state
    measure->reference.end = oracle::engine_body(scene, reference, measure->oracle_scene).in_start_frame;
    const auto shared = std::shared_ptr<OracleMeasure>(std::move(measure));
    return {
        kind,
        oracle_trouble + ": " + what + ", within " + sci((*shared)(check).state) + " of dop853 at tol 1e-15",
        [shared](const State& s) { return (*shared)(s); }};
  }
  const double energy0 = energy(scene, initial_state(scene));
  return {
      kind,
      oracle_trouble + ": " + what + ", within " +
          sci(embedded_errors(scene, check, reference, energy0).state) +
          " of dop853 at tol 1e-15 (errors: embedded components, not geodesic)",
      [scene, reference, energy0](const State& s) { return embedded_errors(scene, s, reference, energy0); }};
}

Point measure(const Reference& reference, double t_end, const std::string& method,
              const std::string& parameter, double value, const std::function<State(long&)>& run) {
  Point p{method, parameter, value};
  State final_state;
  long steps = 0;
  double best = kNotReached, total = 0.0;
  for (int rep = 0; rep < 5 && total < 0.2; ++rep) {  // best of up to 5 runs within 0.2 s
    const auto start = std::chrono::steady_clock::now();
    final_state = run(steps);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best = std::min(best, s);
    total += s;
  }
  p.seconds_per_unit_time = best / t_end;
  p.steps = steps;
  if (!finished(final_state, t_end)) return p;  // errors stay "not reached"
  const Errors e = reference.errors(final_state);
  p.state_error = e.state;
  p.energy_error = e.energy;
  p.position_error = e.position;
  p.velocity_error = e.velocity;
  p.frame_error = e.frame;
  return p;
}

namespace {

// Why the scene's validator refuses to run it with the integrator `name` (exact without a closed
// form; a splitting method where the curvature varies), if it does: the one rule, not a list here.
std::optional<std::string> integrator_refusal(const Scene& scene, std::string_view name) {
  Scene with = main_body_only(scene);
  with.integrator.name = std::string(name);
  for (const FieldError& e : validate_scene(with))
    if (e.field == "integrator.name") return e.reason;
  return std::nullopt;
}

}  // namespace

std::map<std::string, std::string> skipped_integrators(const Scene& scene, const SweepOptions& options) {
  std::map<std::string, std::string> skipped;
  for (const CatalogEntry& entry : integrator_catalog()) {
    const std::string name(entry.info.name);
    const bool wanted = options.integrators.empty() ||
                        std::ranges::find(options.integrators, name) != options.integrators.end();
    if (const auto why = integrator_refusal(scene, name); why && wanted) skipped[name] = *why;
  }
  return skipped;
}

Curves sweep(const Scene& scene_in, const Reference& reference, const SweepOptions& options,
             const std::function<void(const Point&)>& on_point) {
  const Scene scene = main_body_only(scene_in);
  const double t_end = options.t_end;
  const bool closed_form = !exact_unsupported_reason(scene);
  // Fixed steps are fractions of the period (of T where the motion has none or T is shorter).
  const double base_step = std::min(characteristic_period(scene), t_end);
  const auto wanted = [&](std::string_view name) {
    if (options.integrators.empty()) return name != kAutoIntegrator || options.include_auto;
    return std::ranges::find(options.integrators, name) != options.integrators.end();
  };
  Curves curves;
  const auto record = [&](const Point& p) {
    curves[p.method].push_back(p);
    if (on_point) on_point(p);
    return p;
  };
  const auto engine = [&](const std::string& name, double dt, double tolerance) {
    return [&scene, name, dt, tolerance, t_end, &options](long& steps) {
      return run_engine(scene, name, dt, tolerance, t_end, steps, options.max_attempts_per_run);
    };
  };
  const auto too_slow = [&](const Point& p) {
    return p.seconds_per_unit_time * t_end > options.max_seconds_per_run;
  };
  // The methods to sweep, in order: the catalog's wanted entries (exact only with a closed form), then auto.
  std::vector<const CatalogEntry*> methods;
  for (const CatalogEntry& entry : integrator_catalog())
    if (wanted(entry.info.name) && (!entry.info.exact || closed_form) &&
        !integrator_refusal(scene, entry.info.name))
      methods.push_back(&entry);
  const bool with_auto = wanted(kAutoIntegrator);
  const std::size_t total = methods.size() + (with_auto ? 1 : 0);
  std::size_t done = 0;
  const auto proceed = [&] { return !options.proceed || options.proceed(done, total); };
  for (const CatalogEntry* entry : methods) {
    const std::string name(entry->info.name);
    if (entry->info.exact) {
      if (!proceed()) return curves;
      record(measure(reference, t_end, name, "-", 0.0, engine(name, 0.01, 1e-10)));
    } else if (entry->info.adaptive) {
      for (double tol = 1e-3; tol >= 0.9e-15; tol /= 10) {
        if (!proceed()) return curves;
        if (too_slow(record(measure(reference, t_end, name, "tol", tol, engine(name, 0.01, tol))))) break;
      }
    } else {
      for (int k = 3; k <= 16; ++k) {
        if (!proceed()) return curves;
        const double dt = base_step / (1 << k);
        const Point p = record(measure(reference, t_end, name, "dt", dt, engine(name, dt, 1e-10)));
        if (p.state_error < 1e-13 || too_slow(p)) break;
      }
    }
    ++done;
  }
  if (with_auto) {
    if (!proceed()) return curves;
    const std::string name(kAutoIntegrator);
    record(measure(reference, t_end, name, "tol", scene.integrator.tolerance,
                   engine(name, scene.integrator.dt, scene.integrator.tolerance)));
    ++done;
  }
  if (options.proceed) options.proceed(done, total);  // the last progress: every method done
  return curves;
}

double cost_at(const std::vector<Point>& curve, double target) {
  double best = kNotReached;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const Point& p = curve[i];
    if (p.state_error <= target) best = std::min(best, p.seconds_per_unit_time);
    if (i + 1 < curve.size()) {
      const Point& q = curve[i + 1];
      if (p.state_error > target && q.state_error <= target && std::isfinite(p.state_error) &&
          q.state_error > 0) {
        const double f = std::log(target / p.state_error) / std::log(q.state_error / p.state_error);
        best = std::min(best, std::exp(std::log(p.seconds_per_unit_time) +
                                       f * std::log(q.seconds_per_unit_time / p.seconds_per_unit_time)));
      }
    }
  }
  return best;
}

std::string format_cost(double seconds) {
  if (!std::isfinite(seconds)) return "not reached";
  return sci(seconds * 1e6, 3);
}

std::string format_number(double value) {
  if (!std::isfinite(value)) return "inf";
  return sci(value, 6);
}

namespace {

std::string setting(const Point& p) {
  if (p.parameter == "-") return p.method;
  return p.method + " at " + p.parameter + " " + sci(p.value, 3);
}

// "1.6×", "40×", "7800×": two significant digits, never an exponent.
std::string ratio(double a, double b) {
  const double r = a / b;
  if (r >= 100 && std::isfinite(r)) {
    const double unit = std::pow(10.0, std::floor(std::log10(r)) - 1);
    return std::to_string(std::llround(std::round(r / unit) * unit)) + "×";
  }
  return sci(r, 2) + "×";
}

}  // namespace

namespace {

// The cheapest measured setting of a stepping integrator (neither exact nor auto) within the target.
std::optional<Point> best_stepping_setting(const Curves& curves, double target) {
  std::optional<Point> best;
  for (const auto& [method, curve] : curves)
    if (method != "exact" && method != kAutoIntegrator)
      for (const Point& p : curve)
        if (p.state_error <= target && (!best || p.seconds_per_unit_time < best->seconds_per_unit_time))
          best = p;
  return best;
}

// auto at the scene's tolerance, when it reaches the target.
std::optional<Point> auto_setting(const Curves& curves, double target) {
  const auto it = curves.find(std::string(kAutoIntegrator));
  if (it == curves.end() || it->second.empty() || !(it->second[0].state_error <= target)) return std::nullopt;
  return it->second[0];
}

// auto is recommended when it reaches the target at no more than this factor of the best stepping
// setting's cost: it keeps choosing well when the scene is changed later (it picks exact where the
// closed form holds, and the cheapest stepper otherwise).
constexpr double kAutoSlack = 1.25;

}  // namespace

std::optional<Point> recommended_setting(const Curves& curves, double target) {
  const std::optional<Point> stepping = best_stepping_setting(curves, target);
  const std::optional<Point> automatic = auto_setting(curves, target);
  if (automatic &&
      (!stepping || automatic->seconds_per_unit_time <= kAutoSlack * stepping->seconds_per_unit_time))
    return automatic;
  return stepping;
}

std::string auto_picks(const Scene& scene) {
  Scene auto_scene = scene;
  auto_scene.integrator.name = kAutoIntegrator;
  return "picks " + std::string(resolve_integrator(auto_scene));
}

std::string recommendation(const Curves& curves, double target, double t_end, const std::string& auto_picks) {
  // The cheapest measured setting of each method that reaches the target (a setting one can use).
  std::map<std::string, const Point*> cheapest;
  const Point* most_accurate = nullptr;
  for (const auto& [method, curve] : curves)
    for (const Point& p : curve) {
      if (p.state_error <= target &&
          (!cheapest[method] || p.seconds_per_unit_time < cheapest[method]->seconds_per_unit_time))
        cheapest[method] = &p;
      if (std::isfinite(p.state_error) && (!most_accurate || p.state_error < most_accurate->state_error))
        most_accurate = &p;
    }
  std::erase_if(cheapest, [](const auto& kv) { return kv.second == nullptr; });
  const std::string where = "at error " + sci(target) + " over T = " + sci(t_end, 4);
  if (cheapest.empty()) {
    std::string line = "No integrator reached error " + sci(target) + " over T = " + sci(t_end, 4);
    if (most_accurate)
      line += "; the most accurate was " + setting(*most_accurate) + " (error " +
              sci(most_accurate->state_error) + ", " + format_cost(most_accurate->seconds_per_unit_time) +
              " µs per unit time)";
    return line + ".";
  }
  const std::optional<Point> recommended = recommended_setting(curves, target);
  const std::optional<Point> stepping = best_stepping_setting(curves, target);
  const std::string auto_text = "auto (" + auto_picks + ") at the scene's tol ";
  const auto described = [&](const Point& p) {
    return (p.method == kAutoIntegrator ? auto_text + sci(p.value) : setting(p)) + ", " +
           format_cost(p.seconds_per_unit_time) + " µs per unit time (error " + sci(p.state_error) + ")";
  };
  const auto compared = [](const Point& p, double base) {
    return p.seconds_per_unit_time < base ? ratio(base, p.seconds_per_unit_time) + " cheaper"
                                          : ratio(p.seconds_per_unit_time, base) + " dearer";
  };
  std::string line = "For this scene " + where + ": ";
  if (!recommended) {
    line += "no stepping integrator reached it";
    if (const auto it = cheapest.find("exact"); it != cheapest.end())
      line +=
          "; exact is valid here: " + format_cost(it->second->seconds_per_unit_time) + " µs per unit time";
    if (curves.contains(std::string(kAutoIntegrator)))
      line += "; " + auto_text + sci(curves.at(std::string(kAutoIntegrator))[0].value) + " does not reach it";
    return line + ".";
  }
  line += described(*recommended);
  const double base = recommended->seconds_per_unit_time;
  if (recommended->method == kAutoIntegrator) {
    if (stepping)
      line += "; the cheapest stepping setting, " + setting(*stepping) + ", is " + compared(*stepping, base);
  } else {
    if (const auto it = cheapest.find("exact"); it != cheapest.end())
      line += "; exact is valid here and " + compared(*it->second, base) + " (auto picks it where it holds)";
    if (curves.contains(std::string(kAutoIntegrator)) && !cheapest.contains(std::string(kAutoIntegrator)))
      line += "; " + auto_text + sci(curves.at(std::string(kAutoIntegrator))[0].value) + " does not reach it";
    else if (const auto it = cheapest.find(std::string(kAutoIntegrator)); it != cheapest.end())
      line += "; " + auto_text + sci(it->second->value) + " reaches it too, " + compared(*it->second, base);
  }
  return line + ".";
}

std::string recommendation(const Curves& curves, double target, const Horizon& horizon,
                           const std::string& auto_picks) {
  if (horizon.beyond)
    return "No recommendation over T = " + sci(horizon.t_end, 4) + ": " + horizon.note + ".";
  return recommendation(curves, target, horizon.t_end, auto_picks);
}

std::string csv(const std::string& comments, const Curves& curves) {
  std::ostringstream out;
  out << comments << kCsvColumns << "\n";
  for (const auto& [method, curve] : curves)
    for (const Point& p : curve)
      out << method << "," << p.parameter << "," << format_number(p.value) << ","
          << format_number(p.seconds_per_unit_time) << "," << format_number(p.state_error) << ","
          << format_number(p.energy_error) << "," << p.steps << "," << format_number(p.position_error) << ","
          << format_number(p.velocity_error) << "," << format_number(p.frame_error) << "\n";
  return out.str();
}

std::string points_table(const Curves& curves) {
  std::ostringstream md;
  md << "| method | parameter | value | µs per unit time | state error | position / velocity / frame | "
        "energy error | "
        "steps |\n"
     << "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  const auto error = [](double e) { return std::isfinite(e) ? sci(e) : std::string("-"); };
  for (const auto& [method, curve] : curves)
    for (const Point& p : curve)
      md << "| " << method << " | " << p.parameter << " | " << (p.parameter == "-" ? "-" : sci(p.value, 3))
         << " | " << format_cost(p.seconds_per_unit_time) << " | "
         << (std::isfinite(p.state_error) ? sci(p.state_error) : "stopped") << " | "
         << error(p.position_error) << " / " << error(p.velocity_error) << " / " << error(p.frame_error)
         << " | " << error(p.energy_error) << " | " << p.steps << " |\n";
  return md.str();
}

namespace {

bool ours(const std::string& method) {
  return find_integrator(method) || method == kAutoIntegrator;
}
bool drawn(const Point& p) {
  return std::isfinite(p.state_error) && p.state_error > 0;
}

// The gnuplot script of the same plot, with the data inline: `gnuplot <stem>.gp` in its folder draws
// <stem>.svg and <stem>.png again in gnuplot (an export for whoever edits the plot there; nothing
// here runs gnuplot).
std::string gnuplot_script(const std::string& stem, const std::string& title, const std::string& provenance,
                           const Curves& curves, double t_end) {
  const auto quote_safe = [](std::string text) {  // gnuplot's single-quoted strings have no escape
    std::ranges::replace(text, '\'', '"');
    return text;
  };
  std::ostringstream gp;
  gp << "# spinfold work-precision " << version_line() << "\n# provenance: " << provenance << "\n";
  gp << "# Re-plot with `gnuplot " << stem << ".gp` in this folder: draws " << stem << ".svg and " << stem
     << ".png.\n";
  std::string plot;
  int index = 0;
  for (const auto& [method, curve] : curves) {
    std::ostringstream data;
    data.precision(6);
    for (const Point& p : curve)
      if (drawn(p)) data << p.state_error << " " << p.seconds_per_unit_time << "\n";
    if (data.str().empty()) continue;
    const std::string block = "$data" + std::to_string(index++);
    gp << block << " << EOD\n" << data.str() << "EOD\n";
    plot += (plot.empty() ? "plot " : ", ") + block + " using 1:2 with linespoints" +
            (ours(method) ? "" : " dashtype 2") + " title '" + quote_safe(method) + "'";
  }
  gp << "set logscale xy\nset format x '1e%L'\nset format y '1e%L'\nset grid\n"
     << "set xlabel 'state error at T = " << sci(t_end, 4) << "'\n"
     << "set ylabel 'wall time per unit simulated time [s]'\n"
     << "set title '" << quote_safe(title) << "'\nset key outside right\n"
     << "set terminal svg size 1100,800 dynamic noenhanced\nset output '" << stem << ".svg'\n"
     << plot
     << "\n"
     // pngcairo where this gnuplot has it (antialiased), the libgd png terminal otherwise
     << "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1100,800 noenhanced } "
     << "else { set terminal png size 1100,800 noenhanced }\n"
     << "set output '" << stem << ".png'\nreplot\nset output\n";
  return gp.str();
}

}  // namespace

render::FigurePage plot_page(const std::string& title, const std::string& provenance, const Curves& curves,
                             double t_end, const PlotLayout& layout) {
  render::CurvesPlot plot{.x_title = "state error at T = " + sci(t_end, 4),
                          .y_title = "wall time per unit simulated time [s]",
                          .title = title,
                          .metadata = provenance,
                          .width = layout.width,
                          .plot_height = layout.plot_height,
                          .legend_below = layout.key_below};
  for (const auto& [method, curve] : curves) {
    render::Curve line{.label = method, .dashed = !ours(method)};
    for (const Point& p : curve)
      if (drawn(p)) line.points.push_back({p.state_error, p.seconds_per_unit_time});
    if (!line.points.empty()) plot.curves.push_back(std::move(line));
  }
  if (plot.curves.empty()) throw std::invalid_argument("no run finished: nothing to plot");
  return render::curves_page(plot);
}

std::string write_plot(const std::filesystem::path& dir, const std::string& stem, const std::string& title,
                       const std::string& provenance, const Curves& curves, double t_end,
                       const PlotLayout& layout) {
  render::FigurePage page;
  try {
    page = plot_page(title, provenance, curves, t_end, layout);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  const auto write = [&](const std::string& name, const auto& bytes) {
    write_whole_file((dir / name).string(), {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
  };
  try {
    write(stem + ".svg", render::draw_figure(page, render::FigureFormat::svg));
    write(stem + ".png", render::raster_figure(page, layout.pixels_per_point));
    write(stem + ".gp", gnuplot_script(stem, title, provenance, curves, t_end));
  } catch (const WriteError& e) {
    return std::string("the plot's files: ") + e.what();
  } catch (const std::exception& e) {
    return std::string("the plot was not drawn: ") + e.what();
  }
  return "";
}

}  // namespace spinfold::work_precision
