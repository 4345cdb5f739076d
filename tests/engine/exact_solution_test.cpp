// The closed form against tight integrations, across every branch of physics.md §8.3–8.4.
#include "engine/exact_solution.h"

#include <gtest/gtest.h>

#include <numbers>

#include "engine/chart.h"
#include "engine/dynamics.h"
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
  Scene scene = test::w5_scene();
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

// Compares two states through what stays well-conditioned anywhere (far out on H² included):
// r, the position along the circle S·Δφ, the rates ṙ and Sφ̇, and L, M in the paper's frame.
double paper_distance(const Scene& scene, const State& a, const State& b) {
  const GlobalBody x = global_body(scene, a), y = global_body(scene, b);
  const double dphi = std::remainder(x.phi - y.phi, 2.0 * std::numbers::pi);
  // Far out (S ~ e^{r/R}) S·Δφ is compared as φ to 1e-12 rad: the integrations keep φ to ~1e-13.
  return std::max({std::abs(x.r - y.r), std::max(0.0, std::abs(x.S * dphi) - 1e-12 * x.S),
                   std::abs(x.r_dot - y.r_dot), std::abs(x.S * x.phi_dot - y.S * y.phi_dot),
                   (x.L - y.L).norm(), (x.M - y.M).norm()});
}

State run_with(Scene scene, const std::string& integrator, double t) {
  scene.integrator = {integrator, 0.01, 1e-13};
  Simulation run = start_simulation(scene);
  advance_to(run, t);
  return run.state;
}

// physics.md W5 (separable_radial_abc) started at r = 0.3 on R = 1.5, inside the chart's re-centring
// band (sin(r/R) < 0.3): the radial closed form must use p_φ of the scene's chart, not of the moved
// chart the start is stored in (it reported r = 1.3056, φ = −0.254 with status ok).
TEST(ExactChartRules, RadialPotentialFromAStartInTheRecentringBand) {
  Scene scene = test::w5_scene();
  scene.initial.r = 0.3;
  for (const double r0 : {0.3, 0.457, 0.458, 1.2}) {
    scene.initial.r = r0;
    const State exact = run_with(scene, "exact", 5.0), reference = run_with(scene, "dop853", 5.0);
    ASSERT_EQ(exact.status, Status::ok) << r0;
    EXPECT_LT(paper_distance(scene, exact, reference), 1e-9) << r0;
  }
  scene.initial.r = 0.3;
  const PaperCoordinates c = paper_coordinates(scene, run_with(scene, "exact", 5.0));
  EXPECT_NEAR(c.r, 1.26824, 1e-5);  // dop853 and gauss6 (issue 22)
  EXPECT_NEAR(*c.phi, 2.81058, 1e-5);
}

// On H² with V_r > 0, starts at 0.1R and 4.1R (outside the band on both sides) and far out.
TEST(ExactChartRules, RadialPotentialOnThePseudosphereOutsideTheBand) {
  Scene scene;
  scene.surface = {SurfaceKind::pseudosphere, 1.0};
  scene.body = {1.0, 0.4, BodyModel::affine};
  scene.potential.radial = RadialPotential{0.3};
  scene.potential.deformation = AbcPotential{0.02, 0.4, 0.3};
  for (const double r0 : {0.1, 1.0, 4.1, 8.0, 12.0}) {
    scene.initial = {r0, 0.3, 0.1, 0.2, 1.1, 0.6, 0.0, 0.5 / std::sinh(r0), 3.0, 0.2, 0.1, 0.05};
    const State exact = run_with(scene, "exact", 5.0), reference = run_with(scene, "dop853", 5.0);
    ASSERT_EQ(exact.status, Status::ok) << r0;
    EXPECT_LT(paper_distance(scene, exact, reference), 1e-8) << r0;
  }
}

// Far out on H² without a potential the orbit's isometry is taken in the start's chart: from 8R to
// 30R the closed form agrees with dop853 (it erred by 1e-8 at 8R, O(1) from 15R and was non_finite
// at t = 0 near 25R). S·Δφ is compared to S·1e-14 there: φ itself keeps only ~16 digits.
TEST(ExactChartRules, FarOutOnThePseudosphereWithoutPotential) {
  Scene scene;
  scene.surface = {SurfaceKind::pseudosphere, 1.0};
  scene.body = {1.0, 0.4, BodyModel::affine};
  scene.potential.deformation = AbcPotential{0.02, 0.4, 0.3};
  for (const double r0 : {8.0, 12.0, 15.0, 20.0, 25.0, 30.0}) {
    scene.initial = {r0, 0.3, 0.1, 0.2, 1.1, 0.6, 0.0, 0.5 / std::sinh(r0), 3.0, 0.2, 0.1, 0.05};
    const State exact = run_with(scene, "exact", 5.0), reference = run_with(scene, "dop853", 5.0);
    ASSERT_EQ(exact.status, Status::ok) << r0;
    const GlobalBody x = global_body(scene, exact), y = global_body(scene, reference);
    EXPECT_LT(std::abs(x.r - y.r), 1e-10) << r0;
    EXPECT_LT((x.L - y.L).norm(), 1e-10) << r0;
    EXPECT_LT(std::abs(x.r_dot - y.r_dot) + std::abs(x.S * x.phi_dot - y.S * y.phi_dot), 1e-10) << r0;
    EXPECT_LT(x.S * std::abs(std::remainder(x.phi - y.phi, 2.0 * std::numbers::pi)), 1e-9 + 1e-14 * x.S)
        << r0;
  }
}

// det L(τ) in closed form: the roots are where det L changes sign along the closed form itself.
TEST(ExactEvents, DegenerateTimesAreTheSignChangesOfDetL) {
  Scene scene;
  scene.surface = {SurfaceKind::sphere, 1.0};
  scene.body = {1.0, 0.1, BodyModel::affine};
  scene.initial = {1.2, 0.0, 0.0, 0.0, 1.0, 0.3, 0.0, 0.4, 0.3, 0.0, 0.0, -2.0};
  for (const double C : {0.5, 0.0, -0.05}) {
    scene.potential.deformation = AbcPotential{0.0, 0.0, C};
    const ExactSolution sol = make_exact_solution(scene);
    const std::vector<double> roots = degenerate_times(sol, 0.0, 10.0);
    ASSERT_FALSE(roots.empty()) << C;
    for (const double t : roots) {
      const double before = internal_state(scene, exact_state(sol, t - 1e-7).y).L.determinant();
      const double after = internal_state(scene, exact_state(sol, t + 1e-7).y).L.determinant();
      EXPECT_LT(before * after, 0.0) << C << " at " << t;
    }
    // Between consecutive roots (and before the first) the sign does not change on a fine grid.
    int changes = 0;
    double previous = internal_state(scene, exact_state(sol, 0.0).y).L.determinant();
    for (int k = 1; k <= 100000; ++k) {
      const double det = internal_state(scene, exact_state(sol, 1e-4 * k).y).L.determinant();
      if ((det > 0.0) != (previous > 0.0)) ++changes;
      previous = det;
    }
    EXPECT_EQ(changes, static_cast<int>(roots.size())) << C;
  }
}

}  // namespace
}  // namespace spinfold
