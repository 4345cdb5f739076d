// Runs as a whole: invariants along runs, det L = 0 crossings, failed steps, reproducibility.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <numbers>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/exact_solution.h"
#include "engine/invariants.h"
#include "engine/paper_coordinates.h"
#include "test_support.h"

namespace spinfold {
namespace {

struct ConservationCase {
  const char* name;
  Scene scene;
};

Scene deforming(SurfaceKind kind, double R) {
  Scene s;
  s.surface = {kind, R};
  s.body = {1.3, 0.3, BodyModel::affine};
  s.initial = {1.1, 0.2, 0.3, -0.4, 1.4, 0.6, 0.2, 0.5, 0.6, -0.2, 0.1, -0.05};
  s.integrator = {"dop853", 0.01, 1e-12};
  return s;
}

std::vector<ConservationCase> conservation_cases() {
  std::vector<ConservationCase> cases;
  Scene a = deforming(SurfaceKind::sphere, 1.0);
  a.potential.radial = RadialPotential{0.05};
  a.potential.deformation = AbcPotential{0.02, 0.1, 0.4};
  cases.push_back({"sphere_radial_abc", a});
  Scene b = deforming(SurfaceKind::pseudosphere, 1.5);
  b.potential.radial = RadialPotential{0.1};
  b.potential.deformation = AbcPotential{0.0, 0.05, 0.3};
  cases.push_back({"pseudosphere_radial_abc", b});
  Scene c = deforming(SurfaceKind::sphere, 2.0);
  c.potential.deformation = PolarPotential{0.05, -1.0, PolarForm::cot2};
  cases.push_back({"sphere_polar_cot2", c});
  Scene d = deforming(SurfaceKind::pseudosphere, 1.0);
  d.potential.deformation = PolarPotential{0.05, -1.0, PolarForm::literal};
  cases.push_back({"pseudosphere_polar_literal", d});
  Scene e = deforming(SurfaceKind::sphere, 1.0);  // free body, no potential
  cases.push_back({"sphere_free", e});
  Scene f = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.4, 1.2);
  f.potential.radial = RadialPotential{0.08};
  f.initial.r = 1.0;
  test::set_rigid_motion(f, 0.7, 1.0, 0.8);
  cases.push_back({"sphere_rigid_radial", f});
  return cases;
}

// Energy, p_φ, s, p_β, E_orb, C_x, C_y and (without V_r) M stay at their initial values to the
// accuracy DOP853 reaches at tolerance 1e-12 (global error ~1e-10 over t = 20).
TEST(Conservation, InvariantsAlongRuns) {
  for (const ConservationCase& c : conservation_cases()) {
    SCOPED_TRACE(c.name);
    const Scene& scene = c.scene;
    Simulation run = start_simulation(scene);
    const State s0 = run.state;
    const auto sep0 = separated_energies(scene, s0);
    const auto M0 = momentum_map(scene, s0);
    for (int k = 1; k <= 20; ++k) {
      advance_to(run, static_cast<double>(k));
      ASSERT_EQ(run.state.status, Status::ok);
      const State& s = run.state;
      const double tol = 1e-9;
      EXPECT_NEAR(energy(scene, s), energy(scene, s0), tol * std::abs(energy(scene, s0)));
      EXPECT_NEAR(orbital_energy(scene, s), orbital_energy(scene, s0), tol);
      // Relative: far out on H² the charts move and p_φ of the scene's chart is read back through
      // them (the pseudosphere case drifts 1.3e-9 of 2.17 by t = 20, also with one advance).
      EXPECT_NEAR(angular_momentum(scene, s), angular_momentum(scene, s0),
                  tol * std::max(1.0, std::abs(angular_momentum(scene, s0))));
      EXPECT_NEAR(spin(scene, s), spin(scene, s0), tol);
      EXPECT_NEAR(vorticity(scene, s), vorticity(scene, s0), tol);
      if (sep0) {
        const auto sep = separated_energies(scene, s);
        EXPECT_NEAR(sep->C_x, sep0->C_x, tol);
        EXPECT_NEAR(sep->C_y, sep0->C_y, tol);
      }
      if (M0) {
        EXPECT_LT((*momentum_map(scene, s) - *M0).norm(), tol);
      }
    }
  }
}

TEST(RigidModel, IntegratesNoDeformationDegreesOfFreedom) {
  Scene scene = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  EXPECT_EQ(initial_state(scene).y.size(), coord::rigid_size);
  scene.body.model = BodyModel::affine;
  EXPECT_EQ(initial_state(scene).y.size(), coord::affine_size);
}

// physics.md §8.8: the rigid model coincides with the affine one started at λ = μ = λ₀ with
// λ̇ = μ̇ = 0 under abc with A = B = 0 and C = Jw²/2 (the spin equilibrium).
TEST(RigidModel, MatchesTheAffineBodyAtSpinEquilibrium) {
  Scene rigid = test::rigid_scene(SurfaceKind::pseudosphere, 1.0, 1.0, 0.5, 1.0);
  rigid.initial.r = 1.2;
  test::set_rigid_motion(rigid, 0.6, 0.8, 0.9);
  const double w = 0.9 / (2.0 * 0.5);  // s = 2Jλ₀² w
  Scene affine = rigid;
  affine.body.model = BodyModel::affine;
  affine.potential.deformation = AbcPotential{0.0, 0.0, 0.5 * w * w / 2.0};  // C = Jw²/2, J = 0.5
  const Simulation a = test::run_to(rigid, 10.0), b = test::run_to(affine, 10.0);
  const EmbeddedBody ea = global_embedding(rigid, a.state), eb = global_embedding(affine, b.state);
  EXPECT_LT((ea.X - eb.X).norm(), 1e-10);
  EXPECT_LT((ea.e[0] - eb.e[0]).norm(), 1e-10);
  EXPECT_LT((ea.e[1] - eb.e[1]).norm(), 1e-10);
}

TEST(DegenerateFrame, CrossingIsFollowedAndReported) {
  Scene scene = test::degenerate_crossing_scene();
  scene.integrator = {"dop853", 0.01, 1e-12};
  Simulation run = start_simulation(scene);
  const double H0 = energy(scene, run.state);
  advance_to(run, 1.0);
  EXPECT_EQ(run.state.status, Status::ok);
  ASSERT_EQ(run.events.size(), 1u);
  EXPECT_NEAR(run.events[0].t, 0.5, 1e-10);
  EXPECT_NEAR(det_L(scene, run.state), -0.3, 1e-10);  // det L = λ(0.3 − 0.6t) at t = 1
  EXPECT_NEAR(energy(scene, run.state), H0, 1e-10);
  const PaperCoordinates c = paper_coordinates(scene, run.state);
  EXPECT_NEAR(c.mu, -0.3, 1e-10);  // mirrored: μ < 0 after the crossing
}

TEST(DegenerateFrame, StopKeepsTheLastGoodState) {
  Scene scene;
  scene.surface = {SurfaceKind::pseudosphere, 1.0};
  scene.body = {1.0, 0.1, BodyModel::affine};
  scene.initial.r = 1.0;
  scene.initial.lambda = 1.0;
  scene.initial.mu = 0.2;
  scene.initial.mu_dot = -1.0;
  scene.on_degenerate = OnDegenerate::stop;
  Simulation run = start_simulation(scene);
  advance_to(run, 1.0);
  EXPECT_EQ(run.state.status, Status::degenerate_frame);
  ASSERT_EQ(run.events.size(), 1u);
  EXPECT_NEAR(run.events[0].t, 0.2, 1e-10);
  EXPECT_LE(run.state.t, run.events[0].t);
  EXPECT_GT(det_L(scene, run.state), 0.0);
  const State stopped = run.state;
  advance_to(run, 2.0);  // a stopped run stays where it stopped
  EXPECT_EQ(run.state.t, stopped.t);
  EXPECT_EQ(run.state.y, stopped.y);
}

// An integrator that returns garbage: the run must keep its last good state and say why.
class PoisonIntegrator final : public Integrator {
 public:
  explicit PoisonIntegrator(bool adaptive) : info_{"poison", 1, false, adaptive, false, "test"} {}
  const IntegratorInfo& info() const override { return info_; }
  StepResult try_step(const StepProblem&, const Coords& y, double h, double, Coords& increment) override {
    increment = Coords::Zero(y.size());
    increment[0] = std::numeric_limits<double>::quiet_NaN();
    return {true, h};
  }

 private:
  IntegratorInfo info_;
};

TEST(FailedStep, NonFiniteStepLeavesTheStateUnchanged) {
  for (bool adaptive : {false, true}) {
    Scene scene = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
    test::set_rigid_motion(scene, 0.5, 1.0, 0.2);
    Simulation run = start_simulation(scene);
    advance_to(run, 0.5);
    const State before = run.state;
    run.integrator = std::make_unique<PoisonIntegrator>(adaptive);
    advance_to(run, 1.0);
    EXPECT_EQ(run.state.status, Status::non_finite);
    EXPECT_EQ(run.state.t, before.t);
    EXPECT_EQ(run.state.y, before.y);
    EXPECT_TRUE(std::isfinite(energy(scene, run.state)));
  }
}

TEST(FailedStep, StepSizeUnderflowStopsWithStepFailed) {
  class Rejecting final : public Integrator {
   public:
    const IntegratorInfo& info() const override { return dop853_info; }
    StepResult try_step(const StepProblem&, const Coords& y, double h, double, Coords& increment) override {
      increment = Coords::Zero(y.size());
      return {false, h / 10.0};
    }
  };
  Scene scene = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  Simulation run = start_simulation(scene);
  const State before = run.state;
  run.integrator = std::make_unique<Rejecting>();
  advance_to(run, 1.0);
  EXPECT_EQ(run.state.status, Status::step_failed);
  EXPECT_EQ(run.state.y, before.y);
}

// RK4 with a step far beyond its stability blows the state up to 1e40 and beyond while every
// number stays finite. The run stops as diverged on the last state whose energy was right.
TEST(FailedStep, UnstableFixedStepStopsAsDivergedOnTheLastGoodState) {
  Scene scene;
  scene.surface = {SurfaceKind::plane, 0.001};  // the plane's radius sets where charts move
  scene.initial.r = 0.0;
  scene.initial.phi = -3.568627450980415;
  scene.initial.alpha = 0.5;
  scene.initial.beta = 1.0;
  scene.initial.alpha_dot = scene.initial.beta_dot = 1.0;
  scene.initial.lambda_dot = scene.initial.mu_dot = 1.0;
  scene.integrator = {"rk4", 1.5707963267948966, 1e-10};
  Simulation run = start_simulation(scene);
  for (int k = 1; k <= 10; ++k) advance_to(run, 0.5 * k);
  EXPECT_EQ(run.state.status, Status::diverged);
  // The run's own steps are dt = π/2 long (advances to 0.5, 1, … land by a cut step from them):
  // the energy shows the blow-up in the cut step from 2 dt to 3.5, so 2 dt is the last good state.
  EXPECT_EQ(run.state.t, 2 * scene.integrator.dt);
  EXPECT_TRUE(run.state.y.allFinite());
  EXPECT_LT(std::abs(energy(scene, run.state) - run.initial_energy), 0.1 * run.energy_scale);
}

// An unbounded potential (C < 0) lets the frame grow exponentially: the energy error grows with the
// energies far beyond the initial scale, yet stays tiny against the current one: not diverged.
TEST(FailedStep, ExponentialGrowthIsNotDivergence) {
  Scene scene;
  scene.body = {1.0, 0.1, BodyModel::affine};
  scene.potential.deformation = AbcPotential{0.0, 0.0, -1.0};
  scene.initial.lambda = 1.2;
  scene.initial.mu = 0.8;
  scene.integrator = {"dop853", 0.01, 1e-10};
  Simulation run = start_simulation(scene);
  for (int k = 1; k <= 60; ++k) advance_to(run, 0.1 * k);
  EXPECT_EQ(run.state.status, Status::ok);
  EXPECT_EQ(run.state.t, 6.0);
  EXPECT_GT(std::abs(energy(scene, run.state) - run.initial_energy), run.energy_scale);
}

// Far out on H² the global embedding grows as e^{r/R}: the run stops before its outputs overflow,
// on the last state within 250 R, whose outputs are all finite.
TEST(OutOfRange, FarOutOnThePseudosphereStopsBeforeTheOutputsOverflow) {
  for (const char* integrator : {"auto", "dop853"}) {
    Scene scene = test::rigid_scene(SurfaceKind::pseudosphere, 1.0, 1.0, 0.5, 1.0);
    scene.integrator.name = integrator;
    test::set_rigid_motion(scene, 100.0, 0.3, 2.0);
    Simulation run = start_simulation(scene);
    for (int k = 1; k <= 40 && run.state.status == Status::ok; ++k) advance_to(run, 0.1 * k);
    EXPECT_EQ(run.state.status, Status::out_of_range) << integrator;
    const PaperCoordinates c = paper_coordinates(scene, run.state);
    EXPECT_GT(c.r, 200.0) << integrator;
    EXPECT_LE(c.r, kMaxHyperbolicDistance) << integrator;
    EXPECT_TRUE(c.X.allFinite()) << integrator;
    EXPECT_TRUE(std::isfinite(c.p_phi) && std::isfinite(c.lambda) && std::isfinite(c.det_L)) << integrator;
    ASSERT_TRUE(c.phi && c.r_dot) << integrator;
    EXPECT_TRUE(std::isfinite(*c.phi) && std::isfinite(*c.r_dot)) << integrator;
  }
}

TEST(Reproducibility, SameSceneSameBits) {
  for (const ConservationCase& c : conservation_cases()) {
    const Simulation a = test::run_to(c.scene, 7.0), b = test::run_to(c.scene, 7.0);
    ASSERT_EQ(a.state.y.size(), b.state.y.size());
    EXPECT_EQ(std::memcmp(a.state.y.data(), b.state.y.data(), sizeof(double) * a.state.y.size()), 0)
        << c.name;
    EXPECT_EQ(a.steps, b.steps);
  }
}

TEST(StepBudget, StopsEarlyAndContinuesToTheSameBits) {
  for (const ConservationCase& c : conservation_cases()) {
    const Simulation whole = test::run_to(c.scene, 3.0);
    Simulation pieces = start_simulation(c.scene);
    int calls = 0;
    while (!advance_to(pieces, 3.0, 7)) {
      ++calls;
      EXPECT_EQ(pieces.state.status, Status::ok) << c.name;
      EXPECT_LT(pieces.state.t, 3.0) << c.name;
      ASSERT_LT(calls, 100000) << c.name;
    }
    EXPECT_EQ(pieces.state.t, 3.0) << c.name;
    if (whole.exact) continue;  // one attempt: nothing to cut
    EXPECT_GT(calls, 0) << c.name;
    ASSERT_EQ(pieces.state.y.size(), whole.state.y.size());
    EXPECT_EQ(std::memcmp(pieces.state.y.data(), whole.state.y.data(), sizeof(double) * whole.state.y.size()),
              0)
        << c.name;
    EXPECT_EQ(pieces.steps, whole.steps) << c.name;
  }
}

TEST(StepBudget, ZeroAttemptsChangeNothing) {
  const Scene scene = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  Simulation run = start_simulation(scene);
  EXPECT_FALSE(advance_to(run, 1.0, 0));
  EXPECT_EQ(run.state.t, 0.0);
  EXPECT_EQ(run.steps, 0u);
}

TEST(Rk4, FourthOrderOnTheSpinningCircle) {
  Scene scene = test::rigid_scene(SurfaceKind::sphere, 1.0, 1.0, 0.5, 1.0);
  scene.initial.r = 1.0;
  test::set_rigid_motion(scene, 0.5, std::numbers::pi / 2, 1.0);
  const Vec3 reference = global_embedding(scene, test::run_to(scene, 2.0).state).X;
  scene.integrator.name = "rk4";
  double previous = 0.0;
  for (double dt : {0.04, 0.02, 0.01}) {
    scene.integrator.dt = dt;
    const double err = (global_embedding(scene, test::run_to(scene, 2.0).state).X - reference).norm();
    if (previous > 0.0) {
      EXPECT_NEAR(std::log2(previous / err), 4.0, 0.3);
    }
    previous = err;
  }
}

// A free-ish body whose frame passes det L = 0 about once a second (abc with C > 0, A = B = 0:
// L oscillates through the degenerate set).
Scene oscillating_through_degenerate() {
  Scene s;
  s.surface = {SurfaceKind::sphere, 1.0};
  s.body = {1.0, 0.1, BodyModel::affine};
  s.potential.deformation = AbcPotential{0.0, 0.0, 0.5};
  s.initial = {1.2, 0.0, 0.0, 0.0, 1.0, 0.3, 0.0, 0.4, 0.3, 0.0, 0.0, -2.0};
  s.integrator = {"auto", 0.01, 1e-10};
  return s;
}

struct Sampled {
  std::vector<double> events;  // as the samples list them
  State last;
  std::vector<double> last_sample_events;
};

// Advances to `until` by samples `every` apart, collecting the events each sample lists (what
// `spinfold simulate --every` prints).
Sampled sample(const Scene& scene, double every, double until) {
  Simulation run = start_simulation(scene);
  Sampled out;
  double listed = run.state.t;
  for (int k = 1; run.state.status == Status::ok; ++k) {
    const double t = std::min(until, k * every);
    advance_to(run, t);
    out.last_sample_events.clear();
    for (const DegenerateEvent& e : events_after(run, listed)) {
      out.events.push_back(e.t);
      out.last_sample_events.push_back(e.t);
    }
    listed = run.state.t;
    if (t >= until) break;
  }
  out.last = run.state;
  return out;
}

// The same scene gives the same det L = 0 events and the same stop whatever the sampling, for
// every catalog integrator and auto; a stop lands on the first crossing and its sample lists it.
TEST(Events, IndependentOfSamplingForEveryIntegrator) {
  std::vector<std::string> names{"auto"};
  for (const CatalogEntry& e : integrator_catalog()) names.emplace_back(e.info.name);
  const Scene base = oscillating_through_degenerate();
  const std::vector<double> reference = sample(
                                            [&] {
                                              Scene s = base;
                                              s.integrator.name = "exact";
                                              return s;
                                            }(),
                                            10.0, 10.0)
                                            .events;
  ASSERT_GE(reference.size(), 10u);
  for (const std::string& name : names) {
    Scene scene = base;
    scene.integrator.name = name;
    if (name == "rk4" || name == "implicit_midpoint") scene.integrator.dt = 0.001;
    const Sampled coarse = sample(scene, 10.0, 10.0);
    ASSERT_EQ(coarse.events.size(), reference.size()) << name;
    // Against the closed form: each integrator's own accuracy (implicit_midpoint, order 2 at
    // dt = 0.001, is the least accurate at ~1e-5).
    for (std::size_t i = 0; i < reference.size(); ++i)
      EXPECT_NEAR(coarse.events[i], reference[i], 1e-4) << name;
    Scene stopping = scene;
    stopping.on_degenerate = OnDegenerate::stop;
    const Sampled coarse_stop = sample(stopping, 10.0, 10.0);
    EXPECT_EQ(coarse_stop.last.status, Status::degenerate_frame) << name;
    EXPECT_NEAR(coarse_stop.last.t, reference[0], 1e-4) << name;
    ASSERT_EQ(coarse_stop.last_sample_events.size(), 1u) << name;
    EXPECT_NEAR(coarse_stop.last_sample_events[0], coarse_stop.last.t, 1e-12) << name;
    EXPECT_GT(det_L(stopping, coarse_stop.last), 0.0) << name;
    for (const double every : {0.01, 0.25, 1.0}) {
      const Sampled fine = sample(scene, every, 10.0);
      ASSERT_EQ(fine.events.size(), coarse.events.size()) << name << " every " << every;
      for (std::size_t i = 0; i < fine.events.size(); ++i)
        EXPECT_NEAR(fine.events[i], coarse.events[i], 1e-12) << name << " every " << every;
      const Sampled fine_stop = sample(stopping, every, 10.0);
      EXPECT_EQ(fine_stop.last.status, Status::degenerate_frame) << name << " every " << every;
      EXPECT_NEAR(fine_stop.last.t, coarse_stop.last.t, 1e-12) << name << " every " << every;
      ASSERT_EQ(fine_stop.last_sample_events.size(), 1u) << name << " every " << every;
      EXPECT_NEAR(fine_stop.last_sample_events[0], coarse_stop.last_sample_events[0], 1e-12) << name;
    }
  }
}

// An unbounded deformation potential (abc with C < 0): the closed form is right but its state's
// invariants stop carrying 8 digits as the motion grows. The run stops `inconsistent` (never ok with
// an energy error of order 1) at a sampling-independent time, on a state that passes the checks.
TEST(ExactCheck, UnboundedPotentialStopsOnACheckedState) {
  Scene scene;
  scene.surface = {SurfaceKind::sphere, 1.0};
  scene.body = {1.0, 0.4, BodyModel::affine};
  scene.potential.deformation = AbcPotential{0.02, 0.4, -0.3};
  scene.initial = {1.2, 0.0, 0.0, 0.0, 1.1, 0.6, 0.0, 0.4, 0.5, 0.2, 0.0, 0.05};
  scene.integrator = {"exact", 0.01, 1e-10};
  std::optional<double> stop_t;
  for (const double every : {0.1, 1.0, 5.0, 40.0}) {
    Simulation run = start_simulation(scene);
    for (int k = 1; k * every <= 40.0 && run.state.status == Status::ok; ++k) {
      advance_to(run, k * every);
      const double error = std::abs(energy(scene, run.state) - run.initial_energy);
      EXPECT_LE(error, 1e-8 * run.energy_scale) << "every " << every << " t " << run.state.t;
    }
    EXPECT_EQ(run.state.status, Status::inconsistent) << every;
    if (!stop_t) stop_t = run.state.t;
    EXPECT_NEAR(run.state.t, *stop_t, 1e-9) << every;
  }
  EXPECT_GT(*stop_t, 1.0);
}

// The check is independent of the closed form: a closed form with a wrong constant (the p_φ of the
// wrong chart, as before issue 22) is caught at the first sample, and the run keeps its start.
TEST(ExactCheck, AWrongClosedFormIsNeverOk) {
  Scene scene = test::w5_scene();
  scene.integrator = {"exact", 0.01, 1e-10};
  Simulation run = start_simulation(scene);
  ASSERT_TRUE(run.exact && run.exact->radial);
  run.exact->radial->p_phi *= 1.0 + 1e-6;
  advance_to(run, 5.0);
  EXPECT_EQ(run.state.status, Status::inconsistent);
  EXPECT_EQ(run.state.t, 0.0);
  Simulation good = start_simulation(scene);
  advance_to(good, 5.0);
  EXPECT_EQ(good.state.status, Status::ok);
}

}  // namespace
}  // namespace spinfold

namespace spinfold {
namespace {

// The closed form jumps any distance in one advance, and a breathing body's det L crosses zero
// twice a period: one advance of 10⁸ listed ~10⁸ crossings (minutes, gigabytes; issue 48's hunt for
// unbounded loops). A run keeps kMaxDegenerateEvents of them, every one, and stops just before the
// one past that with too_many_events, at once.
TEST(Simulation, AClosedFormRunKeepsAtMostItsCrossingsAndStopsBeforeTheNext) {
  Scene s;
  s.surface = {SurfaceKind::sphere, 1.0};
  s.body = {1.0, 0.2, BodyModel::affine};
  s.potential.deformation = AbcPotential{0.0, 0.0, 0.5};
  s.initial.r = 1.2, s.initial.lambda = 1.3, s.initial.mu = 0.7, s.initial.phi_dot = 0.3;
  s.initial.alpha_dot = 0.2, s.initial.lambda_dot = -5.0, s.initial.mu_dot = 3.0;
  s.integrator.name = "exact";
  const auto started = std::chrono::steady_clock::now();
  Simulation run = start_simulation(s);
  advance_to(run, 1e8);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 5.0);
  ASSERT_EQ(run.state.status, Status::too_many_events);
  EXPECT_EQ(run.events.size(), kMaxDegenerateEvents);
  // Every crossing kept, oldest first, the stop before the next: the closed form's own list.
  const std::vector<double> all =
      degenerate_times(*run.exact, 0.0, run.state.t + 10.0, kMaxDegenerateEvents + 1);
  ASSERT_EQ(all.size(), kMaxDegenerateEvents + 1);
  for (std::size_t i = 0; i < kMaxDegenerateEvents; i += 9973)
    EXPECT_NEAR(run.events[i].t, all[i], 1e-9 * all[i]);
  EXPECT_LT(run.state.t, all.back());
  EXPECT_GT(run.state.t, all[kMaxDegenerateEvents - 1]);
  // In pieces, the same.
  Simulation pieces = start_simulation(s);
  for (double t = 1e4; t <= 1e6 && pieces.state.status == Status::ok; t += 1e4) advance_to(pieces, t);
  EXPECT_EQ(pieces.state.status, Status::too_many_events);
  EXPECT_EQ(pieces.state.t, run.state.t);
}

}  // namespace
}  // namespace spinfold
