#include "bench/work_precision.h"

#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "bench/bench_scenes.h"
#include "codec/provenance.h"
#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/simulation.h"
#include "workprecision/work_precision.h"

namespace spinfold::bench {

namespace {

namespace odeint = boost::numeric::odeint;
using OdeState = std::array<double, 12>;  // rigid bodies use the first 6 entries

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

}  // namespace

int run_work_precision(const WorkPrecisionOptions& options) {
  namespace fs = std::filesystem;
  namespace wp = work_precision;
  std::vector<std::string> unknown;
  for (const std::string& name : options.scenes)
    if (std::ranges::none_of(work_precision_scenes(), [&](const BenchScene& b) { return b.name == name; }))
      unknown.push_back(name);
  if (!unknown.empty()) {
    std::string valid;
    for (const BenchScene& b : work_precision_scenes()) valid += (valid.empty() ? "" : ", ") + b.name;
    for (const std::string& name : unknown)
      std::cerr << "spinfold-bench: no bench scene named '" << name << "'\n";
    std::cerr << "(bench scenes: " << valid << "; `spinfold work-precision` takes any scene)\n";
    return 2;
  }
  const fs::path dir = options.out_dir;
  fs::create_directories(dir);
  std::ofstream csv(dir / "work_precision.csv");
  csv << "scene,method,parameter,value,seconds_per_unit_time,state_error,energy_error,steps\n";
  std::ostringstream md;
  md << "| scene | T | reference | auto picks | best of ours at " << options.target_error
     << " (µs per unit time) | best Odeint | speed-up | best stepping integrator of ours | its speed-up |\n"
     << "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";

  for (const BenchScene& bench : work_precision_scenes()) {
    if (!options.scenes.empty() && std::ranges::find(options.scenes, bench.name) == options.scenes.end())
      continue;
    const Scene& scene = bench.scene;
    const double t_end = options.periods * wp::characteristic_period(scene);
    const wp::Reference reference = wp::make_reference(scene, t_end);
    std::cerr << bench.name << ": T = " << t_end << ", reference " << reference.kind << ": "
              << reference.description << "\n";

    const auto record = [&](const wp::Point& p) {
      csv << bench.name << "," << p.method << "," << p.parameter << "," << wp::format_number(p.value) << ","
          << wp::format_number(p.seconds_per_unit_time) << "," << wp::format_number(p.state_error) << ","
          << wp::format_number(p.energy_error) << "," << p.steps << "\n";
    };
    wp::SweepOptions sweep;
    sweep.t_end = t_end;
    sweep.include_auto = false;  // the table names what auto picks instead
    sweep.max_seconds_per_run = options.max_seconds_per_run;
    wp::Curves curves = wp::sweep(scene, reference, sweep, record);
    for (const std::string stepper : {"odeint_dopri5", "odeint_fehlberg78", "odeint_bulirsch_stoer"})
      for (double tol = 1e-3; tol >= 0.9e-16; tol /= 10) {
        const wp::Point p = wp::measure(reference, t_end, stepper, "tol", tol, [&](long& evals) {
          return run_odeint(scene, stepper, tol, t_end, evals);
        });
        curves[stepper].push_back(p);
        record(p);
      }

    // Summary at the target error.
    std::string best_ours, best_odeint, best_stepping;
    double cost_ours = wp::kNotReached, cost_odeint = wp::kNotReached, cost_stepping = wp::kNotReached;
    for (const auto& [method, curve] : curves) {
      const double cost = wp::cost_at(curve, options.target_error);
      std::cerr << "  " << method << ": " << wp::format_cost(cost) << " µs per unit time at "
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
    row << "| " << bench.name << " | " << t_end << " | " << reference.kind << ": " << reference.description
        << " | " << resolve_integrator(auto_scene) << " | " << best_ours << " " << wp::format_cost(cost_ours)
        << " | " << best_odeint << " " << wp::format_cost(cost_odeint) << " | " << cost_odeint / cost_ours
        << "× | " << best_stepping << " " << wp::format_cost(cost_stepping) << " | "
        << cost_odeint / cost_stepping << "× |\n";
    md << row.str();
    if (const std::string why = wp::write_plot(
            dir, bench.name, "work-precision: " + bench.name,
            provenance_json(bench.scene, "spinfold-bench work-precision").dump(), curves, t_end);
        !why.empty())
      std::cerr << "  no plot: " << why << "\n";
  }
  md << "\nError: " << wp::kErrorMeaning << ".\n";
  std::ofstream(dir / "summary.md") << md.str();
  std::cout << md.str();
  return 0;
}

}  // namespace spinfold::bench
