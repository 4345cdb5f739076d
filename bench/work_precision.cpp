#include "bench/work_precision.h"

#include <array>
#include <boost/numeric/odeint.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>

#include "bench/bench_scenes.h"
#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/exact_solution.h"
#include "engine/invariants.h"
#include "engine/simulation.h"

namespace spinfold::bench {

namespace {

namespace odeint = boost::numeric::odeint;
using OdeState = std::array<double, 12>;  // rigid bodies use the first 6 entries

struct Point {
  std::string method;
  std::string parameter;  // "dt" or "tol"
  double value = 0.0;
  double seconds_per_unit_time = 0.0;
  double state_error = 0.0;
  double energy_error = 0.0;
  long steps = 0;  // accepted steps (ours) or right-hand-side evaluations (Odeint)
};

constexpr double kInf = std::numeric_limits<double>::infinity();

// Smallest wall time of repeated runs (at least 1, until 0.2 s have been spent or 5 runs).
template <typename Run>
double min_seconds(Run&& run) {
  double best = kInf, total = 0.0;
  for (int rep = 0; rep < 5 && total < 0.2; ++rep) {
    const auto start = std::chrono::steady_clock::now();
    run();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best = std::min(best, s);
    total += s;
  }
  return best;
}

struct Case {
  const BenchScene& bench;
  double t_end;
  State reference;
  double energy0;
};

Point measure(const Case& c, const std::string& method, const std::string& parameter, double value,
              const std::function<State(long&)>& run) {
  Point p{method, parameter, value};
  State final_state;
  long steps = 0;
  p.seconds_per_unit_time = min_seconds([&] { final_state = run(steps); }) / c.t_end;
  p.steps = steps;
  if (final_state.status != Status::ok || !final_state.y.allFinite()) {
    p.state_error = p.energy_error = kInf;
    return p;
  }
  p.state_error = state_error(c.bench.scene, final_state, c.reference);
  p.energy_error = std::abs(energy(c.bench.scene, final_state) - c.energy0) / std::abs(c.energy0);
  return p;
}

State run_ours(const Scene& base, const std::string& name, double dt, double tolerance, double t_end,
               long& steps) {
  Scene scene = base;
  scene.integrator = {name, dt, tolerance};
  Simulation run = start_simulation(scene);
  advance_to(run, t_end);
  steps = static_cast<long>(run.steps);
  return run.state;
}

// Boost.Odeint on the same vector field in the scene's chart (the bench scenes never leave it).
struct OdeintSystem {
  const Scene& scene;
  Chart chart;
  Eigen::Index size;
  long* evaluations;
  void operator()(const OdeState& x, OdeState& dxdt, double /*t*/) const {
    Coords y = Eigen::Map<const Eigen::VectorXd>(x.data(), size);
    Coords d;
    vector_field(scene, chart, y, d);
    dxdt.fill(0.0);
    std::copy(d.data(), d.data() + size, dxdt.begin());
    ++*evaluations;
  }
};

State run_odeint(const Scene& scene, const std::string& stepper, double tolerance, double t_end,
                 long& evaluations) {
  State state = initial_state(scene);
  OdeState x{};
  std::copy(state.y.data(), state.y.data() + state.y.size(), x.begin());
  evaluations = 0;
  const OdeintSystem system{scene, state.chart, state.y.size(), &evaluations};
  const double dt0 = 0.01;
  try {
    if (stepper == "odeint_dopri5")
      odeint::integrate_adaptive(
          odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_dopri5<OdeState>()), system, x,
          0.0, t_end, dt0);
    else if (stepper == "odeint_fehlberg78")
      odeint::integrate_adaptive(
          odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_fehlberg78<OdeState>()), system,
          x, 0.0, t_end, dt0);
    else
      odeint::integrate_adaptive(odeint::bulirsch_stoer<OdeState>(tolerance, tolerance), system, x, 0.0,
                                 t_end, dt0);
  } catch (const std::exception&) {
    state.status = Status::step_failed;  // Odeint gave up on the step size (tolerance below round-off)
    return state;
  }
  state.y = Eigen::Map<const Eigen::VectorXd>(x.data(), state.y.size());
  state.t = t_end;
  return state;
}

// Cost at the target error, interpolated log-log along the curve (points ordered from coarse to fine).
double cost_at(const std::vector<Point>& curve, double target) {
  double best = kInf;
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
  std::ostringstream out;
  out.precision(3);
  out << seconds * 1e6;
  return out.str();
}

void write_plot(const std::filesystem::path& dir, const std::string& scene,
                const std::map<std::string, std::vector<Point>>& curves, double t_end) {
  std::ofstream gp(dir / (scene + ".gp"));
  gp << "set terminal png size 1100,800\nset output '" << (dir / (scene + ".png")).string() << "'\n"
     << "set termoption noenhanced\nset logscale xy\nset format x '1e%L'\nset format y '1e%L'\nset grid\n"
     << "set xlabel 'state error at T = " << t_end
     << "'\nset ylabel 'wall time per unit simulated time [s]'\n"
     << "set title 'work-precision: " << scene << "'\nset key outside right\n";
  std::string plot = "plot ";
  for (const auto& [method, curve] : curves) {
    const std::string file = (dir / (scene + "_" + method + ".dat")).string();
    std::ofstream dat(file);
    for (const Point& p : curve)
      if (std::isfinite(p.state_error) && p.state_error > 0)
        dat << p.state_error << " " << p.seconds_per_unit_time << "\n";
    const std::string style = method.starts_with("odeint") ? " dashtype 2" : "";  // competitors dashed
    plot += "'" + file + "' using 1:2 with linespoints" + style + " title '" + method + "', ";
  }
  gp << plot.substr(0, plot.size() - 2) << "\n";
}

}  // namespace

int run_work_precision(const WorkPrecisionOptions& options) {
  namespace fs = std::filesystem;
  const fs::path dir = options.out_dir;
  fs::create_directories(dir);
  std::ofstream csv(dir / "work_precision.csv");
  csv << "scene,method,parameter,value,seconds_per_unit_time,state_error,energy_error,steps\n";
  csv.precision(6);
  std::ostringstream md;
  md << "| scene | T | reference | auto picks | best of ours at " << options.target_error
     << " (µs per unit time) | best Odeint | speed-up | best stepping integrator of ours | its speed-up |\n"
     << "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";

  for (const BenchScene& bench : work_precision_scenes()) {
    if (!options.scenes.empty() &&
        std::find(options.scenes.begin(), options.scenes.end(), bench.name) == options.scenes.end())
      continue;
    const Scene& scene = bench.scene;
    const double t_end = options.periods * characteristic_period(scene);
    const bool closed_form = !exact_unsupported_reason(scene);
    State reference;
    std::string reference_kind = "closed form";
    if (closed_form) {
      reference = exact_state(make_exact_solution(scene), t_end);
    } else {
      // Two independent methods at their finest: Gauss–Legendre 6 at period/4096 (the reference,
      // so that DOP853 is not measured against itself) and DOP853 at 1e-15 (the cross-check).
      long steps = 0;
      reference = run_ours(scene, "gauss6", characteristic_period(scene) / 4096, 1e-10, t_end, steps);
      const State check = run_ours(scene, "dop853", 0.01, 1e-15, t_end, steps);
      std::ostringstream kind;
      kind.precision(1);
      kind << "gauss6 at period/4096, within " << std::scientific << state_error(scene, reference, check)
           << " of DOP853 at 1e-15";
      reference_kind = kind.str();
    }
    const Case c{bench, t_end, reference, energy(scene, initial_state(scene))};
    std::cerr << bench.name << ": T = " << t_end << ", reference " << reference_kind << "\n";

    std::map<std::string, std::vector<Point>> curves;
    const auto record = [&](const Point& p) {
      curves[p.method].push_back(p);
      csv << bench.name << "," << p.method << "," << p.parameter << "," << p.value << ","
          << p.seconds_per_unit_time << "," << p.state_error << "," << p.energy_error << "," << p.steps
          << "\n";
    };
    const double period = characteristic_period(scene);
    for (const CatalogEntry& entry : integrator_catalog()) {
      const std::string name(entry.info.name);
      if (entry.info.exact) {
        if (closed_form)
          record(measure(c, name, "-", 0.0,
                         [&](long& steps) { return run_ours(scene, name, 0.01, 1e-10, t_end, steps); }));
      } else if (entry.info.adaptive) {
        for (double tol = 1e-3; tol >= 0.9e-15; tol /= 10)
          record(measure(c, name, "tol", tol,
                         [&](long& steps) { return run_ours(scene, name, 0.01, tol, t_end, steps); }));
      } else {
        for (int k = 3; k <= 16; ++k) {
          const double dt = period / (1 << k);
          const Point p = measure(
              c, name, "dt", dt, [&](long& steps) { return run_ours(scene, name, dt, 1e-10, t_end, steps); });
          record(p);
          if (p.state_error < 1e-13 || p.seconds_per_unit_time * t_end > options.max_seconds_per_run) break;
        }
      }
    }
    for (const std::string stepper : {"odeint_dopri5", "odeint_fehlberg78", "odeint_bulirsch_stoer"})
      for (double tol = 1e-3; tol >= 0.9e-16; tol /= 10)
        record(measure(c, stepper, "tol", tol,
                       [&](long& evals) { return run_odeint(scene, stepper, tol, t_end, evals); }));

    // Summary at the target error.
    std::string best_ours, best_odeint, best_stepping;
    double cost_ours = kInf, cost_odeint = kInf, cost_stepping = kInf;
    for (const auto& [method, curve] : curves) {
      const double cost = cost_at(curve, options.target_error);
      std::cerr << "  " << method << ": " << format_cost(cost) << " µs per unit time at "
                << options.target_error << "\n";
      if (method.starts_with("odeint")) {
        if (cost < cost_odeint) cost_odeint = cost, best_odeint = method;
      } else {
        if (cost < cost_ours) cost_ours = cost, best_ours = method;
        if (method != "exact" && cost < cost_stepping) cost_stepping = cost, best_stepping = method;
      }
    }
    Scene auto_scene = scene;
    auto_scene.integrator.name = "auto";
    std::ostringstream row;
    row.precision(3);
    row << "| " << bench.name << " | " << t_end << " | " << reference_kind << " | "
        << resolve_integrator(auto_scene) << " | " << best_ours << " " << format_cost(cost_ours) << " | "
        << best_odeint << " " << format_cost(cost_odeint) << " | " << cost_odeint / cost_ours << "× | "
        << best_stepping << " " << format_cost(cost_stepping) << " | " << cost_odeint / cost_stepping
        << "× |\n";
    md << row.str();
    write_plot(dir, bench.name, curves, t_end);
    if (std::system("command -v gnuplot > /dev/null 2>&1") == 0)
      std::system(("gnuplot '" + (dir / (bench.name + ".gp")).string() + "'").c_str());
  }
  std::ofstream(dir / "summary.md") << md.str();
  std::cout << md.str();
  return 0;
}

}  // namespace spinfold::bench
