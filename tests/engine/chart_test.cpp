// Charts and the embedding (engine/chart.h, physics.md §7): a state built from the scene's polar
// values reads back as those values in the embedding, re-centring changes no physics, and the
// chart's bands and maps are what their comments say.
#include "engine/chart.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace spinfold {
namespace {

Scene scene_on(SurfaceKind kind) {
  Scene s;
  s.surface = {kind, 1.5};
  s.initial = {.r = 1.2,
               .phi = 0.3,
               .alpha = 0.1,
               .beta = -0.4,
               .lambda = 1.1,
               .mu = 0.6,
               .r_dot = 0.2,
               .phi_dot = -0.3,
               .alpha_dot = 0.5};
  return s;
}

constexpr SurfaceKind kKinds[] = {SurfaceKind::sphere, SurfaceKind::pseudosphere, SurfaceKind::plane};

// The body starts at chart_point(r, φ) with velocity ṙE₁ + Sφ̇E₂ and frame e_A = E_B L_BA,
// L = U(α) diag(λ, μ) U(β)ᵀ (physics.md §2), whatever chart the state is kept in.
TEST(Chart, InitialStateEmbedsTheScenesValues) {
  for (const SurfaceKind kind : kKinds) {
    const Scene s = scene_on(kind);
    const ChartPoint p = chart_point(s.surface, s.initial.r, s.initial.phi);
    const Mat2 L = rotation2(s.initial.alpha) * Eigen::Vector2d(1.1, 0.6).asDiagonal() *
                   rotation2(s.initial.beta).transpose();
    const EmbeddedBody body = global_embedding(s, initial_state(s));
    const Vec3 V = 0.2 * p.E1 + polar_S(s.surface, 1.2) * -0.3 * p.E2;
    EXPECT_LT((body.X - p.X).norm(), 1e-13) << static_cast<int>(kind);
    EXPECT_LT((body.V - V).norm(), 1e-13) << static_cast<int>(kind);
    for (int a = 0; a < 2; ++a)
      EXPECT_LT((body.e[a] - (L(0, a) * p.E1 + L(1, a) * p.E2)).norm(), 1e-13) << static_cast<int>(kind) << a;
    EXPECT_LT((initial_kinematics(s).X - p.X).norm(), 1e-13);
  }
}

// At the pole the polar chart is singular: the state is kept in another chart, and still embeds
// at the pole.
TEST(Chart, InitialStateAtThePoleIsInAMovedChart) {
  Scene s = scene_on(SurfaceKind::sphere);
  s.initial.r = 0.0;
  const State state = initial_state(s);
  EXPECT_FALSE(state.chart.global);
  EXPECT_TRUE(chart_well_conditioned(s.surface, state.y[coord::r]));
  EXPECT_LT((global_embedding(s, state).X - Vec3(0.0, 0.0, 1.5)).norm(), 1e-13);
}

// Re-centring moves the chart, not the body.
TEST(Chart, RecentreKeepsThePhysicalState) {
  for (const SurfaceKind kind : kKinds) {
    const Scene s = scene_on(kind);
    const State before = initial_state(s);
    State after = before;
    recentre(s, after);
    EXPECT_FALSE(after.chart.global) << static_cast<int>(kind);
    EXPECT_LT(embedded_state_error(s, before, after), 1e-12) << static_cast<int>(kind);
  }
}

// chart_coords reads back the coordinates chart_kinematics was built from.
TEST(Chart, ChartCoordsInvertChartKinematics) {
  for (const SurfaceKind kind : kKinds) {
    const Scene s = scene_on(kind);
    const Coords y = initial_state(s).y;
    const Coords back = chart_coords(s, chart_kinematics(s, y));
    ASSERT_EQ(back.size(), y.size());
    EXPECT_LT((back - y).cwiseAbs().maxCoeff(), 1e-12) << static_cast<int>(kind);
  }
}

// A body placed far out on H² (where the global embedding is ~R e^{r/R}/2) sits where chart_point
// puts it, moving as given.
TEST(Chart, PlaceBodyPutsItWhereTheChartSays) {
  const Scene s = scene_on(SurfaceKind::pseudosphere);
  const PlacedBody placed{6.0, 0.7, 0.3, -0.2, Mat2::Identity(), Mat2::Zero(), 0.0};
  const State state = place_body(s, placed);
  EXPECT_EQ(state.t, 0.0);
  EXPECT_EQ(state.status, Status::ok);
  const ChartPoint p = chart_point(s.surface, 6.0, 0.7);
  const EmbeddedBody body = global_embedding(s, state);
  EXPECT_LT((body.X - p.X).norm(), 1e-12 * p.X.norm());
  EXPECT_LT((body.V - (0.3 * p.E1 - 0.2 * p.E2)).norm(), 1e-11 * p.X.norm());
}

// The bands of physics.md §7 on the unit sphere (|sin r| ≥ 0.3 well conditioned, ≥ 0.5 comfortable)
// and on H² (0.3 ≤ r ≤ 4 and 0.5 ≤ r ≤ 3).
TEST(Chart, ConditioningBands) {
  const Surface sphere{SurfaceKind::sphere, 1.0}, h2{SurfaceKind::pseudosphere, 1.0};
  EXPECT_FALSE(chart_well_conditioned(sphere, 0.1));
  EXPECT_TRUE(chart_well_conditioned(sphere, 0.4));
  EXPECT_FALSE(chart_comfortable(sphere, 0.4));
  EXPECT_TRUE(chart_comfortable(sphere, std::numbers::pi / 2));
  EXPECT_FALSE(chart_well_conditioned(sphere, std::numbers::pi - 0.1));  // near the antipode
  EXPECT_FALSE(chart_well_conditioned(h2, 0.2));
  EXPECT_TRUE(chart_well_conditioned(h2, 3.5));
  EXPECT_FALSE(chart_comfortable(h2, 3.5));
  EXPECT_TRUE(chart_comfortable(h2, 1.0));
  EXPECT_FALSE(chart_well_conditioned(h2, 4.5));
}

// A state comfortably inside the scene's chart stays there.
TEST(Chart, MaintainChartLeavesAComfortableState) {
  const Scene s = scene_on(SurfaceKind::sphere);
  State state = initial_state(s);
  ASSERT_TRUE(state.chart.global);
  const State before = state;
  EXPECT_FALSE(maintain_chart(s, state));
  EXPECT_EQ(state.y, before.y);
}

TEST(Chart, EmbeddedStateErrorIsZeroOnlyForTheSameState) {
  const Scene s = scene_on(SurfaceKind::sphere);
  const State a = initial_state(s);
  EXPECT_EQ(embedded_state_error(s, a, a), 0.0);
  State b = a;
  b.y[coord::r] += 1e-6;  // moves X by 1e-6 along E₁: no component by more than that
  EXPECT_GT(embedded_state_error(s, a, b), 1e-7);
  EXPECT_LE(embedded_state_error(s, a, b), 1.0001e-6);
  b.y[coord::r] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(embedded_state_error(s, a, b), std::numeric_limits<double>::infinity());
}

// U(ψ) rotates by ψ; inverse_linear is Aᵀ for a rotation and ηAᵀη for a Lorentz boost.
TEST(Chart, Rotation2AndInverseLinear) {
  const Mat2 U = rotation2(std::numbers::pi / 2);
  EXPECT_LT((U * Eigen::Vector2d(1.0, 0.0) - Eigen::Vector2d(0.0, 1.0)).norm(), 1e-16);
  const Mat3 rotation = Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  EXPECT_LT((inverse_linear({SurfaceKind::sphere, 1.0}, rotation) * rotation - Mat3::Identity()).norm(),
            1e-15);
  const double w = 1.3;
  Mat3 boost;
  boost << std::cosh(w), 0.0, std::sinh(w), 0.0, 1.0, 0.0, std::sinh(w), 0.0, std::cosh(w);
  EXPECT_LT((inverse_linear({SurfaceKind::pseudosphere, 1.0}, boost) * boost - Mat3::Identity()).norm(),
            1e-14);
}

}  // namespace
}  // namespace spinfold
