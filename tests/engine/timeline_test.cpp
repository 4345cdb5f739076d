// Parameter changes continue a run (retune), and a timeline replays it bit for bit.
#include "engine/timeline.h"

#include <gtest/gtest.h>

#include <cstring>
#include <numbers>

#include "engine/chart.h"
#include "engine/invariants.h"
#include "test_support.h"

namespace spinfold {
namespace {

using test::same_bits;

Scene base(std::string_view integrator) {
  Scene s;
  s.surface = {SurfaceKind::sphere, 1.0};
  s.body = {1.0, 0.1, BodyModel::affine};
  s.potential.radial = RadialPotential{0.02};
  s.potential.deformation = AbcPotential{0.0, 0.0, 0.4};
  s.initial.lambda = 1.2;
  s.initial.mu = 0.8;
  s.initial.phi_dot = 0.6;
  s.initial.alpha_dot = 2.0;
  s.integrator = {std::string(integrator), 0.01, 1e-10};
  return s;
}

// Every kind of parameter a change can touch, one after another.
std::vector<ParameterChange> changes_of(const Scene& start) {
  std::vector<ParameterChange> list;
  Scene s = start;
  s.body.mass = 1.5;
  list.push_back({0.7, s});
  s.potential.deformation = AbcPotential{0.01, 0.02, 0.3};
  list.push_back({1.3, s});
  s.surface.radius = 1.4;
  list.push_back({2.05, s});
  s.body.inertia = 0.2;
  s.integrator.tolerance = 1e-9;
  list.push_back({3.3, s});
  s.potential.radial.reset();
  list.push_back({4.0, s});
  s.on_degenerate = OnDegenerate::stop;
  s.integrator.dt = 0.02;
  list.push_back({4.3, s});
  s.integrator.name = s.integrator.name == "split6" ? "gauss6" : "split6";  // another integrator
  list.push_back({4.6, s});
  return list;
}

class Replay : public ::testing::TestWithParam<const char*> {};

// A live run changed at the moments it was advanced to equals its replay from t = 0.
TEST_P(Replay, RebuiltRunEqualsTheLiveOneBitForBit) {
  const Scene scene = base(GetParam());
  const auto changes = changes_of(scene);
  Simulation live = start_simulation(scene);
  Trail live_trail;
  std::size_t next = 0;
  for (double t = 0.1; t <= 5.0 + 1e-9; t += 0.1) {
    if (next < changes.size() && changes[next].t <= t) {
      advance_sampling_trail(live, live_trail, changes[next].t);
      retune_carrying_trail(live, live_trail, changes[next].scene);
      ++next;
    }
    advance_sampling_trail(live, live_trail, t);
  }
  ASSERT_EQ(live.state.status, Status::ok);
  Simulation rebuilt;
  Trail rebuilt_trail;
  ASSERT_TRUE(replay(scene, changes, live.state.t, rebuilt, rebuilt_trail));
  EXPECT_TRUE(same_bits(live.state, rebuilt.state));
  ASSERT_EQ(live_trail.points.size(), rebuilt_trail.points.size());
  for (std::size_t i = 0; i < live_trail.points.size(); ++i)
    EXPECT_EQ(live_trail.points[i].X, rebuilt_trail.points[i].X);
}

// The replay a recording draws its frames from, asked at frame times that straddle the changes
// (never exactly at one), ends where replay() asked once ends, bit for bit, trail included; and a
// change is applied at its own time, not at the first frame after it.
TEST_P(Replay, StepwiseReplayEqualsTheReplayAskedOnce) {
  const Scene scene = base(GetParam());
  const auto changes = changes_of(scene);
  TimelineReplay stepwise(scene, changes);
  for (double t = 0.0; t <= 5.0 + 1e-9; t += 0.3) ASSERT_TRUE(stepwise.advance_to(t));
  const double end = stepwise.run().state.t;
  Simulation once;
  Trail once_trail;
  ASSERT_TRUE(replay(scene, changes, end, once, once_trail));
  EXPECT_TRUE(same_bits(stepwise.run().state, once.state));
  EXPECT_EQ(stepwise.run().scene.integrator.name, changes.back().scene.integrator.name);
  ASSERT_EQ(stepwise.trail().points.size(), once_trail.points.size());
  for (std::size_t i = 0; i < once_trail.points.size(); ++i)
    EXPECT_EQ(stepwise.trail().points[i].X, once_trail.points[i].X);
  // Up to a time before the first change, the run has the starting parameters still.
  TimelineReplay early(scene, changes);
  ASSERT_TRUE(early.advance_to(changes.front().t - 0.05));
  EXPECT_EQ(early.run().scene.body.mass, scene.body.mass);
  ASSERT_TRUE(early.advance_to(changes.front().t));
  EXPECT_EQ(early.run().scene.body.mass, changes.front().scene.body.mass);
}

INSTANTIATE_TEST_SUITE_P(ExactAndStepping, Replay, ::testing::Values("auto", "dop853", "split6", "rk4"));

TEST(Retune, EveryParameterKeepsTimeAndPlace) {
  const Scene scene = base("dop853");
  for (const ParameterChange& change : changes_of(scene)) {
    Simulation run = start_simulation(scene);
    advance_to(run, 1.1);
    const EmbeddedBody before = global_embedding(run.scene, run.state);
    const double scale = change.scene.surface.radius / scene.surface.radius;
    retune(run, change.scene);
    const EmbeddedBody after = global_embedding(run.scene, run.state);
    EXPECT_EQ(run.state.t, 1.1);
    EXPECT_LT((after.X - scale * before.X).norm(), 1e-13);  // the same place on the surface
    EXPECT_LT((after.V - before.V).norm(), 1e-13);          // the same velocity
    for (int a = 0; a < 2; ++a) EXPECT_LT((after.e[a] - before.e[a]).norm(), 1e-13);
    EXPECT_EQ(run.segment_start, 1.1);
    EXPECT_EQ(run.initial_energy, energy(run.scene, run.state));  // errors count from here
    advance_to(run, 2.0);
    EXPECT_EQ(run.state.status, Status::ok);
  }
}

TEST(Retune, NewParametersActFromTheChange) {
  // A heavier body on a sphere without potentials: the same path, spin now weaker against mass.
  Scene scene = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  test::set_rigid_motion(scene, 0.5, std::numbers::pi / 2, 1.0);
  Simulation run = start_simulation(scene);
  advance_to(run, 1.0);
  Scene heavier = scene;
  heavier.body.mass = 2.0;
  retune(run, heavier);
  // Energy is conserved under the new parameters from the change on.
  const double E = energy(heavier, run.state);
  advance_to(run, 5.0);
  EXPECT_NEAR(energy(heavier, run.state), E, 1e-10 * std::abs(E));
  EXPECT_NEAR(spin(heavier, run.state), 1.0, 1e-12);  // ω and J kept: s = 2Jλ₀²ω
}

TEST(Retune, WorksAtThePoleAndAfterAFrameCrossing) {
  // At the pole the paper's coordinates are undefined; the state is not.
  const auto preset = [] {
    Scene s = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
    s.initial.r = 1.0;
    s.initial.phi = 0.5;
    s.initial.r_dot = -0.5;
    s.integrator.name = "auto";
    return s;
  }();
  Simulation run = start_simulation(preset);
  advance_to(run, 2.0);  // r = 0: the pole
  ASSERT_LT(global_body(preset, run.state).r, 1e-9);
  Scene changed = preset;
  changed.body.inertia = 0.7;
  changed.potential.deformation = AbcPotential{};
  retune(run, changed);
  EXPECT_EQ(run.state.t, 2.0);
  EXPECT_LT(global_body(changed, run.state).r, 1e-9);
  advance_to(run, 3.0);
  EXPECT_EQ(run.state.status, Status::ok);
  EXPECT_NEAR(global_body(changed, run.state).r, 0.5, 1e-9);  // straight on through the pole

  // After det L = 0 the frame is mirrored, which no initial state can be.
  const Scene crossing = test::degenerate_crossing_scene();
  Simulation mirrored = start_simulation(crossing);
  advance_to(mirrored, 0.8);
  ASSERT_LT(det_L(crossing, mirrored.state), 0.0);
  Scene heavier = crossing;
  heavier.body.mass = 3.0;
  retune(mirrored, heavier);
  EXPECT_LT(det_L(heavier, mirrored.state), 0.0);
  advance_to(mirrored, 1.5);
  EXPECT_EQ(mirrored.state.status, Status::ok);
}

TEST(Retune, ModelChangeKeepsSpinAndRotation) {
  Scene scene = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  test::set_rigid_motion(scene, 0.5, 1.0, 0.8);
  Simulation run = start_simulation(scene);
  advance_to(run, 1.0);
  const double s = spin(scene, run.state);
  const EmbeddedBody before = global_embedding(scene, run.state);
  Scene affine = scene;
  affine.body.model = BodyModel::affine;
  retune(run, affine);
  EXPECT_NEAR(spin(affine, run.state), s, 1e-12);
  const EmbeddedBody after = global_embedding(affine, run.state);
  for (int a = 0; a < 2; ++a) EXPECT_LT((after.e[a] - before.e[a]).norm(), 1e-13);
  advance_to(run, 2.0);
  EXPECT_EQ(run.state.status, Status::ok);
}

TEST(Retune, ACureForAStoppedRunContinuesItFromTheLastGoodState) {
  Scene scene = base("rk4");
  scene.integrator.dt = 2.0;  // far beyond stability
  Simulation run = start_simulation(scene);
  for (int k = 1; k <= 40 && run.state.status == Status::ok; ++k) advance_to(run, 0.5 * k);
  ASSERT_EQ(run.state.status, Status::diverged);
  const double t = run.state.t;
  Scene small = scene;
  small.integrator.dt = 0.01;
  retune(run, small);
  EXPECT_EQ(run.state.status, Status::ok);
  advance_to(run, t + 1.0);
  EXPECT_EQ(run.state.status, Status::ok);
}

}  // namespace
}  // namespace spinfold
