// The trail and the step sequence: the same numbers however a run is advanced.
#include "engine/trail.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "engine/chart.h"
#include "test_support.h"

namespace spinfold {
namespace {

using test::same_bits;

bool same_points(const Trail& a, const Trail& b) {
  if (a.points.size() != b.points.size() || a.spacing != b.spacing) return false;
  for (std::size_t i = 0; i < a.points.size(); ++i)
    if (a.points[i].t != b.points[i].t || a.points[i].X != b.points[i].X) return false;
  return true;
}

// A spinning affine body with a deformation potential (no closed form) under every integrator,
// and the closed form.
Scene spinning(std::string_view integrator) {
  Scene s;
  s.surface = {SurfaceKind::sphere, 1.0};
  s.body = {1.0, 0.1, BodyModel::affine};
  s.potential.deformation = PolarPotential{0.05, -1.0, PolarForm::cot2};
  s.initial.lambda = 1.2;
  s.initial.mu = 0.8;
  s.initial.phi_dot = 0.6;
  s.initial.alpha_dot = 2.0;
  s.integrator = {std::string(integrator), 0.01, 1e-10};
  if (integrator == "exact") s.potential.deformation = AbcPotential{0.0, 0.0, 0.5};
  return s;
}

class AnyIntegrator : public ::testing::TestWithParam<const char*> {};

TEST_P(AnyIntegrator, OneAdvanceOrSixtyGiveTheSameStateAndTrail) {
  const Scene scene = spinning(GetParam());
  Simulation once = start_simulation(scene), many = start_simulation(scene);
  Trail trail_once, trail_many;
  advance_sampling_trail(once, trail_once, 6.0);
  for (int k = 1; k <= 60; ++k) advance_sampling_trail(many, trail_many, 0.1 * k);
  advance_sampling_trail(many, trail_many, 6.0);
  ASSERT_EQ(once.state.status, Status::ok);
  EXPECT_TRUE(same_bits(once.state, many.state));
  EXPECT_TRUE(same_bits(once.grid.state, many.grid.state));
  EXPECT_TRUE(same_points(trail_once, trail_many));
  EXPECT_EQ(trail_once.points.size(), 601u);  // t = 0, 0.01, …, 6
  // Irregular stops (play ticks of any length) too.
  Simulation ragged = start_simulation(scene);
  Trail trail_ragged;
  for (double t = 0.0137; t < 6.0; t += 0.0137 + 0.05 * (t - std::floor(t)))
    advance_sampling_trail(ragged, trail_ragged, t);
  advance_sampling_trail(ragged, trail_ragged, 6.0);
  EXPECT_TRUE(same_bits(once.state, ragged.state));
  EXPECT_TRUE(same_points(trail_once, trail_ragged));
}

INSTANTIATE_TEST_SUITE_P(Catalog, AnyIntegrator,
                         ::testing::Values("dop853", "rk4", "implicit_midpoint", "gauss4", "gauss6", "split4",
                                           "split6", "exact"));

TEST(Trail, FollowsTheTruePathAtItsSpacing) {
  // Each sample is the state at its time: a run advanced exactly there has the same position.
  const Scene scene = spinning("dop853");
  Simulation run = start_simulation(scene);
  Trail trail;
  advance_sampling_trail(run, trail, 2.0);
  for (const std::size_t i : {std::size_t{1}, std::size_t{57}, std::size_t{200}}) {
    Simulation probe = start_simulation(scene);
    advance_to(probe, trail.points[i].t);
    EXPECT_EQ(trail.points[i].t, static_cast<double>(i) * trail.spacing);
    EXPECT_EQ(global_embedding(scene, probe.state).X, trail.points[i].X);
  }
}

TEST(Trail, PastItsCapItKeepsTheWholeRunAtHalfTheResolution) {
  const Scene scene = spinning("exact");
  Simulation run = start_simulation(scene);
  Trail trail;
  trail.max_points = 100;
  advance_sampling_trail(run, trail, 3.0);  // 301 samples at 0.01 → 76 at 0.04
  EXPECT_LE(trail.points.size(), 100u);
  EXPECT_EQ(trail.spacing, 0.04);
  EXPECT_EQ(trail.points.front().t, 0.0);
  EXPECT_EQ(trail.points.back().t, 3.0);
  // The kept samples are those a trail with the coarse spacing from the start takes.
  Simulation coarse_run = start_simulation(scene);
  Trail coarse;
  coarse.spacing = 4 * Trail{}.spacing;
  advance_sampling_trail(coarse_run, coarse, 3.0);
  EXPECT_TRUE(same_points(trail, coarse));
}

TEST(Trail, SpanSelectsTheRecentPast) {
  const Scene scene = spinning("exact");
  Simulation run = start_simulation(scene);
  Trail trail;
  advance_sampling_trail(run, trail, 1.0);
  EXPECT_EQ(trail_positions(trail, 1.0, -1.0).size(), 101u);
  EXPECT_EQ(trail_positions(trail, 1.0, 0.5).size(), 51u);
}

}  // namespace
}  // namespace spinfold
