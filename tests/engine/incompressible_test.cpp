// The incompressible body (physics.md §15): det L held at λμ by RATTLE inside split4/split6. Its
// residual stays at round-off, the compositions have their orders, energy and spin behave as for a
// symplectic method, and the other integrators are refused with a reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/exact_solution.h"
#include "engine/integrator.h"
#include "engine/invariants.h"
#include "engine/potentials.h"
#include "engine/validation.h"
#include "engine/worked_examples.h"
#include "test_support.h"

namespace spinfold {
namespace {

// A breathing ellipse on S² under radial + abc potentials, det L = 1.1·0.6 = 0.66, λ̇μ + λμ̇ = 0.
Scene incompressible_scene() {
  Scene s = incompressible_w5_scene();
  s.integrator = {"split6", 0.05, 1e-10};
  return s;
}

double det_of(const Scene& scene, const State& s) {
  return internal_state(scene, s.y).L.determinant();
}

double state_distance(const Scene& scene, const State& a, const State& b) {
  const EmbeddedBody x = global_embedding(scene, a), y = global_embedding(scene, b);
  return std::max({(x.X - y.X).norm(), (x.V - y.V).norm(), (x.e[0] - y.e[0]).norm(), (x.e[1] - y.e[1]).norm(),
                   (x.W[0] - y.W[0]).norm(), (x.W[1] - y.W[1]).norm()});
}

TEST(Incompressible, DetLStaysAtItsInitialValueToRoundOff) {
  for (const char* name : {"split4", "split6"}) {
    Scene scene = incompressible_scene();
    scene.integrator.name = name;
    ASSERT_TRUE(validate_scene(scene).empty());
    Simulation run = start_simulation(scene);
    const double c = scene.initial.lambda * scene.initial.mu;
    const double s0 = spin(scene, run.state), H0 = energy(scene, run.state);
    double worst = 0.0, dH[2] = {0.0, 0.0}, x2_min = 1e300, x2_max = 0.0;
    for (int k = 1; k <= 200; ++k) {
      advance_to(run, 0.5 * k);
      ASSERT_EQ(run.state.status, Status::ok) << name;
      worst = std::max(worst, std::abs(det_of(scene, run.state) - c));
      EXPECT_NEAR(spin(scene, run.state), s0, 1e-12) << name;  // left-invariant: exact up to round-off
      dH[k <= 100 ? 0 : 1] =
          std::max(dH[k <= 100 ? 0 : 1], std::abs(energy(scene, run.state) - H0) / std::abs(H0));
      const double x2 = deformation_invariants(internal_state(scene, run.state.y).L).a;
      x2_min = std::min(x2_min, x2);
      x2_max = std::max(x2_max, x2);
    }
    EXPECT_LT(worst, 1e-14) << name << ": det L residual over t = 100";
    EXPECT_LT(dH[1], 1e-5) << name;
    EXPECT_LT(dH[1], 2.0 * dH[0] + 1e-13) << name << ": the energy error drifts";
    EXPECT_GT(x2_max - x2_min, 0.05) << name << ": the body does deform";
  }
}

TEST(Incompressible, CompositionsHaveTheirOrders) {
  Scene scene = incompressible_scene();
  const double t_end = 4.0;
  // The reference: split6 at a step far below the ones measured.
  scene.integrator = {"split6", 0.002, 1e-10};
  const State reference = test::run_to(scene, t_end).state;
  for (const char* name : {"split4", "split6"}) {
    const int order = find_integrator(name)->info.order;
    double errors[3];
    const double h = order >= 6 ? 0.4 : 0.2;
    for (int i = 0; i < 3; ++i) {
      scene.integrator = {name, h / (1 << i), 1e-10};
      errors[i] = state_distance(scene, test::run_to(scene, t_end).state, reference);
    }
    EXPECT_GT(errors[2], 1e-12) << name;
    EXPECT_NEAR(0.5 * std::log2(errors[0] / errors[2]), order, 0.35)
        << name << " errors " << errors[0] << ", " << errors[1] << ", " << errors[2];
  }
}

TEST(Incompressible, OtherIntegratorsAreRefusedWithAReason) {
  for (const CatalogEntry& e : integrator_catalog()) {
    Scene scene = incompressible_scene();
    scene.integrator.name = std::string(e.info.name);
    bool refused = false;
    for (const FieldError& error : validate_scene(scene))
      refused |= error.field == "integrator.name" && !error.reason.empty();
    EXPECT_EQ(refused, e.info.name != "split4" && e.info.name != "split6") << e.info.name;
  }
  Scene scene = incompressible_scene();
  scene.integrator.name = "auto";
  EXPECT_EQ(resolve_integrator(scene), "split6");
  EXPECT_TRUE(exact_unsupported_reason(scene).has_value());
}

// `auto` runs split6 with its step sized from the tolerance (step doubling), not at the scene's dt:
// at a dt far too coarse for the tolerance it still meets it, keeps det L, and the state does not
// depend on how the run was sampled.
TEST(Incompressible, AutoMeetsTheToleranceWhateverTheDt) {
  Scene scene = incompressible_scene();
  scene.integrator = {"auto", 0.5, 1e-12};
  const double t_end = 4.0;
  Scene fine = incompressible_scene();
  fine.integrator = {"split6", 0.002, 1e-12};
  const State reference = test::run_to(fine, t_end).state;
  Scene fixed = scene;
  fixed.integrator.name = "split6";  // the same dt, fixed: what auto ran before
  const double fixed_error = state_distance(scene, test::run_to(fixed, t_end).state, reference);
  const Simulation one = test::run_to(scene, t_end);
  ASSERT_EQ(one.state.status, Status::ok);
  EXPECT_TRUE(one.info->adaptive);
  EXPECT_EQ(std::string(one.info->name), "split6");
  const double error = state_distance(scene, one.state, reference);
  EXPECT_LT(error, 1e-9) << "fixed dt 0.5 gave " << fixed_error;
  EXPECT_GT(fixed_error, 1e3 * error);
  EXPECT_NEAR(det_of(scene, one.state), 0.66, 1e-12);
  Simulation many = start_simulation(scene);
  for (int k = 1; k <= 40; ++k) advance_to(many, 0.1 * k);
  ASSERT_EQ(many.state.t, t_end);
  ASSERT_EQ(many.state.y.size(), one.state.y.size());
  EXPECT_EQ(std::memcmp(many.state.y.data(), one.state.y.data(), sizeof(double) * one.state.y.size()), 0);
}

// Switching between `auto` (adaptive) and `split6` by name (fixed dt) mid-run changes the stepping,
// although both report split6.
TEST(Incompressible, RetuningBetweenAutoAndSplit6SwitchesTheStepping) {
  Scene scene = incompressible_scene();
  scene.integrator = {"auto", 0.05, 1e-12};  // ~50 adaptive steps per unit time
  Simulation run = start_simulation(scene);
  advance_to(run, 1.0);
  ASSERT_TRUE(run.info->adaptive);
  Scene fixed = scene;
  fixed.integrator.name = "split6";
  retune(run, fixed);
  EXPECT_FALSE(run.info->adaptive);
  const std::uint64_t steps = run.steps;
  advance_to(run, 2.0);
  // 1.0 / 0.05 = 20, the last one the cut landing step (not counted) when rounding falls short
  EXPECT_GE(run.steps - steps, 19u);
  EXPECT_LE(run.steps - steps, 20u);
  retune(run, scene);
  EXPECT_TRUE(run.info->adaptive);
  EXPECT_EQ(std::string(run.info->name), "split6");
}

TEST(Incompressible, StartOffTheLevelSetIsRefused) {
  Scene scene = incompressible_scene();
  scene.initial.mu_dot = 0.1;  // d(det L)/dt ≠ 0
  const std::vector<FieldError> errors = validate_scene(scene);
  ASSERT_FALSE(errors.empty());
  EXPECT_EQ(errors.front().field, "initial.mu_dot");
  EXPECT_NE(errors.front().reason.find("det L"), std::string::npos);
}

TEST(Incompressible, MatchesTheAffineBodyWhoseDeterminantStaysPut) {
  // A rigidly spinning body at spin equilibrium (λ = μ, no deformation rates, abc with A = B = 0)
  // never changes det L: the constrained and the free body move alike (the free one by the closed
  // form, the constrained one by split6 at h = 0.01, whose error is ~h⁶).
  Scene affine;
  affine.surface = {SurfaceKind::sphere, 1.0};
  affine.body = {1.0, 0.5, BodyModel::affine};
  affine.initial.r = 1.0;
  affine.initial.lambda = affine.initial.mu = 1.0;
  affine.initial.phi_dot = 0.5 / std::sin(1.0);
  affine.initial.alpha_dot = 1.0 - std::cos(1.0) * affine.initial.phi_dot;
  affine.potential.deformation = AbcPotential{0.0, 0.0, 0.5 * 0.5 * 1.0};  // C = J w²/2, w = 1
  affine.integrator = {"exact", 0.05, 1e-10};
  Scene incompressible = affine;
  incompressible.body.model = BodyModel::incompressible;
  incompressible.integrator = {"split6", 0.01, 1e-10};
  const State a = test::run_to(affine, 5.0).state, b = test::run_to(incompressible, 5.0).state;
  EXPECT_LT(state_distance(affine, a, b), 1e-11);
}

}  // namespace
}  // namespace spinfold
