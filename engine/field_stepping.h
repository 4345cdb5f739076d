// A bare loop that steps a vector field given as a function (StepProblem::field) with a catalog
// integrator to a time: the chart-free equations of a surface whose curvature varies, before a
// Simulation runs them (issue 33), and the baseline the surface benchmarks time against Odeint.
// No chart, no events, no compensated summation: Simulation's loop (simulation.h) is the run's.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>

#include "engine/integrator.h"

namespace spinfold {

struct FieldRun {
  Coords y;                    // the state at t_end (or where it stopped)
  std::uint64_t steps = 0;     // accepted steps
  std::uint64_t rejected = 0;  // rejected attempts
  bool ok = true;              // false: the step size underflowed or a value was not finite
};

// Steps y from 0 to t_end: fixed steps of h, or for an adaptive method steps it chooses at
// `tolerance` from a first trial h [time].
// `after_step`, when given, is applied to the state after each accepted step (a projection back
// onto the constraints: engine/constraint_projection.h).
inline FieldRun step_field(Integrator& integrator, const StepProblem& problem, Coords y, double t_end,
                           double h, double tolerance,
                           const std::function<void(Coords&)>& after_step = nullptr) {
  FieldRun run;
  const bool adaptive = integrator.info().adaptive;
  Coords increment;
  double t = 0.0;
  while (t < t_end) {
    const double step = std::min(h, t_end - t);
    const StepResult r = integrator.try_step(problem, y, step, tolerance, increment);
    if (adaptive) h = r.h_next;
    if (!r.accepted || !increment.allFinite()) {
      ++run.rejected;
      if (!adaptive || !(h > 1e-14 * std::max(1.0, t))) {
        run.ok = false;
        break;
      }
      continue;
    }
    y += increment;
    if (after_step) after_step(y);
    t += step;
    ++run.steps;
  }
  run.y = y;
  return run;
}

}  // namespace spinfold
