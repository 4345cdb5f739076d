// Surfaces whose curvature varies (issue 33): run time against error on a torus scene for the
// engine's stepping (the chart-free equations, engine/embedded_dynamics.h, through a catalog
// integrator), the same stepping only the orbit (the internal motion in closed form: engine/embedded_run.h),
// and Boost.Odeint's steppers on the same equations.
#pragma once

namespace spinfold::bench {

struct SurfacesBenchOptions {
  double t_end = 20.0;          // simulated time
  double target_error = 1e-10;  // the error at which methods are compared
  int repeats = 3;              // timings per point (median)
};

// Prints each method's work-precision points and the cheapest run within the target error of each,
// with the ratio of Odeint's best to the engine's best. Returns 0.
int run_surfaces_bench(const SurfacesBenchOptions& options);

}  // namespace spinfold::bench
