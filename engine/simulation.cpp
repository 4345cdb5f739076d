#include "engine/simulation.h"

#include <cmath>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/invariants.h"

namespace spinfold {

double det_L(const Scene& scene, const State& state) {
  return internal_state(scene, state.y).L.determinant();
}

std::string_view resolve_integrator(const Scene& scene) {
  if (scene.integrator.name != kAutoIntegrator) return scene.integrator.name;
  if (!exact_unsupported_reason(scene)) return exact_info.name;
  return dop853_info.name;
}

namespace {

// Kinetic + |potential| energy [energy]: what an energy error is measured against.
double energy_scale(const EnergyParts& e) {
  return e.kinetic + std::abs(e.potential);
}

}  // namespace

Simulation start_simulation(const Scene& scene, double start_time) {
  Simulation run;
  run.scene = scene;
  run.state = initial_state(scene);
  run.state.t = start_time;
  run.start_time = start_time;
  const CatalogEntry* entry = find_integrator(resolve_integrator(scene));
  run.info = &entry->info;
  if (entry->make)
    run.integrator = entry->make();
  else
    run.exact = make_exact_solution(scene);
  run.h_next = scene.integrator.dt;
  const EnergyParts start = energy_parts(scene, run.state.chart, run.state.y);
  run.initial_energy = start.kinetic + start.potential;  // = energy(): the same sum
  run.energy_scale = energy_scale(start);
  return run;
}

namespace {

bool all_finite(const Coords& y) {
  return y.allFinite();
}

// The coordinates and the chart they are in (an extreme scene can overflow the chart alone).
bool all_finite(const State& state) {
  return state.y.allFinite() && state.chart.A.allFinite() && state.chart.b.allFinite();
}

double det_of(const Coords& y) {
  return y[coord::L] * y[coord::L + 3] - y[coord::L + 1] * y[coord::L + 2];
}

// Time in [0, h] where det L crosses zero along the step from y, by bisection on sub-steps.
double locate_degenerate(Integrator& integrator, const StepProblem& f, const Coords& y, double h,
                         double tolerance) {
  const double det0 = det_of(y);
  double lo = 0.0, hi = h;
  Coords trial;
  for (int i = 0; i < 60 && hi - lo > 1e-14 * h; ++i) {
    const double mid = 0.5 * (lo + hi);
    integrator.try_step(f, y, mid, tolerance, trial);
    trial += y;
    if ((det_of(trial) > 0.0) == (det0 > 0.0))
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

namespace {

// The closed form jumps straight to t_end; a det L sign change since the last state is located by
// bisection on the closed form itself.
void advance_exact(Simulation& run, double t_end) {
  State next = exact_state(*run.exact, t_end - run.start_time);
  next.t = t_end;
  if (!all_finite(next)) {
    run.state.status = Status::non_finite;
    return;
  }
  const Scene& scene = run.scene;
  if (scene.body.model == BodyModel::affine && (det_of(run.state.y) > 0.0) != (det_of(next.y) > 0.0)) {
    const bool positive = det_of(run.state.y) > 0.0;
    double lo = run.state.t, hi = t_end;
    for (int i = 0; i < 200 && hi - lo > 1e-14 * std::max(1.0, std::abs(hi)); ++i) {
      const double mid = 0.5 * (lo + hi);
      if ((det_of(exact_state(*run.exact, mid).y) > 0.0) == positive)
        lo = mid;
      else
        hi = mid;
    }
    run.events.push_back({0.5 * (lo + hi)});
    if (scene.on_degenerate == OnDegenerate::stop) {
      run.state.status = Status::degenerate_frame;
      return;
    }
  }
  run.state = next;
  ++run.steps;
}

bool advance_steps(Simulation& run, double t_end, std::uint64_t max_attempts) {
  State& state = run.state;
  const Scene& scene = run.scene;
  const bool adaptive = run.integrator->info().adaptive;
  const bool affine = scene.body.model == BodyModel::affine;
  const double tolerance = scene.integrator.tolerance;
  const StepProblem f{scene, state.chart};
  Coords increment, y_next;
  if (run.carry.size() != state.y.size()) run.carry = Coords::Zero(state.y.size());
  for (std::uint64_t attempts = 0; state.status == Status::ok && state.t < t_end; ++attempts) {
    if (attempts == max_attempts) return false;
    const double remaining = (t_end - state.t) - run.t_carry;  // the true elapsed time is t + carry
    const double h_planned = adaptive ? run.h_next : scene.integrator.dt;
    const bool last = h_planned >= remaining;
    const double h = last ? remaining : h_planned;

    StepResult result = run.integrator->try_step(f, state.y, h, tolerance, increment);
    // Compensated summation: the carry holds the low-order bits lost in earlier additions.
    const Coords corrected = increment + run.carry;
    y_next = state.y + corrected;
    const bool finite = all_finite(y_next);
    if (!result.accepted || !finite) {
      ++run.rejected;
      if (!adaptive) {
        state.status = finite ? Status::step_failed : Status::non_finite;
        return true;
      }
      const double h_min = 1e-14 * std::max(1.0, std::abs(state.t));
      run.h_next = finite ? result.h_next : 0.25 * h;
      if (!(run.h_next > h_min)) {
        state.status = finite ? Status::step_failed : Status::non_finite;
        return true;
      }
      continue;
    }

    if (affine && (det_of(state.y) > 0.0) != (det_of(y_next) > 0.0)) {
      const double t_cross = state.t + locate_degenerate(*run.integrator, f, state.y, h, tolerance);
      run.events.push_back({t_cross});
      if (scene.on_degenerate == OnDegenerate::stop) {
        state.status = Status::degenerate_frame;
        return true;
      }
    }
    run.carry = corrected - (y_next - state.y);
    state.y = y_next;
    // Time is summed with compensation too: over millions of steps a plain sum drifts by ~Nεt,
    // and the last step, cut to land on t_end, would absorb that drift as a phase error.
    if (last) {
      state.t = t_end;
      run.t_carry = 0.0;
    } else {
      const double dt = h + run.t_carry, t_new = state.t + dt;
      run.t_carry = dt - (t_new - state.t);
      state.t = t_new;
    }
    ++run.steps;
    // A step shortened to land on t_end says nothing about the step the solution allows.
    if (adaptive) run.h_next = (last && h < h_planned) ? h_planned : result.h_next;
    const State before_chart_move = state;
    if (maintain_chart(scene, state)) {
      if (!all_finite(state)) {
        state = before_chart_move;
        state.status = Status::non_finite;
        return true;
      }
      ++run.recentres;
      run.carry.setZero(state.y.size());  // the new chart's coordinates start exact
    }
  }
  return true;
}

}  // namespace

bool advance_to(Simulation& run, double t_end, std::uint64_t max_attempts) {
  const State checkpoint = run.state;
  bool done = true;
  if (!run.exact)
    done = advance_steps(run, t_end, max_attempts);
  else if (run.state.status == Status::ok && run.state.t < t_end && max_attempts > 0)
    advance_exact(run, t_end);
  else
    done = run.state.status != Status::ok || run.state.t >= t_end;
  // The motion conserves energy. A step beyond a method's stability blows the state up (to 1e64
  // and on, every number still finite) long before anything overflows: then the energy error is
  // as large as the initial energy scale and as the current one (a body that legitimately speeds
  // up, C < 0, has an error far below the current scale). The last state known to be good is the
  // one this call started from.
  const EnergyParts now = energy_parts(run.scene, run.state.chart, run.state.y);
  const double E = now.kinetic + now.potential;
  const double error = std::abs(E - run.initial_energy);
  Status trouble = Status::ok;
  if (!std::isfinite(E))
    trouble = Status::non_finite;
  else if (error > run.energy_scale && error > 0.5 * energy_scale(now))
    trouble = Status::diverged;
  else if (run.scene.surface.kind == SurfaceKind::pseudosphere &&
           global_body(run.scene, run.state).r > kMaxHyperbolicDistance * run.scene.surface.radius)
    trouble = Status::out_of_range;
  if (trouble != Status::ok) {
    run.state = checkpoint;
    run.state.status = trouble;
    run.carry.setZero(run.state.y.size());
    run.t_carry = 0.0;
    return true;
  }
  return done;
}

}  // namespace spinfold
