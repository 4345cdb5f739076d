// Action variables and frequencies (engine/actions.h, physics.md §8.10, §14): constant along runs,
// H recomputed from them, and the frequencies against periods measured on long integrations.
#include "engine/actions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/integrator.h"
#include "engine/invariants.h"
#include "test_support.h"

namespace spinfold {
namespace {

// physics.md W5 under dop853 at 1e-13.
Scene w5_scene() {
  Scene s = test::w5_scene();
  s.integrator = {"dop853", 0.01, 1e-13};
  return s;
}

// H², radial + abc, spin large enough for a bounded orbit (s² > 2mR²E_orb).
Scene bounded_h2_scene() {
  Scene s;
  s.surface = {SurfaceKind::pseudosphere, 1.0};
  s.body = {1.0, 0.3, BodyModel::affine};
  s.potential.radial = RadialPotential{0.05};
  s.potential.deformation = AbcPotential{0.02, 0.1, 0.4};
  s.initial = {1.2, 0.0, 0.3, -0.4, 1.4, 0.6, 0.1, 0.3, 2.0, -0.2, 0.1, -0.05};
  s.integrator = {"dop853", 0.01, 1e-13};
  return s;
}

// A rigid body spinning on S² without potential (W3): r(t) from the scene's pole oscillates.
Scene rigid_sphere_scene() {
  Scene s = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  test::set_rigid_motion(s, 0.5, 0.4, 1.0);
  return s;
}

std::vector<Scene> separable_scenes() {
  return {w5_scene(), bounded_h2_scene(), rigid_sphere_scene()};
}

TEST(Actions, DefinedOnTheSeparableScenesAndConstantAlongRuns) {
  for (const Scene& scene : separable_scenes()) {
    ASSERT_FALSE(actions_unsupported_reason(scene).has_value());
    Simulation run = start_simulation(scene);
    const ActionVariables a0 = action_variables(scene, run.state);
    ASSERT_TRUE(a0.J_r && a0.J_phi && a0.J_alpha && a0.nu_r);
    if (scene.body.model == BodyModel::affine) {
      ASSERT_TRUE(a0.J_x && a0.J_y && a0.J_beta && a0.nu_x && a0.nu_y);
      EXPECT_TRUE(a0.undefined.empty());
    }
    EXPECT_GT(*a0.J_r, 0.0);
    for (int k = 1; k <= 20; ++k) {
      advance_to(run, 2.5 * k);
      ASSERT_EQ(run.state.status, Status::ok);
      const ActionVariables a = action_variables(scene, run.state);
      const double scale = std::abs(*a0.J_phi) + std::abs(*a0.J_alpha) + std::abs(*a0.J_r);
      EXPECT_NEAR(*a.J_r, *a0.J_r, 1e-9 * scale) << "t " << run.state.t;
      EXPECT_NEAR(*a.J_phi, *a0.J_phi, 1e-9 * scale);
      EXPECT_NEAR(*a.J_alpha, *a0.J_alpha, 1e-9 * scale);
      if (a0.J_x) {
        EXPECT_NEAR(*a.J_x, *a0.J_x, 1e-9 * (std::abs(*a0.J_x) + 1.0));
        EXPECT_NEAR(*a.J_y, *a0.J_y, 1e-9 * (std::abs(*a0.J_y) + 1.0));
        EXPECT_NEAR(*a.J_beta, *a0.J_beta, 1e-9 * scale);
      }
    }
  }
}

TEST(Actions, EnergyFromTheActionsIsH) {
  for (const Scene& scene : separable_scenes()) {
    const State start = initial_state(scene);
    const std::optional<double> E = energy_from_actions(scene, action_variables(scene, start));
    ASSERT_TRUE(E.has_value());
    EXPECT_NEAR(*E, energy(scene, start), 1e-13 * std::abs(energy(scene, start)));
  }
  // And without a radial potential (k = 0) on both surfaces.
  for (const SurfaceKind kind : {SurfaceKind::sphere, SurfaceKind::pseudosphere}) {
    Scene scene = offers(kind, Offer::positive_curvature) ? w5_scene() : bounded_h2_scene();
    scene.potential.radial.reset();
    const State start = initial_state(scene);
    const ActionVariables a = action_variables(scene, start);
    ASSERT_TRUE(a.J_r.has_value()) << static_cast<int>(kind);
    EXPECT_NEAR(*energy_from_actions(scene, a), energy(scene, start), 1e-13 * std::abs(energy(scene, start)));
  }
}

// Integrates from `from` for time h with DOP853 at tolerance 1e-14 in its chart (no re-centring:
// h is a fraction of a period).
State flow(const Scene& scene, const State& from, double h) {
  auto integrator = make_dop853();
  State s = from;
  double done = 0.0, step = std::min(h, 0.01);
  Coords increment;
  while (done < h) {
    step = std::min(step, h - done);
    const StepResult r = integrator->try_step(StepProblem{scene, s.chart}, s.y, step, 1e-14, increment);
    if (r.accepted) {
      s.y += increment;
      done += step;
    }
    step = r.h_next;
  }
  s.t = from.t + h;
  return s;
}

// The mean period of g's downward zero crossings over `cycles` cycles: the first and the last
// crossing located by bisection (the ones between are only counted).
double measured_period(const Scene& scene, const std::function<double(const State&)>& g, double expected,
                       int cycles) {
  Simulation run = start_simulation(scene);
  const double dt = expected / 16.0;
  int count = 0;
  double first = 0.0, last = 0.0;
  double g_prev = g(run.state);
  while (count <= cycles) {
    const State before = run.state;
    advance_to(run, run.state.t + dt);
    EXPECT_EQ(run.state.status, Status::ok);
    if (run.state.status != Status::ok) return 0.0;
    const double g_now = g(run.state);
    if (g_prev > 0.0 && g_now <= 0.0) {
      if (count == 0 || count == cycles) {
        double lo = 0.0, hi = run.state.t - before.t;
        for (int i = 0; i < 60 && hi - lo > 1e-15 * run.state.t; ++i) {
          const double mid = 0.5 * (lo + hi);
          (g(flow(scene, before, mid)) > 0.0 ? lo : hi) = mid;
        }
        (count == 0 ? first : last) = before.t + 0.5 * (lo + hi);
      }
      ++count;
    }
    g_prev = g_now;
  }
  return (last - first) / cycles;
}

double r_rate(const Scene& scene, const State& s) {
  return global_body(scene, s).r_dot;
}
// d(x²)/dt ∝ u u_M + v v_M, d(y²)/dt ∝ p p_M + q q_M (the drive only turns L, physics.md §2).
double x2_rate(const Scene& scene, const State& s) {
  const InternalState in = internal_state(scene, s.y);
  return (in.L(0, 0) - in.L(1, 1)) * (in.M(0, 0) - in.M(1, 1)) +
         (in.L(0, 1) + in.L(1, 0)) * (in.M(0, 1) + in.M(1, 0));
}
double y2_rate(const Scene& scene, const State& s) {
  const InternalState in = internal_state(scene, s.y);
  return (in.L(0, 0) + in.L(1, 1)) * (in.M(0, 0) + in.M(1, 1)) +
         (in.L(1, 0) - in.L(0, 1)) * (in.M(1, 0) - in.M(0, 1));
}

TEST(Actions, FrequenciesPredictTheMeasuredPeriods) {
  for (const Scene& scene : {w5_scene(), bounded_h2_scene()}) {
    const ActionVariables a = action_variables(scene, initial_state(scene));
    const double T_r = 1.0 / *a.nu_r, T_x = 1.0 / *a.nu_x, T_y = 1.0 / *a.nu_y;
    const auto r = [&](const State& s) { return r_rate(scene, s); };
    const auto x = [&](const State& s) { return x2_rate(scene, s); };
    const auto y = [&](const State& s) { return y2_rate(scene, s); };
    EXPECT_NEAR(measured_period(scene, r, T_r, 10) / T_r, 1.0, 1e-8) << "r, T " << T_r;
    EXPECT_NEAR(measured_period(scene, x, T_x, 20) / T_x, 1.0, 1e-8) << "x^2, T " << T_x;
    EXPECT_NEAR(measured_period(scene, y, T_y, 20) / T_y, 1.0, 1e-8) << "y^2, T " << T_y;
  }
}

// φ advances by 2πν_φ/ν_r per period of r: measured over 20 periods in the scene's chart (which
// these runs never leave, so φ is continuous).
TEST(Actions, PrecessionFrequencyPredictsTheAdvanceOfPhi) {
  for (const Scene& scene : {w5_scene(), bounded_h2_scene()}) {
    Simulation run = start_simulation(scene);
    const ActionVariables a = action_variables(scene, run.state);
    ASSERT_TRUE(a.nu_phi && a.nu_r);
    const double phi0 = run.state.y[coord::phi], periods = 20.0;
    advance_to(run, periods / *a.nu_r);
    ASSERT_TRUE(run.state.chart.global);
    const double advance = run.state.y[coord::phi] - phi0,
                 predicted = 2.0 * std::numbers::pi * periods * *a.nu_phi / *a.nu_r;
    EXPECT_NEAR(advance / predicted, 1.0, 1e-8) << advance << " vs " << predicted;
  }
}

TEST(Actions, UndefinedValuesCarryAReason) {
  // H² with too little spin: the orbit is unbounded.
  Scene unbounded = bounded_h2_scene();
  unbounded.initial.alpha_dot = 0.0;
  unbounded.initial.r_dot = 1.0;
  const ActionVariables a = action_variables(unbounded, initial_state(unbounded));
  EXPECT_FALSE(a.J_r.has_value());
  EXPECT_FALSE(a.nu_r.has_value());
  EXPECT_TRUE(a.J_phi.has_value());
  EXPECT_FALSE(energy_from_actions(unbounded, a).has_value());
  bool named = false;
  for (const UndefinedValue& u : a.undefined)
    named |= u.field == "J_r" && u.reason.find("unbounded") != std::string::npos;
  EXPECT_TRUE(named);
  // No deformation potential: x² and y² are not bounded.
  Scene free = w5_scene();
  free.potential.deformation = std::monostate{};
  const ActionVariables b = action_variables(free, initial_state(free));
  EXPECT_TRUE(b.J_r.has_value());
  EXPECT_FALSE(b.J_x.has_value());
  EXPECT_EQ(b.undefined.size(), 4u);  // J_x, J_y, nu_x, nu_y
  // Not separable: the reason says why.
  Scene polar = w5_scene();
  polar.potential.deformation = PolarPotential{0.05, -1.0, PolarForm::cot2};
  EXPECT_NE(actions_unsupported_reason(polar)->find("polar"), std::string::npos);
  Scene anisotropic = w5_scene();
  anisotropic.body.inertia_matrix = InertiaMatrix{0.3, 0.08, 0.08, 0.15};
  EXPECT_NE(actions_unsupported_reason(anisotropic)->find("anisotropic"), std::string::npos);
  Scene plane = w5_scene();
  plane.surface.kind = SurfaceKind::plane;
  EXPECT_TRUE(actions_unsupported_reason(plane).has_value());
}

}  // namespace
}  // namespace spinfold
