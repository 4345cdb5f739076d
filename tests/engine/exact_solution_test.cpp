// The closed form against tight integrations, across every branch of physics.md §8.3–8.4.
#include "engine/exact_solution.h"

#include <gtest/gtest.h>

#include <numbers>

#include "engine/chart.h"
#include "engine/invariants.h"
#include "engine/paper_coordinates.h"
#include "test_support.h"

namespace spinfold {
namespace {

Scene deforming(SurfaceKind kind, double A, double B, double C) {
  Scene s;
  s.surface = {kind, 1.5};
  s.body = {1.3, 0.3, BodyModel::affine};
  s.potential.deformation = AbcPotential{A, B, C};
  s.initial = {1.1, 0.2, 0.3, -0.4, 1.4, 0.6, 0.2, 0.5, 0.6, -0.2, 0.1, -0.05};
  s.integrator = {"dop853", 0.01, 1e-13};
  return s;
}

double state_distance(const Scene& scene, const State& a, const State& b) {
  const EmbeddedBody x = global_embedding(scene, a), y = global_embedding(scene, b);
  return std::max({(x.X - y.X).norm(), (x.V - y.V).norm(), (x.e[0] - y.e[0]).norm(), (x.e[1] - y.e[1]).norm(),
                   (x.W[0] - y.W[0]).norm(), (x.W[1] - y.W[1]).norm()});
}

struct Branch {
  SurfaceKind kind;
  double A, B, C;
  double gamma = 0.0;  // radial potential g (0: none, the chart-free path of §8.6)
  BodyModel model = BodyModel::affine;
};

class ExactAgainstIntegration : public ::testing::TestWithParam<Branch> {};

TEST_P(ExactAgainstIntegration, WholeStateAgreesAtSeveralTimes) {
  const Branch b = GetParam();
  Scene scene = deforming(b.kind, b.A, b.B, b.C);
  if (b.gamma > 0.0) scene.potential.radial = RadialPotential{b.gamma};
  if (b.model == BodyModel::rigid) {
    scene.body.model = BodyModel::rigid;
    scene.potential.deformation = std::monostate{};
    scene.initial.lambda = scene.initial.mu = 1.0;
    scene.initial.lambda_dot = scene.initial.mu_dot = 0.0;
  }
  const ExactSolution exact = make_exact_solution(scene);
  Simulation run = start_simulation(scene);
  EXPECT_LT(state_distance(scene, exact_state(exact, 0.0), run.state), 1e-14);
  for (double t : {0.7, 2.0, 5.0}) {
    advance_to(run, t);
    const State e = exact_state(exact, t);
    EXPECT_LT(state_distance(scene, e, run.state), 1e-9) << "t = " << t;
    EXPECT_NEAR(energy(scene, e), energy(scene, run.state), 1e-10);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Branches, ExactAgainstIntegration,
    ::testing::Values(Branch{SurfaceKind::sphere, 0.02, 0.1, 0.4},   // harmonic |w|², §8.4 (i)
                      Branch{SurfaceKind::sphere, 0.05, 0.0, -0.1},  // hyperbolic, §8.4 (ii)
                      Branch{SurfaceKind::sphere, 0.02, 0.1, 0.0},   // quadratic, §8.4 (iii)
                      Branch{SurfaceKind::pseudosphere, 0.02, 0.1, 0.4},
                      Branch{SurfaceKind::pseudosphere, 0.0, 0.1, 0.3},  // A = 0: linear oscillator plane
                      Branch{SurfaceKind::plane, 0.02, 0.1, 0.4},
                      Branch{SurfaceKind::plane, 0.0, 0.0, 0.0},  // free body
                      // Radial potential (physics.md §8.2, §8.9): Λ > 0 on S², Λ < 0 on H², the plane.
                      Branch{SurfaceKind::sphere, 0.02, 0.1, 0.4, 0.05},
                      Branch{SurfaceKind::sphere, 0.0, 0.0, 0.0, 0.5, BodyModel::rigid},
                      Branch{SurfaceKind::pseudosphere, 0.02, 0.1, 0.4, 0.5},
                      Branch{SurfaceKind::pseudosphere, 0.0, 0.0, 0.0, 0.05, BodyModel::rigid},
                      Branch{SurfaceKind::plane, 0.02, 0.1, 0.4, 0.5}));

TEST(Exact, ManyPeriodsStayOnTheClosedOrbit) {
  // W3 after 1000 periods: the closed form does not accumulate error.
  Scene scene = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  scene.initial.r = 1.0;
  test::set_rigid_motion(scene, 0.5, std::numbers::pi / 2, 1.0);
  scene.integrator.name = "exact";
  Simulation run = start_simulation(scene);
  const Vec3 X0 = global_embedding(scene, run.state).X;
  advance_to(run, 1000 * 5.619851784832581);
  EXPECT_LT((global_embedding(scene, run.state).X - X0).norm(), 1e-10);
  EXPECT_EQ(run.steps, 1u);  // one evaluation, whatever the time
}

TEST(Exact, W5ClosedFormStateAtTwoToRoundOff) {
  Scene scene;
  scene.surface = {SurfaceKind::sphere, 1.5};
  scene.body = {1.0, 0.4, BodyModel::affine};
  scene.potential.radial = RadialPotential{0.05};
  scene.potential.deformation = AbcPotential{0.02, 0.4, 0.3};
  scene.initial = {1.2, 0.0, 0.0, 0.0, 1.1, 0.6, 0.1, 0.4, 0.5, 0.2, 0.0, 0.05};
  const State s = exact_state(make_exact_solution(scene), 2.0);
  const PaperCoordinates c = paper_coordinates(scene, s);
  EXPECT_NEAR(c.r, 1.650073264590784, 1e-14);  // physics.md W5
  EXPECT_NEAR(*c.phi, 0.7053552271149849, 1e-14);
  const double L_t2[2][2] = {{0.9337349005373956, -0.47142953066718696},
                             {0.7376511798429146, 0.160781033418681}};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) EXPECT_NEAR((*c.L)(i, j), L_t2[i][j], 1e-14);
}

TEST(Exact, RefusesScenesWithoutAClosedFormAndSaysWhy) {
  Scene scene = deforming(SurfaceKind::sphere, 0.0, 0.0, 0.1);
  EXPECT_FALSE(exact_unsupported_reason(scene));
  scene.potential.radial = RadialPotential{0.1};
  EXPECT_FALSE(exact_unsupported_reason(scene));
  scene.potential.deformation = PolarPotential{0.1, -1.0, PolarForm::cot2};
  ASSERT_TRUE(exact_unsupported_reason(scene));
  EXPECT_NE(exact_unsupported_reason(scene)->find("polar"), std::string::npos);
}

TEST(Exact, AutoPicksTheClosedFormOnlyWhereItExists) {
  Scene scene = deforming(SurfaceKind::pseudosphere, 0.0, 0.1, 0.3);
  scene.integrator.name = "auto";
  EXPECT_EQ(resolve_integrator(scene), "exact");
  scene.potential.radial = RadialPotential{0.1};
  EXPECT_EQ(resolve_integrator(scene), "exact");
  scene.potential.deformation = PolarPotential{0.1, -1.0, PolarForm::cot2};
  EXPECT_NE(resolve_integrator(scene), "exact");
  EXPECT_EQ(start_simulation(scene).info->name, resolve_integrator(scene));
}

TEST(Exact, DegenerateCrossingLocatedOnTheClosedForm) {
  Scene scene = test::degenerate_crossing_scene();
  scene.integrator.name = "exact";
  Simulation run = start_simulation(scene);
  advance_to(run, 1.0);
  ASSERT_EQ(run.events.size(), 1u);
  EXPECT_NEAR(run.events[0].t, 0.5, 1e-12);
  scene.on_degenerate = OnDegenerate::stop;
  Simulation stopped = start_simulation(scene);
  advance_to(stopped, 1.0);
  EXPECT_EQ(stopped.state.status, Status::degenerate_frame);
  // The last good state: just before the crossing, whatever the advances were (replay is exact).
  EXPECT_LT(stopped.state.t, 0.5);
  EXPECT_GT(stopped.state.t, 0.5 - 1e-12);
  EXPECT_GT(det_L(scene, stopped.state), 0.0);
}

}  // namespace
}  // namespace spinfold
