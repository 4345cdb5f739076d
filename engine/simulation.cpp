#include "engine/simulation.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/inertia.h"
#include "engine/invariants.h"

namespace spinfold {

double det_L(const Scene& scene, const State& state) {
  if (chart_free(scene.surface)) return embedded_det(EmbeddedScene(scene), state.y);
  return internal_state(scene, state.y).L.determinant();
}

std::string_view resolve_integrator(const Scene& scene) {
  if (scene.integrator.name != kAutoIntegrator) return scene.integrator.name;
  // The incompressible body runs only under the RATTLE compositions (physics.md §15).
  if (scene.body.model == BodyModel::incompressible) return split6_info.name;
  if (!exact_unsupported_reason(scene)) return exact_info.name;
  return dop853_info.name;
}

namespace {

// Kinetic + |potential| energy [energy]: what an energy error is measured against.
double energy_scale(const EnergyParts& e) {
  return e.kinetic + std::abs(e.potential);
}

}  // namespace

namespace {

// H of a state of the run, split (the chart's Hamiltonian, or the chart-free energy).
EnergyParts parts_of(const Simulation& run, const State& state) {
  if (run.embedded) return embedded_energy_parts(*run.embedded, state.y);
  return energy_parts(run.scene, state.chart, state.y);
}

// The run's surface model, and for a scene whose curvature varies its chart-free scene and field
// (none otherwise).
void use_surface(Simulation& run) {
  run.surface = surface_model_of(run.scene.surface);
  if (!run.surface->offers(Offer::implicit_equation)) {
    run.embedded.reset();
    run.field.reset();
    return;
  }
  run.embedded = make_embedded_scene(run.scene);
  run.field = std::make_shared<const VectorField>(embedded_field(run.embedded));
}

void measure_energy_from_here(Simulation& run) {
  const EnergyParts now = parts_of(run, run.state);
  run.initial_energy = now.kinetic + now.potential;  // = energy(): the same sum
  run.energy_scale = energy_scale(now);
  run.segment_start = run.state.t;
}

void use_integrator(Simulation& run, std::string_view name) {
  const CatalogEntry* entry = find_integrator(name);
  run.info = &entry->info;
  run.integrator = entry->make ? entry->make() : nullptr;
  run.exact.reset();
}

// `auto` on the incompressible body: split6 with its step sized from the tolerance, not the scene's
// fixed dt (the tolerance is what `auto` promises; dop853 cannot keep det L, physics.md §15).
bool auto_adaptive_split6(const Scene& scene) {
  return scene.integrator.name == kAutoIntegrator && resolve_integrator(scene) == split6_info.name;
}

void use_integrator(Simulation& run) {
  if (auto_adaptive_split6(run.scene)) {
    run.info = &split6_adaptive_info;
    run.integrator = make_split6_adaptive();
    run.exact.reset();
    return;
  }
  use_integrator(run, resolve_integrator(run.scene));
}

bool all_finite(const Coords& y) {
  return y.allFinite();
}

// The coordinates and the chart they are in (an extreme scene can overflow the chart alone).
bool all_finite(const State& state) {
  return state.y.allFinite() && state.chart.A.allFinite() && state.chart.b.allFinite();
}

// The closed form's state at run time t [time].
State exact_at(const Simulation& run, double t) {
  State s = exact_state(*run.exact, t - run.segment_start);
  s.t = t;
  return s;
}

// The check is at this relative level: the closed forms agree with 35-digit evaluations to ~1e-13
// (physics.md §11), so anything near 1e-8 is a wrong orbit or a state whose invariants no longer
// carry 8 digits (a motion whose energy grew 1e6-fold).
constexpr double kExactCheck = 1e-8;
constexpr double kExactGrowth = 1e6;

bool near(double a, double b, double scale) {
  return std::abs(a - b) <= kExactCheck * scale;
}

// The conserved quantities of `state` against those of the segment's start.
bool exact_consistent(const Simulation& run, const State& state) {
  const Scene& scene = run.scene;
  const ExactCheck& c = run.exact_check;
  const EnergyParts now = energy_parts(scene, state.chart, state.y);
  // A motion grown kExactGrowth-fold (an unbounded potential) has invariants whose round-off
  // approaches the check's level: stop at that smooth, sampling-independent threshold, not at the
  // first noisy failure.
  if (!(energy_scale(now) <= kExactGrowth * run.energy_scale)) return false;
  if (!near(now.kinetic + now.potential, run.initial_energy, run.energy_scale)) return false;
  if (!near(orbital_energy(scene, state), c.orbital_energy, run.energy_scale)) return false;
  if (!near(spin(scene, state), c.spin, c.momentum_scale)) return false;
  if (c.p_phi_checked) {
    const double rounding = angular_momentum_rounding(scene, state);
    if (well_conditioned(rounding, c.momentum_scale) &&
        std::abs(angular_momentum(scene, state) - c.p_phi) > kExactCheck * c.momentum_scale + rounding)
      return false;
  }
  if (c.separated) {
    const auto e = separated_energies(scene, state);
    if (!e || !near(e->C_x, c.separated->C_x, run.energy_scale) ||
        !near(e->C_y, c.separated->C_y, run.energy_scale))
      return false;
  }
  return true;
}

// Records the start's invariants and checks the closed form at τ = 0 against the start (r, ṙ, L,
// M in the paper's frame and the invariants). Call after measure_energy_from_here.
void prepare_exact_check(Simulation& run) {
  const Scene& scene = run.scene;
  const State& start = run.state;
  ExactCheck& c = run.exact_check;
  c = ExactCheck{};
  c.spin = spin(scene, start);
  c.orbital_energy = orbital_energy(scene, start);
  c.separated = separated_energies(scene, start);
  const double m = scene.body.mass, R = scene.surface.radius;
  const double L_norm = internal_state(scene, start.y).L.norm();
  const double J = rigid_inertia(inertia_of(scene.body));
  c.momentum_scale = std::abs(c.spin) + std::sqrt(2.0 * m * run.energy_scale) * R +
                     std::sqrt(2.0 * J * run.energy_scale) * L_norm;
  if (!offers(scene.surface, Offer::zero_curvature))
    c.momentum_scale += chart_momentum(scene, start).local.cwiseAbs().sum();
  c.p_phi = angular_momentum(scene, start);
  c.p_phi_checked = well_conditioned(angular_momentum_rounding(scene, start), c.momentum_scale);

  // Without V_r the closed form at τ = 0 is the start's own chart and local body (nothing to
  // compare); the radial closed form is rebuilt in the scene's chart and is compared.
  if (!run.exact->radial) return;
  State zero = exact_at(run, start.t);
  c.start_ok = all_finite(zero) && exact_consistent(run, zero);
  if (c.start_ok) {
    const GlobalBody a = global_body(scene, start), b = global_body(scene, zero);
    const double speed = std::sqrt(2.0 * run.energy_scale / m);
    const double rate = std::sqrt(2.0 * run.energy_scale / J);
    c.start_ok = std::abs(a.r - b.r) <= kExactCheck * (R + a.r) &&
                 std::abs(a.r_dot - b.r_dot) <= kExactCheck * speed &&
                 (a.L - b.L).norm() <= kExactCheck * a.L.norm() &&
                 (a.M - b.M).norm() <= kExactCheck * (rate + a.M.norm() + speed * a.L.norm() / R);
  }
}

// An exact run: the closed form, or for `auto` dop853 where the closed form fails its check at the start.
void prepare_exact(Simulation& run, const State& start, bool scene_start) {
  run.exact = scene_start ? make_exact_solution(run.scene) : make_exact_solution(run.scene, start);
  prepare_exact_check(run);
  if (!run.exact_check.start_ok && run.scene.integrator.name == kAutoIntegrator)
    use_integrator(run, dop853_info.name);
}

}  // namespace

Simulation start_simulation(const Scene& scene, double start_time) {
  Simulation run;
  for (std::size_t i = 0; i < scene.companions.size(); ++i)
    run.companions.push_back(start_simulation(companion_scene(scene, i), start_time));
  run.scene = scene;
  use_surface(run);
  if (run.embedded)
    run.state.y = embedded_start(*run.embedded, scene.initial);
  else
    run.state = initial_state(scene);
  run.state.t = start_time;
  run.start_time = start_time;
  use_integrator(run);
  measure_energy_from_here(run);
  if (!run.integrator) prepare_exact(run, run.state, true);
  run.grid = {run.state, Coords::Zero(run.state.y.size()), 0.0, scene.integrator.dt};
  run.checked = run.grid;
  return run;
}

namespace {

// det L of the chart's L, or det[e₁, e₂, n] where the curvature varies.
double det_of(const Simulation& run, const Coords& y) {
  if (run.embedded) return embedded_det(*run.embedded, y);
  return y[coord::L] * y[coord::L + 3] - y[coord::L + 1] * y[coord::L + 2];
}

// det L of y has the sign `positive` however it is rounded (det_of and det_L may differ by an ulp).
bool det_on_side(const Simulation& run, const Coords& y, bool positive) {
  const double a = det_of(run, y);
  const double b = run.embedded ? a : internal_state(run.scene, y).L.determinant();
  return positive ? a > 0.0 && b > 0.0 : a < 0.0 && b < 0.0;
}

// Where det L crosses zero along the step from y: the time in [0, h] (by bisection on sub-steps
// from y, so it is the same whichever sample the step was cut for), and the state just before it.
struct Crossing {
  double t = 0.0;       // offset of the crossing [time]
  double before = 0.0;  // offset of `y`, ≤ 1e-14 h before it [time]
  Coords y;             // the state there (the integrator's sub-step from y)
};
Crossing locate_degenerate(const Simulation& run, Integrator& integrator, const StepProblem& f,
                           const Coords& y, double h, double tolerance) {
  const double det0 = det_of(run, y);
  double lo = 0.0, hi = h;
  Coords trial;
  for (int i = 0; i < 60 && hi - lo > 1e-14 * h; ++i) {
    const double mid = 0.5 * (lo + hi);
    integrator.try_step(f, y, mid, tolerance, trial);
    trial += y;
    if ((det_of(run, trial) > 0.0) == (det0 > 0.0))
      lo = mid;
    else
      hi = mid;
  }
  Crossing c{0.5 * (lo + hi), lo, y};
  // The state just before: back off (by 1e-15 h, doubling) until det L keeps its sign however rounded.
  for (int k = 0; c.before > 0.0; ++k) {
    integrator.try_step(f, y, c.before, tolerance, trial);
    c.y = y + trial;
    if (det_on_side(run, c.y, det0 > 0.0) || k == 50) break;
    c.before = std::max(0.0, lo - std::ldexp(1e-15 * h, k));
    c.y = y;
  }
  return c;
}

}  // namespace

namespace {

// Every this many accepted steps the sequence's energy and range are checked, so that a run that
// blows up stops at a good point of its own sequence, wherever advances stopped.
constexpr std::uint64_t kCheckEvery = 16;

// What the energy and the position say of a state: diverged (a step beyond the method's
// stability blows the state up to 1e64 and on, every number still finite, long before anything
// overflows: the energy error is then as large as the energy scale at the last change and as the
// current one; a body that legitimately speeds up, C < 0, has an error far below the current
// scale), non_finite, out_of_range (far out on H²) or ok.
//
// With friction the energy only falls (dE/dt = −2R, physics-surfaces.md §13): a fall is physics, so
// only a rise counts as divergence.
Status health(const Simulation& run, const State& state) {
  const EnergyParts now = parts_of(run, state);
  const double E = now.kinetic + now.potential;
  const bool dissipative = run.scene.friction && run.scene.friction->any();
  const double error = dissipative ? E - run.initial_energy : std::abs(E - run.initial_energy);
  if (!std::isfinite(E)) return Status::non_finite;
  if (error > run.energy_scale && error > 0.5 * energy_scale(now)) return Status::diverged;
  if (offers(run.scene.surface, Offer::negative_curvature) &&
      global_body(run.scene, state).r > kMaxHyperbolicDistance * run.scene.surface.radius)
    return Status::out_of_range;
  return Status::ok;
}

// A crossing found again (by the sequence after the cut step, or twice by bisection) is one event.
void add_event(std::vector<DegenerateEvent>& events, double t) {
  if (!events.empty() && std::abs(events.back().t - t) <= 1e-9 * std::max(1.0, std::abs(t))) return;
  events.push_back({t});
}

// The closed form jumps straight to t_end from the segment's start. The det L = 0 crossings since
// the last state are the roots of det L(τ) in the closed form's own time (degenerate_times), so
// they do not depend on where the run was sampled; a stop lands on the first one.
void advance_exact(Simulation& run, double t_end) {
  const auto at = [&run](double t) { return exact_at(run, t); };
  State next = at(t_end);
  if (!all_finite(next)) {
    run.state.status = Status::non_finite;
    return;
  }
  // The sign before the next crossing (only the affine body has crossings, and L in its state).
  bool positive = run.scene.body.model == BodyModel::affine && det_of(run, run.state.y) > 0.0;
  const std::size_t room = kMaxDegenerateEvents - std::min(kMaxDegenerateEvents, run.events.size());
  const std::vector<double> crossings =
      degenerate_times(*run.exact, run.state.t - run.segment_start, t_end - run.segment_start, room + 1);
  for (std::size_t i = 0; i < crossings.size(); ++i) {
    const double t = run.segment_start + crossings[i];
    if (i == room && run.scene.on_degenerate != OnDegenerate::stop) {
      // One crossing more than a run keeps: the run stops before it (engine/state.h).
      const State before = at(std::nextafter(t, run.state.t));
      if (before.t > run.state.t && all_finite(before)) run.state = before;
      run.state.status = Status::too_many_events;
      return;
    }
    if (run.scene.on_degenerate != OnDegenerate::stop) {
      add_event(run.events, t);
      positive = !positive;
      continue;
    }
    // The stop lands just before the crossing, where det L keeps its sign, and lists the event at
    // its own time (≤ ~1e-15 t before the root).
    State stop = at(t);
    for (int k = 0; k < 50 && !det_on_side(run, stop.y, positive); ++k) {
      const double t_before = t - std::ldexp(1e-15 * std::max(1.0, std::abs(t)), k);
      if (!(t_before > run.state.t)) break;
      stop = at(t_before);
    }
    add_event(run.events, stop.t);
    run.state = stop;
    run.state.status = Status::degenerate_frame;
    return;
  }
  run.state = next;
  if (!run.exact_evaluated) ++run.steps;  // one per segment: the same however the run was advanced
  run.exact_evaluated = true;
}

enum class Mode {
  sequence,  // only whole steps that end before t_end: the run's own step sequence
  land,      // the last step cut to end exactly at t_end
};

// Steps `p` toward t_end; every attempt uses one of `attempts`. False when they ran out first.
bool step_toward(Simulation& run, StepPoint& p, double t_end, Mode mode, std::uint64_t& attempts,
                 std::vector<DegenerateEvent>& events) {
  State& state = p.state;
  const Scene& scene = run.scene;
  const bool adaptive = run.integrator->info().adaptive;
  const bool affine = scene.body.model == BodyModel::affine;
  const bool sequence = mode == Mode::sequence;
  const double tolerance = scene.integrator.tolerance;
  const StepProblem f{scene, state.chart, run.field.get()};
  Coords increment, y_next;
  if (p.carry.size() != state.y.size()) p.carry = Coords::Zero(state.y.size());
  while (state.status == Status::ok && state.t < t_end) {
    const double remaining = (t_end - state.t) - p.t_carry;  // the true elapsed time is t + carry
    const double h_planned = adaptive ? p.h_next : scene.integrator.dt;
    const bool last = h_planned >= remaining;
    if (last && sequence) return true;
    if (attempts == 0) return false;
    --attempts;
    const double h = last ? remaining : h_planned;

    StepResult result = run.integrator->try_step(f, state.y, h, tolerance, increment);
    // Compensated summation: the carry holds the low-order bits lost in earlier additions.
    const Coords corrected = increment + p.carry;
    y_next = state.y + corrected;
    const bool finite = all_finite(y_next);
    if (!result.accepted || !finite) {
      if (sequence) ++run.rejected;
      if (!adaptive) {
        state.status = finite ? Status::step_failed : Status::non_finite;
        return true;
      }
      const double h_min = 1e-14 * std::max(1.0, std::abs(state.t));
      p.h_next = finite ? result.h_next : 0.25 * h;
      if (!(p.h_next > h_min)) {
        state.status = finite ? Status::step_failed : Status::non_finite;
        return true;
      }
      continue;
    }

    if (affine && (det_of(run, state.y) > 0.0) != (det_of(run, y_next) > 0.0)) {
      const Crossing crossing = locate_degenerate(run, *run.integrator, f, state.y, h, tolerance);
      const bool stop = scene.on_degenerate == OnDegenerate::stop;
      // A stop reports the event at its own time (≤ 1e-14 h before the crossing's midpoint), so
      // the stopped sample lists it.
      add_event(events, state.t + (stop ? crossing.before : crossing.t));
      if (stop) {
        // The stop lands on the crossing (its last good side), not on the step before it: the
        // stopped sample's time is the event's, whatever the sampling and the integrator.
        if (all_finite(crossing.y)) {
          state.y = crossing.y;
          state.t += crossing.before;
          p.carry.setZero(state.y.size());
          p.t_carry = 0.0;
        }
        state.status = Status::degenerate_frame;
        return true;
      }
    }
    p.carry = corrected - (y_next - state.y);
    state.y = y_next;
    if (run.embedded && run.embedded->project) {  // back onto F = 0 (its bits are new: no carry)
      project_state(*run.embedded, state.y);
      p.carry.setZero(state.y.size());
    }
    // Time is summed with compensation too: over millions of steps a plain sum drifts by ~Nεt,
    // and the last step, cut to land on t_end, would absorb that drift as a phase error.
    if (last) {
      state.t = t_end;
      p.t_carry = 0.0;
    } else {
      const double dt = h + p.t_carry, t_new = state.t + dt;
      p.t_carry = dt - (t_new - state.t);
      state.t = t_new;
    }
    // A step shortened to land on t_end says nothing about the step the solution allows.
    if (adaptive) p.h_next = (last && h < h_planned) ? h_planned : result.h_next;
    const State before_chart_move = state;
    if (!run.embedded && maintain_chart(scene, state)) {
      if (!all_finite(state)) {
        state = before_chart_move;
        state.status = Status::non_finite;
        return true;
      }
      if (sequence) ++run.recentres;
      p.carry.setZero(state.y.size());  // the new chart's coordinates start exact
    }
    if (sequence && run.monitor) {
      if (std::optional<State> stop = run.monitor->step(run, state)) {
        // A terminal event: the sequence ends on the crossing (as a det L stop does).
        state = std::move(*stop);
        p.carry.setZero(state.y.size());
        p.t_carry = 0.0;
        ++run.steps;
        return true;
      }
    }
    if (sequence && ++run.steps % kCheckEvery == 0) {
      if (const Status trouble = health(run, state); trouble != Status::ok) {
        p = run.checked;
        p.state.status = trouble;
        run.monitor = run.monitor_checked;
        return true;
      }
      run.checked = p;
      run.monitor_checked = run.monitor;
    }
  }
  return true;
}

// Stops the run on `trouble` at the last good state: the later of the state asked for before
// (checked when it was reached) and the sequence's last good point.
void stop_at_last_good(Simulation& run, const State& before, Status trouble) {
  // The sequence's point may be unchecked whatever stopped it (a non-finite step after a step that
  // blew the state up to 1e131, whose energy is already inf − inf): check it now.
  if (health(run, run.grid.state) != Status::ok) run.grid = run.checked;
  run.grid.state.status = trouble;
  run.state = before.t > run.grid.state.t ? before : run.grid.state;
  run.state.status = trouble;
  run.view_events.clear();
}

// The sequence up to t_end, then the cut step from it to t_end (recomputed on every call).
bool advance_steps(Simulation& run, double t_end, std::uint64_t& attempts) {
  const State before = run.state;
  const std::vector<DegenerateEvent> view_events_before = std::move(run.view_events);
  run.view_events.clear();
  const bool sequence_done = step_toward(run, run.grid, t_end, Mode::sequence, attempts, run.events);
  const Status sequence_status = run.grid.state.status;
  if (sequence_status == Status::degenerate_frame || sequence_status == Status::event_stop) {
    run.state = run.grid.state;
    return true;
  }
  if (sequence_status != Status::ok) {
    stop_at_last_good(run, before, sequence_status);
    return true;
  }
  if (!sequence_done) {
    run.state = run.grid.state.t > before.t ? run.grid.state : before;
    if (run.state.t == before.t) run.view_events = view_events_before;
    return false;
  }
  StepPoint view = run.grid;
  if (!step_toward(run, view, t_end, Mode::land, attempts, run.view_events)) {
    run.state = run.grid.state.t > before.t ? run.grid.state : before;
    run.view_events = run.state.t == before.t ? view_events_before : std::vector<DegenerateEvent>{};
    return false;
  }
  if (view.state.status == Status::degenerate_frame) {
    // The crossing stops the run: the point before it becomes the sequence's last.
    for (const DegenerateEvent& e : run.view_events) add_event(run.events, e.t);
    run.view_events.clear();
    run.grid = view;
    run.state = view.state;
    return true;
  }
  Status trouble = view.state.status;
  if (trouble == Status::ok) trouble = health(run, view.state);
  if (trouble != Status::ok) {
    stop_at_last_good(run, before, trouble);
    return true;
  }
  run.state = view.state;
  return true;
}

// One body (not its companions), without its monitor.
bool advance_body_only(Simulation& run, double t_end, std::uint64_t& attempts) {
  if (run.state.status != Status::ok || !(t_end > run.state.t)) return true;
  if (!run.exact) return advance_steps(run, t_end, attempts);
  if (attempts == 0) return false;
  --attempts;
  if (!run.exact_check.start_ok) {  // the closed form does not reproduce its own start
    run.state.status = Status::inconsistent;
    return true;
  }
  const State before = run.state;
  advance_exact(run, t_end);
  if ((run.state.status == Status::ok || run.state.status == Status::degenerate_frame) &&
      !exact_consistent(run, run.state)) {
    // The last consistent time, by bisection on the closed form (before passed the check).
    double lo = before.t, hi = run.state.t;
    for (int i = 0; i < 100 && hi - lo > 1e-12 * std::max(1.0, std::abs(hi)); ++i) {
      const double mid = 0.5 * (lo + hi);
      const State s = exact_at(run, mid);
      if (all_finite(s) && exact_consistent(run, s))
        lo = mid;
      else
        hi = mid;
    }
    run.state = lo > before.t ? exact_at(run, lo) : before;
    run.state.status = Status::inconsistent;
    std::erase_if(run.events, [&](const DegenerateEvent& e) { return e.t > run.state.t; });
    return true;
  }
  if (run.state.status == Status::ok) {
    if (const Status trouble = health(run, run.state); trouble != Status::ok) {
      run.state = before;
      run.state.status = trouble;
    }
  }
  return true;
}

// The closed form has no steps: the monitor is fed its points segment_start + k·dt (the scene's
// dt), so what it reports does not depend on the sampling either.
void monitor_closed_form(Simulation& run) {
  RunMonitor& m = *run.monitor;
  const double dt = run.scene.integrator.dt;
  for (;;) {
    const double t = run.segment_start + static_cast<double>(m.closed_form_points + 1) * dt;
    if (!(t <= run.state.t) || m.stopped()) return;
    ++m.closed_form_points;
    State point = exact_at(run, t);
    if (!all_finite(point)) return;
    if (std::optional<State> stop = m.step(run, point)) {
      run.state = std::move(*stop);
      std::erase_if(run.events, [&](const DegenerateEvent& e) { return e.t > run.state.t; });
      return;
    }
  }
}

// What taking steps of the sequence changes in a run, to undo a trial of them.
struct SequenceSnapshot {
  StepPoint grid, checked;
  std::optional<RunMonitor> monitor, monitor_checked;
  std::uint64_t steps, rejected, recentres;
  std::vector<DegenerateEvent> events;
};
SequenceSnapshot snapshot(const Simulation& run) {
  return {run.grid,  run.checked,  run.monitor,   run.monitor_checked,
          run.steps, run.rejected, run.recentres, run.events};
}
void restore(Simulation& run, SequenceSnapshot&& s) {
  run.grid = std::move(s.grid);
  run.checked = std::move(s.checked);
  run.monitor = std::move(s.monitor);
  run.monitor_checked = std::move(s.monitor_checked);
  std::tie(run.steps, run.rejected, run.recentres) = std::tie(s.steps, s.rejected, s.recentres);
  run.events = std::move(s.events);
}

// A terminal event between the sequence's last point and the state asked for stops the run there
// (the sample then shows it, as a det L stop between samples does). It is located on the run's own
// steps, never in the cut step to the sample, so that where the run is sampled cannot move it: the
// sequence's next steps (or the closed form's next points) are taken on a copy, and kept only when
// they reach the event before the state's time.
void stop_on_event_before_state(Simulation& run, std::uint64_t& attempts) {
  const bool terminal = std::any_of(run.monitor->spec().events.begin(), run.monitor->spec().events.end(),
                                    [](const EventSpec& e) { return e.stop > 0; });
  if (!terminal || run.state.status != Status::ok || !(run.state.t > run.monitor->last().t)) return;
  {
    RunMonitor trial = *run.monitor;
    if (!trial.step(run, run.state)) return;  // no crossing before the state: nothing to do
  }
  const double t_state = run.state.t;
  const auto stopped_here = [&](const State& stop) {
    run.state = stop;
    std::erase_if(run.events, [&](const DegenerateEvent& e) { return e.t > run.state.t; });
    run.view_events.clear();
  };
  if (run.exact) {
    RunMonitor m = *run.monitor;
    const double dt = run.scene.integrator.dt;
    for (std::uint64_t k = m.closed_form_points + 1;; ++k) {
      const double t = run.segment_start + static_cast<double>(k) * dt;
      if (t - dt >= t_state) return;
      m.closed_form_points = k;
      State point = exact_at(run, t);
      if (!all_finite(point)) return;
      if (std::optional<State> stop = m.step(run, point)) {
        if (stop->t > t_state) return;
        run.monitor = std::move(m);
        stopped_here(*stop);
        return;
      }
    }
  }
  // Steppers: the sequence's next whole steps, undone unless they reach the event.
  SequenceSnapshot before = snapshot(run);
  StepPoint p = run.grid;
  while (p.state.status == Status::ok && p.state.t <= t_state && attempts > 0) {
    const double h = run.integrator->info().adaptive ? p.h_next : run.scene.integrator.dt;
    step_toward(run, p, p.state.t + 2.0 * h, Mode::sequence, attempts, run.events);
  }
  if (p.state.status == Status::event_stop && p.state.t <= t_state) {
    run.grid = p;
    stopped_here(p.state);
    return;
  }
  restore(run, std::move(before));
}

// One body (not its companions), with its monitor.
bool advance_body(Simulation& run, double t_end, std::uint64_t& attempts) {
  if (run.monitor && run.exact) {
    // The closed form's monitor looks at its points every dt (monitor_closed_form), each one of
    // `attempts`: a jump over 10⁹ of them is taken in slices that --max-steps and the callers' clocks
    // bound (the state at any t is the closed form's, however it was reached).
    if (attempts == 0) return false;
    const std::uint64_t before = run.monitor->closed_form_points;
    const double reach = run.segment_start + (static_cast<double>(before) + static_cast<double>(attempts)) *
                                                 run.scene.integrator.dt;
    const bool limited = reach < t_end;
    const bool done = advance_body_only(run, limited ? reach : t_end, attempts);
    monitor_closed_form(run);
    attempts -= std::min(attempts, run.monitor->closed_form_points - before);
    stop_on_event_before_state(run, attempts);
    if (limited && run.state.status == Status::ok) return false;
    return done;
  }
  const bool done = advance_body_only(run, t_end, attempts);
  if (run.monitor) stop_on_event_before_state(run, attempts);
  return done;
}

}  // namespace

bool advance_within(Simulation& run, double t_end, std::uint64_t& attempts) {
  if (!advance_body(run, t_end, attempts)) return false;
  // A run that stopped (an event's stop, a failure) ends there: its companions are taken to its
  // last time, not to the time asked, so their last record does not depend on the sampling.
  const bool stopped = run.state.status != Status::ok;
  const double companions_end = stopped ? std::min(t_end, run.state.t) : t_end;
  for (Simulation& companion : run.companions) {
    if (stopped && companion.state.t >= companions_end) continue;
    if (!advance_body(companion, companions_end, attempts)) return false;
  }
  return true;
}

std::vector<DegenerateEvent> events_after(const Simulation& run, double after) {
  std::vector<DegenerateEvent> list;
  for (const auto* events : {&run.events, &run.view_events})
    for (const DegenerateEvent& e : *events)
      if (e.t > after && e.t <= run.state.t) add_event(list, e.t);
  return list;
}

State state_after(const Simulation& run, const State& from, double tau) {
  if (run.exact) return exact_at(run, from.t + tau);
  const StepProblem f{run.scene, from.chart, run.field.get()};
  Coords increment;
  run.integrator->try_step(f, from.y, tau, run.scene.integrator.tolerance, increment);
  State s = from;
  s.y += increment;
  s.t = from.t + tau;
  return s;
}

void watch(Simulation& run, MonitorSpec spec) {
  run.monitor.emplace(std::move(spec), run);
  run.monitor_checked = run.monitor;
}

std::vector<double> monitor_values(const Simulation& run) {
  if (!run.monitor) return {};
  // The cut step to the state is added to a copy: the sequence's monitor goes on unchanged. A run
  // stopped by trouble reports up to the last good point of its sequence.
  const Status s = run.state.status;
  if (s != Status::ok && s != Status::degenerate_frame && s != Status::event_stop)
    return run.monitor->values();
  RunMonitor through = *run.monitor;
  through.step(run, run.state);
  return through.values();
}

bool advance_to(Simulation& run, double t_end, std::uint64_t max_attempts) {
  return advance_within(run, t_end, max_attempts);
}

bool dialled(const Surface& before, const Surface& after) {
  return after.curvature_given && (before.kind != after.kind || before.radius != after.radius);
}

Vec3 carried_position(const Surface& before, const Surface& after, const Vec3& X) {
  if (dialled(before, after)) {
    const PolarCoordinates pc = polar_coordinates(before, X);
    return chart_point(after, pc.r, pc.phi).X;
  }
  if (!offers(before, Offer::zero_curvature) && after.radius != before.radius)
    return X * (after.radius / before.radius);
  return X;
}

void retune(Simulation& run, const Scene& next) {
  for (std::size_t i = 0; i < run.companions.size() && i < next.companions.size(); ++i)
    retune(run.companions[i], companion_scene(next, i));
  // Summaries describe one scene's run (simulate and sweeps never retune): a change ends them.
  run.monitor.reset();
  run.monitor_checked.reset();
  // The state asked for becomes a point of the step sequence: a change is hit exactly. New
  // parameters may cure what stopped the run (a step beyond stability): it continues.
  State here = run.state;
  here.status = Status::ok;
  const Surface& before = run.scene.surface;
  if (chart_free(before)) {
    // The chart-free state keeps X, V, e_A and W_A (so the velocities and frame rates); the rigid
    // body's spin follows its rate s/I with the new inertia I = |e₁|² tr J.
    // An orbit-only state (embedded_run.h) starts its closed form again here, with the new internal
    // potential and inertia; a change that makes the internal motion need stepping unfolds it.
    if (run.embedded->rigid)
      here.y(embedded::spin) *=
          inertia_of(next.body).matrix.trace() / run.embedded->body.inertia.matrix.trace();
    else
      here.y = embedded_layout(EmbeddedScene(next), *run.embedded, here.y);
    // A formula surface that changed (its text or a parameter): the body carried onto the new one
    // from where it is (Newton along ∇F, then V, e_A, W_A onto the new tangent plane).
    if (offers(next.surface, Offer::formula) && (next.surface.F != before.F || next.surface.z != before.z ||
                                                 next.surface.parameters != before.parameters))
      carry_onto_surface(EmbeddedScene(next), here.y);
  } else if (dialled(before, next.surface)) {
    // The same geodesic polar place (r, φ), velocity and frame in (E₁, E₂) on the new surface.
    const GlobalBody g = global_body(run.scene, here);
    PlacedBody p{g.r, g.phi, g.r_dot, g.S * g.phi_dot, g.L, g.M, 0.0};
    if (g.at_pole) {  // the frame L and M refer to (the chart's F₁ carried to O) stands in for E₁
      const BodyKinematics body = chart_kinematics(run.scene, here.y);
      const Vec3 F1 = here.chart.A * body.F1, F2 = rotate_quarter(before, g.X, F1);
      p.phi = std::atan2(F1.y(), F1.x());
      p.v_r = dot(before, g.V, F1);
      p.v_phi = dot(before, g.V, F2);
    }
    p.spin = spin_from_rate(inertia_of(next.body), p.L, p.M);
    const State placed = place_body(next, p);
    here.chart = placed.chart;
    here.y = placed.y;
  } else {
    BodyKinematics body = chart_kinematics(run.scene, here.y);
    if (!offers(before, Offer::zero_curvature) && next.surface.radius != before.radius)
      body.X *= next.surface.radius / before.radius;  // the same place on the surface
    // Velocities and frame rates are kept; the spin follows from the new inertia (s = tr((εL)ᵀMJ)).
    body.spin = spin_from_rate(inertia_of(next.body), body.L, body.M);
    here.y = chart_coords(next, body);
    if (!chart_well_conditioned(next.surface, here.y[coord::r])) recentre(next, here);
  }

  const bool same_method = resolve_integrator(next) == run.info->name &&
                           auto_adaptive_split6(next) == auto_adaptive_split6(run.scene) &&
                           next.integrator.tolerance == run.scene.integrator.tolerance;
  const double h_next = same_method && run.info->adaptive ? run.grid.h_next : next.integrator.dt;
  run.scene = next;
  use_surface(run);
  if (!same_method || !run.integrator) use_integrator(run);
  run.state = here;
  run.view_events.clear();
  run.exact_evaluated = false;
  measure_energy_from_here(run);
  if (!run.integrator) prepare_exact(run, here, false);
  run.grid = {here, Coords::Zero(here.y.size()), 0.0, h_next};
  run.checked = run.grid;
}

}  // namespace spinfold
