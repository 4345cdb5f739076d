// One conformance suite run over every catalog entry (style.md): order of convergence, invariants,
// staying on the surface, failed steps, bit-identical repeats.
#include <gtest/gtest.h>

#include <cstring>
#include <set>

#include "engine/chart.h"
#include "engine/invariants.h"
#include "test_support.h"

namespace spinfold {
namespace {

using test::w5_scene;  // physics.md W5: sphere, radial + abc potentials, a deforming spinning body

// W5 with anisotropic inertia J = [[0.3, 0.08], [0.08, 0.15]] (physics.md §13).
Scene anisotropic_scene() {
  Scene s = w5_scene();
  s.body.inertia_matrix = InertiaMatrix{0.3, 0.08, 0.08, 0.15};
  return s;
}

double state_distance(const Scene& scene, const State& a, const State& b) {
  const EmbeddedBody x = global_embedding(scene, a), y = global_embedding(scene, b);
  return std::max({(x.X - y.X).norm(), (x.V - y.V).norm(), (x.e[0] - y.e[0]).norm(), (x.e[1] - y.e[1]).norm(),
                   (x.W[0] - y.W[0]).norm(), (x.W[1] - y.W[1]).norm()});
}

// Steps of exactly h (accepting every step, also for adaptive methods), re-centring as a run does.
State fixed_step_run(const Scene& scene, Integrator& integrator, double h, double t_end) {
  State state = initial_state(scene);
  Coords next;
  const int n = static_cast<int>(std::lround(t_end / h));
  for (int i = 0; i < n; ++i) {
    integrator.try_step(StepProblem{scene, state.chart}, state.y, h, 1.0, next);
    state.y += next;
    maintain_chart(scene, state);
  }
  state.t = t_end;
  return state;
}

State reference_at(const Scene& scene, double t) {
  Scene tight = scene;
  tight.integrator = {"dop853", 0.01, 1e-15};
  return test::run_to(tight, t).state;
}

std::vector<std::string> stepping_integrators() {
  std::vector<std::string> names;
  for (const CatalogEntry& e : integrator_catalog())
    if (e.make) names.emplace_back(e.info.name);
  return names;
}

class Conformance : public ::testing::TestWithParam<std::string> {
 protected:
  const CatalogEntry& entry() const { return *find_integrator(GetParam()); }
};

// Three step sizes h, h/2, h/4 whose errors sit between round-off and the pre-asymptotic range;
// the measured order is the mean slope over the two halvings.
void expect_measured_order(const CatalogEntry& entry, const Scene& scene) {
  const int order = entry.info.order;
  const double h = order >= 6 ? 0.2 : order >= 4 ? 0.1 : 0.02;
  const double t_end = 4.0;
  const State reference = reference_at(scene, t_end);
  double errors[3];
  for (int i = 0; i < 3; ++i) {
    auto integrator = entry.make();
    errors[i] = state_distance(scene, fixed_step_run(scene, *integrator, h / (1 << i), t_end), reference);
  }
  EXPECT_GT(errors[2], 1e-12) << "too close to round-off to measure";
  EXPECT_NEAR(0.5 * std::log2(errors[0] / errors[2]), order, 0.3)
      << "errors " << errors[0] << ", " << errors[1] << ", " << errors[2];
}

TEST_P(Conformance, MeasuredOrderMatchesTheCatalog) {
  expect_measured_order(entry(), w5_scene());
}

TEST_P(Conformance, AnisotropicInertiaOrderMatchesTheCatalog) {
  expect_measured_order(entry(), anisotropic_scene());
}

TEST_P(Conformance, AnisotropicInertiaKeepsEnergyAndSpin) {
  const IntegratorInfo& info = entry().info;
  Scene scene = anisotropic_scene();
  scene.integrator = {GetParam(), info.order >= 4 ? 0.05 : 0.005, 1e-12};
  Simulation run = start_simulation(scene);
  const State s0 = run.state;
  const double H0 = energy(scene, s0), spin0 = spin(scene, s0);
  double dH[2] = {0.0, 0.0};
  for (int k = 1; k <= 40; ++k) {
    advance_to(run, 0.5 * k);
    ASSERT_EQ(run.state.status, Status::ok);
    dH[k <= 20 ? 0 : 1] =
        std::max(dH[k <= 20 ? 0 : 1], std::abs(energy(scene, run.state) - H0) / std::abs(H0));
    // Left rotations commute with J: s stays a quadratic invariant of (L, P), kept to round-off by
    // Gauss methods and by the splitting's exact flows and left-invariant kicks.
    if (info.symplectic) {
      EXPECT_NEAR(spin(scene, run.state), spin0, 1e-12);
    }
  }
  EXPECT_LT(dH[1], 1e-4);
  if (info.symplectic) {
    EXPECT_LT(dH[1], 2.0 * dH[0] + 1e-13) << "energy error drifts";
  }
}

TEST_P(Conformance, StaysOnTheSurfaceWithATangentFrame) {
  for (SurfaceKind kind : {SurfaceKind::sphere, SurfaceKind::pseudosphere}) {
    Scene scene = w5_scene();
    scene.surface.kind = kind;
    scene.integrator = {GetParam(), 0.05, 1e-10};
    Simulation run = start_simulation(scene);
    for (int k = 1; k <= 10; ++k) {
      advance_to(run, 1.0 * k);
      ASSERT_EQ(run.state.status, Status::ok);
      const EmbeddedBody b = global_embedding(scene, run.state);
      const double K = curvature(scene.surface), scale = b.X.squaredNorm();
      EXPECT_NEAR(K * dot(scene.surface, b.X, b.X), 1.0, 1e-12 * std::max(1.0, scale));
      for (const Vec3& v : {b.V, b.e[0], b.e[1], b.W[0], b.W[1]})
        EXPECT_NEAR(dot(scene.surface, b.X, v), 0.0, 1e-12 * std::max(1.0, scale * v.norm()));
    }
  }
}

TEST_P(Conformance, InvariantsHeldToTheClaimedAccuracy) {
  const IntegratorInfo& info = entry().info;
  Scene scene = w5_scene();
  scene.integrator = {GetParam(), info.order >= 4 ? 0.05 : 0.005, 1e-12};
  Simulation run = start_simulation(scene);
  const State s0 = run.state;
  // Largest relative energy error and p_φ error over the first and the second half of the run.
  double dH[2] = {0.0, 0.0}, dp[2] = {0.0, 0.0};
  const double H0 = energy(scene, s0), p0 = angular_momentum(scene, s0);
  for (int k = 1; k <= 200; ++k) {
    advance_to(run, 0.5 * k);
    ASSERT_EQ(run.state.status, Status::ok);
    const int half = k <= 100 ? 0 : 1;
    dH[half] = std::max(dH[half], std::abs(energy(scene, run.state) - H0) / std::abs(H0));
    dp[half] = std::max(dp[half], std::abs(angular_momentum(scene, run.state) - p0));
    if (info.symplectic) {
      // Quadratic invariants of (L, P) are kept to round-off by Gauss methods and exact flows.
      EXPECT_NEAR(spin(scene, run.state), spin(scene, s0), 1e-12);
      EXPECT_NEAR(vorticity(scene, run.state), vorticity(scene, s0), 1e-12);
    }
  }
  EXPECT_LT(dH[1], 1e-4);
  EXPECT_LT(dp[1], 1e-4);
  if (info.symplectic) {
    // Bounded, not drifting: the second half is no worse than the first (with round-off slack).
    EXPECT_LT(dH[1], 2.0 * dH[0] + 1e-13) << "energy error drifts";
    EXPECT_LT(dp[1], 2.0 * dp[0] + 1e-13) << "p_phi error drifts";
  }
}

TEST_P(Conformance, BitIdenticalRepeats) {
  Scene scene = w5_scene();
  scene.integrator = {GetParam(), 0.05, 1e-10};
  const Simulation a = test::run_to(scene, 5.0), b = test::run_to(scene, 5.0);
  ASSERT_EQ(a.state.y.size(), b.state.y.size());
  EXPECT_EQ(std::memcmp(a.state.y.data(), b.state.y.data(), sizeof(double) * a.state.y.size()), 0);
  EXPECT_EQ(a.state.chart.A, b.state.chart.A);
}

TEST_P(Conformance, AFailedStepLeavesTheStateUnchanged) {
  // A stiff deformation potential (C = 1e4) with a step far beyond stability: explicit methods
  // overflow, implicit stage solves diverge; either way the run stops on its last good state.
  Scene scene = w5_scene();
  std::get<AbcPotential>(scene.potential.deformation).C = 1e4;
  scene.integrator = {GetParam(), 0.5, 1e-10};
  Simulation run = start_simulation(scene);
  State last_good = run.state;
  // Adaptive methods shrink their steps instead of failing: a short stretch shows they survive.
  const int intervals = entry().info.adaptive ? 10 : 200;
  for (int k = 1; k <= intervals && run.state.status == Status::ok; ++k) {
    last_good = run.state;
    advance_to(run, 0.5 * k);
  }
  if (run.state.status == Status::ok) {
    // Adaptive and exact-flow methods survive the stiff case: nothing failed, nothing to check.
    EXPECT_TRUE(entry().info.adaptive || GetParam().starts_with("split")) << GetParam();
    return;
  }
  EXPECT_TRUE(run.state.y.allFinite());
  EXPECT_EQ(run.state.y, last_good.y);
  EXPECT_EQ(run.state.t, last_good.t);
}

INSTANTIATE_TEST_SUITE_P(Catalog, Conformance, ::testing::ValuesIn(stepping_integrators()),
                         [](const auto& param) { return param.param; });

TEST(Catalog, EveryEntryHasAUniqueNameAndASummary) {
  std::set<std::string_view> names;
  for (const CatalogEntry& e : integrator_catalog()) {
    EXPECT_TRUE(names.insert(e.info.name).second) << e.info.name;
    EXPECT_FALSE(e.info.summary.empty());
    EXPECT_EQ(e.make == nullptr, e.info.exact) << e.info.name;
  }
  EXPECT_EQ(names.count("auto"), 0u);
}

}  // namespace
}  // namespace spinfold
