// A scene on a surface whose curvature varies, run as every scene runs (start_simulation,
// advance_to, retune): the scene's initial values reach the chart-free state of physics-surfaces.md
// §7 (checked against WS1's reference state, with L decomposed by an SVD in revolution_examples.h,
// not by the engine),
// the run reproduces WS1's 30-digit trajectory, a spheroid with a = b runs as the sphere's closed
// chart does, friction obeys dE/dt = −2R, a body passes over an axis point, and the refusals name
// the field.
#include "engine/embedded_run.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <tuple>

#include "engine/integrator.h"
#include "engine/paper_coordinates.h"
#include "engine/simulation.h"
#include "engine/validation.h"
#include "tests/engine/revolution_examples.h"

namespace spinfold {
namespace {

using test::matrix;
using test::ws1_rates;
using test::ws1_scene;
using test::ws1_state;

void expect_close(const Coords& got, const Coords& want, double tolerance) {
  ASSERT_EQ(got.size(), want.size());
  for (Eigen::Index i = 0; i < want.size(); ++i)
    EXPECT_NEAR(got(i), want(i), tolerance * (1.0 + std::abs(want(i)))) << "entry " << i;
}

TEST(EmbeddedRun, TheScenesStartIsWS1sState) {
  const Scene scene = ws1_scene();
  ASSERT_TRUE(validate_scene(scene).empty()) << validate_scene(scene).front().reason;
  const Simulation run = start_simulation(scene);
  ASSERT_NE(run.embedded, nullptr);
  expect_close(run.state.y, Coords(ws1_state()), 1e-14);
  EXPECT_EQ(run.info->name, "dop853");
}

// The run (the engine's dop853, advanced in pieces) against the reference's 30-digit X(2), and the
// read-out against the start's chart values and WS1's invariants.
TEST(EmbeddedRun, RunReproducesWS1sTrajectoryAndReadsBack) {
  const Scene scene = ws1_scene();
  Simulation run = start_simulation(scene);
  const ProfileReadout start = profile_readout(*run.embedded, run.state.y);
  const RevolutionRates r = ws1_rates();
  EXPECT_NEAR(start.coordinates.r, r.u, 1e-14);  // u
  EXPECT_NEAR(*start.coordinates.phi, r.phi, 1e-14);
  EXPECT_NEAR(*start.coordinates.r_dot, r.u_dot, 1e-14);
  EXPECT_NEAR(*start.coordinates.phi_dot, r.phi_dot, 1e-14);
  EXPECT_NEAR((*start.coordinates.L - r.L).norm(), 0.0, 1e-14);
  EXPECT_NEAR(start.coordinates.lambda, scene.initial.lambda, 1e-14);
  EXPECT_NEAR(*start.coordinates.alpha_dot, scene.initial.alpha_dot, 1e-13);
  EXPECT_NEAR(start.K, std::cos(0.7) / (1.0 * (3.0 + std::cos(0.7))),
              1e-15);  // torus: cos u/(a(c + a cos u))
  for (const double t : {0.5, 1.3, 2.0}) ASSERT_TRUE(advance_to(run, t));
  ASSERT_EQ(run.state.status, Status::ok);
  const Eigen::Vector3d X2(2.8242096200506657, -0.6183870861207411, -0.9940546679244858);
  EXPECT_LT((run.state.y.head<3>() - X2).norm(), 1e-11);
  const ProfileReadout later = profile_readout(*run.embedded, run.state.y);
  EXPECT_NEAR(later.coordinates.p_alpha, 0.013627619086836, 1e-12);  // s
  EXPECT_NEAR(later.coordinates.p_phi, -5.678393831313499, 1e-11);
  const EnergyParts e = embedded_energy_parts(*run.embedded, run.state.y);
  EXPECT_NEAR(e.kinetic + e.potential, 0.7726449045081352, 1e-12);
}

// The same times reached in one advance or many give the same state to the bit (the run's own step
// sequence, as on every surface).
TEST(EmbeddedRun, AdvancingInPiecesIsBitExact) {
  Simulation one = start_simulation(ws1_scene()), many = start_simulation(ws1_scene());
  advance_to(one, 3.0);
  for (int k = 1; k <= 30; ++k) advance_to(many, 0.1 * k);
  advance_to(many, 3.0);
  EXPECT_EQ(one.state.y, many.state.y);
}

// Every admitted method and auto run the torus, within the bound it meets on WS1 (embedded_dynamics_test);
// splitting and exact are refused by the validator naming integrator.name.
TEST(EmbeddedRun, EveryAdmittedIntegratorRunsAndTheOthersAreRefused) {
  const Eigen::Vector3d X2(2.8242096200506657, -0.6183870861207411, -0.9940546679244858);
  for (const std::string name : {"auto", "dop853", "rk4", "gauss4", "gauss6", "implicit_midpoint"}) {
    SCOPED_TRACE(name);
    Scene scene = ws1_scene(name);
    scene.integrator.dt = name == "gauss6" ? 0.02 : 1e-3;
    ASSERT_TRUE(validate_scene(scene).empty());
    Simulation run = start_simulation(scene);
    advance_to(run, 2.0);
    ASSERT_EQ(run.state.status, Status::ok);
    EXPECT_LT((run.state.y.head<3>() - X2).norm(), name == "implicit_midpoint" ? 1e-6 : 5e-12);
  }
  for (const std::string name : {"split4", "split6", "exact"}) {
    const std::vector<FieldError> errors = validate_scene(ws1_scene(name));
    ASSERT_FALSE(errors.empty()) << name;
    EXPECT_EQ(errors.front().field, "integrator.name");
    EXPECT_NE(errors.front().reason.find("torus"), std::string::npos) << errors.front().reason;
  }
}

// ---- only the orbit stepped (physics-surfaces.md §4, decoupling) ----------------------------

// WS1's torus, gravity and abc with an isotropic body (J = 0.4): the internal motion has a closed form.
Scene isotropic_torus(Stepping stepping) {
  Scene scene = ws1_scene();
  scene.body.inertia_matrix.reset();
  scene.body.inertia = 0.4;
  scene.integrator = {"dop853", 0.01, 1e-12, stepping};
  return scene;
}

// What is stepped: the orbit alone only where the internal motion has a closed form.
TEST(OrbitOnly, ChosenOnlyWhereTheInternalMotionHasAClosedForm) {
  EXPECT_TRUE(steps_orbit_only(isotropic_torus(Stepping::automatic)));
  EXPECT_FALSE(steps_orbit_only(isotropic_torus(Stepping::full)));
  EXPECT_FALSE(steps_orbit_only(ws1_scene()));  // anisotropic J
  Scene polar = isotropic_torus(Stepping::automatic);
  polar.potential.deformation = PolarPotential{0.1, -0.2, PolarForm::cot2};
  EXPECT_FALSE(steps_orbit_only(polar));
  Scene damped = isotropic_torus(Stepping::automatic);
  damped.friction = Friction{0.1, 0.0};
  EXPECT_TRUE(steps_orbit_only(damped));  // translational friction acts on the orbit alone
  damped.friction = Friction{0.1, 0.05};
  EXPECT_FALSE(steps_orbit_only(damped));
  Scene rigid = isotropic_torus(Stepping::automatic);
  rigid.body.model = BodyModel::rigid;
  rigid.potential.deformation = std::monostate{};
  EXPECT_FALSE(steps_orbit_only(rigid));  // already 10 numbers, its own closed form for the frame
  Scene free_body = isotropic_torus(Stepping::automatic);
  free_body.potential.deformation = std::monostate{};
  EXPECT_TRUE(steps_orbit_only(free_body));
  Scene sphere;
  EXPECT_FALSE(steps_orbit_only(sphere));
  const Simulation run = start_simulation(isotropic_torus(Stepping::automatic));
  EXPECT_TRUE(run.embedded->orbit_only);
}

// The same motion as stepping all 18 numbers (a different computation of the internal state: the
// integrator against physics.md §8.3's closed form in the transported frame), at every read-out,
// with translational friction too, over T = 20.
TEST(OrbitOnly, AgreesWithSteppingEverything) {
  for (const bool friction : {false, true}) {
    SCOPED_TRACE(friction ? "friction" : "no friction");
    Scene a = isotropic_torus(Stepping::automatic), b = isotropic_torus(Stepping::full);
    if (friction) a.friction = b.friction = Friction{0.05, 0.0};
    Simulation orbit = start_simulation(a), all = start_simulation(b);
    ASSERT_TRUE(orbit.embedded->orbit_only);
    ASSERT_FALSE(all.embedded->orbit_only);
    for (const double t : {0.0, 1.0, 7.5, 20.0}) {
      advance_to(orbit, t);
      advance_to(all, t);
      ASSERT_EQ(orbit.state.status, Status::ok);
      const EmbeddedBody p = embedded_body(*orbit.embedded, orbit.state.y),
                         q = embedded_body(*all.embedded, all.state.y);
      EXPECT_LT((p.X - q.X).norm(), 1e-9) << "t = " << t;
      EXPECT_LT((p.V - q.V).norm(), 1e-9);
      for (int A = 0; A < 2; ++A) {
        EXPECT_LT((p.e[A] - q.e[A]).norm(), 1e-9) << "t = " << t;
        EXPECT_LT((p.W[A] - q.W[A]).norm(), 1e-9) << "t = " << t;
      }
      const ProfileReadout ro = profile_readout(*orbit.embedded, orbit.state.y);
      const ProfileReadout ra = profile_readout(*all.embedded, all.state.y);
      EXPECT_NEAR(ro.coordinates.p_alpha, ra.coordinates.p_alpha, 1e-10);
      EXPECT_NEAR(ro.coordinates.p_phi, ra.coordinates.p_phi, 1e-9);
      EXPECT_NEAR(ro.coordinates.det_L, ra.coordinates.det_L, 1e-9);
      const EnergyParts eo = embedded_energy_parts(*orbit.embedded, orbit.state.y);
      const EnergyParts ea = embedded_energy_parts(*all.embedded, all.state.y);
      EXPECT_NEAR(eo.kinetic + eo.potential, ea.kinetic + ea.potential, 1e-10);
    }
    // it did fewer evaluations' worth of steps: the internal time scale no longer sets the step
    EXPECT_LE(orbit.steps, all.steps);
  }
}

// det L = 0 crossings (a body squashed through a segment under C < 0) are found at the same times, and
// a change of parameters mid-run (a stiffer potential, then anisotropic J: the internal motion then
// needs stepping) continues both runs alike.
TEST(OrbitOnly, EventsAndChangesOfParametersAsSteppingEverything) {
  Scene a = isotropic_torus(Stepping::automatic), b = isotropic_torus(Stepping::full);
  a.potential.deformation = b.potential.deformation = AbcPotential{0.0, 0.0, -0.05};
  a.initial.mu = b.initial.mu = 0.08;
  a.initial.mu_dot = b.initial.mu_dot = -0.4;
  ASSERT_TRUE(validate_scene(a).empty());
  Simulation orbit = start_simulation(a), all = start_simulation(b);
  advance_to(orbit, 3.0);
  advance_to(all, 3.0);
  ASSERT_FALSE(all.events.empty());
  ASSERT_EQ(orbit.events.size(), all.events.size());
  for (std::size_t i = 0; i < all.events.size(); ++i) EXPECT_NEAR(orbit.events[i].t, all.events[i].t, 1e-9);

  Scene a2 = a, b2 = b;
  a2.potential.deformation = b2.potential.deformation = AbcPotential{0.01, 0.02, 0.3};
  retune(orbit, a2);
  retune(all, b2);
  ASSERT_TRUE(orbit.embedded->orbit_only);
  Scene a3 = a2, b3 = b2;
  a3.body.inertia_matrix = b3.body.inertia_matrix = InertiaMatrix{0.4, 0.05, 0.05, 0.3};
  for (const auto& [t, sa, sb] : {std::tuple{5.0, &a2, &b2}, std::tuple{8.0, &a3, &b3}}) {
    if (sa == &a3) {
      retune(orbit, a3);
      retune(all, b3);
      ASSERT_FALSE(orbit.embedded->orbit_only);  // anisotropic: the internal motion is stepped now
    }
    advance_to(orbit, t);
    advance_to(all, t);
    const EmbeddedBody p = embedded_body(*orbit.embedded, orbit.state.y),
                       q = embedded_body(*all.embedded, all.state.y);
    EXPECT_LT((p.X - q.X).norm(), 1e-9) << "t = " << t;
    EXPECT_LT((p.e[0] - q.e[0]).norm(), 1e-8) << "t = " << t;
    EXPECT_LT((p.W[1] - q.W[1]).norm(), 1e-8) << "t = " << t;
  }
}

// A spheroid with a = b = R runs as the sphere's chart does (a different formulation: closed-form
// polar chart, recentred): u = r/R, the same frame E₁ (away from the north pole), E₂.
TEST(EmbeddedRun, SpheroidWithEqualAxesIsTheSphere) {
  const double R = 1.3;
  Scene sphere;
  sphere.surface = {SurfaceKind::sphere, R};
  sphere.body = {1.5, 0.2, BodyModel::affine};
  sphere.potential.deformation = AbcPotential{0.0, 0.0, 0.4};
  sphere.initial = {1.1, 0.4, 0.3, -0.2, 1.2, 0.7, 0.35, 0.6, 1.1, -0.3, 0.05, -0.1};
  sphere.integrator = {"dop853", 0.01, 1e-13};
  Scene spheroid = sphere;
  spheroid.surface.kind = SurfaceKind::spheroid;
  spheroid.surface.equatorial_radius = spheroid.surface.polar_radius = R;
  spheroid.initial.u = sphere.initial.r / R;
  spheroid.initial.u_dot = sphere.initial.r_dot / R;
  ASSERT_TRUE(validate_scene(spheroid).empty());
  Simulation a = start_simulation(sphere), b = start_simulation(spheroid);
  for (const double t : {1.0, 4.0, 8.0}) {
    advance_to(a, t);
    advance_to(b, t);
    ASSERT_EQ(b.state.status, Status::ok);
    const PaperCoordinates pa = paper_coordinates(sphere, a.state);
    const PaperCoordinates pb = profile_readout(*b.embedded, b.state.y).coordinates;
    EXPECT_LT((pa.X - pb.X).norm(), 1e-10) << "t = " << t;
    EXPECT_NEAR(pa.r / R, pb.r, 1e-10);
    EXPECT_LT((*pa.L - *pb.L).norm(), 1e-10);
    EXPECT_NEAR(pa.p_alpha, pb.p_alpha, 1e-10);
    EXPECT_NEAR(pa.p_phi, pb.p_phi, 1e-10);
  }
}

// Friction (§13): E(T) − E(0) = −∫₀ᵀ 2R dt (the integral by Simpson's rule on the run's samples), and
// the energy falls at every sample; the health check does not take the fall for divergence.
TEST(EmbeddedRun, FrictionDissipatesAsRayleighSays) {
  Scene scene = ws1_scene();
  scene.potential.height = std::monostate{};  // a height potential's work would enter the balance
  scene.friction = Friction{0.1, 0.05};
  ASSERT_TRUE(validate_scene(scene).empty());
  Simulation run = start_simulation(scene);
  const auto energy_now = [&] {
    const EnergyParts e = embedded_energy_parts(*run.embedded, run.state.y);
    return e.kinetic + e.potential;
  };
  const double E0 = energy_now();
  const int n = 400;  // even, for Simpson
  const double T = 4.0, h = T / n;
  double integral = 0.0, previous = E0;
  for (int k = 0; k <= n; ++k) {
    advance_to(run, k * h);
    ASSERT_EQ(run.state.status, Status::ok);
    const double R = embedded_dissipation(*run.embedded, run.state.y);
    integral += (k == 0 || k == n ? 1.0 : k % 2 ? 4.0 : 2.0) * 2.0 * R;
    const double E = energy_now();
    EXPECT_LE(E, previous + 1e-13);
    previous = E;
  }
  integral *= h / 3.0;
  EXPECT_NEAR(energy_now() - E0, -integral, 1e-8);
  EXPECT_LT(energy_now(), E0 - 0.05);  // a real loss, not round-off
}

// Over the bump's top (an axis point): a body started towards the axis passes it with energy, spin
// and p_φ kept; the read-out at the axis names φ as undefined.
TEST(EmbeddedRun, PassesOverTheBumpsTop) {
  Scene scene;
  scene.surface.kind = SurfaceKind::bump;
  scene.surface.height = 0.8;
  scene.surface.width = 1.0;
  scene.body = {1.0, 0.1, BodyModel::affine};
  scene.potential.deformation = AbcPotential{0.0, 0.0, 0.3};
  scene.initial.u = 0.5;
  scene.initial.u_dot = -1.0;
  scene.initial.lambda = 1.1;
  scene.initial.mu = 0.8;
  scene.integrator = {"dop853", 0.01, 1e-12};
  ASSERT_TRUE(validate_scene(scene).empty());
  Simulation run = start_simulation(scene);
  const EmbeddedScene& model = *run.embedded;
  const auto energy_of = [&](const Coords& y) {
    const EnergyParts e = embedded_energy_parts(model, y);
    return e.kinetic + e.potential;
  };
  const double E0 = energy_of(run.state.y), s0 = embedded_spin_of(model, run.state.y);
  const double p0 = embedded_p_phi(model, run.state.y);
  advance_to(run, 1.2);
  ASSERT_EQ(run.state.status, Status::ok);
  const ProfileReadout after = profile_readout(model, run.state.y);
  EXPECT_GT(after.coordinates.r, 0.1);                                                     // u: out again,
  EXPECT_GT(std::abs(std::remainder(*after.coordinates.phi, 2 * std::numbers::pi)), 3.0);  // opposite side
  EXPECT_NEAR(energy_of(run.state.y), E0, 1e-10);
  EXPECT_NEAR(embedded_spin_of(model, run.state.y), s0, 1e-10);
  EXPECT_NEAR(embedded_p_phi(model, run.state.y), p0, 1e-10);
  // The start on the axis itself: φ is undefined and said so.
  scene.initial.u = 0.0;
  const Simulation top = start_simulation(scene);
  const ProfileReadout on_axis = profile_readout(*top.embedded, top.state.y);
  EXPECT_FALSE(on_axis.coordinates.phi.has_value());
  EXPECT_NEAR(on_axis.K, 0.8 * 0.8, 1e-12);  // both principal curvatures h/w² at the top: K = h²/w⁴
}

// A rigid body on the torus: 10 numbers; energy and spin kept; the spin's rate kept when retune
// changes the inertia (s scales with it).
TEST(EmbeddedRun, RigidBodyStepsTenNumbers) {
  Scene scene = ws1_scene();
  scene.body.model = BodyModel::rigid;
  scene.body.inertia_matrix.reset();
  scene.body.inertia = 0.3;
  scene.potential.deformation = std::monostate{};
  scene.initial.mu = scene.initial.lambda;
  scene.initial.lambda_dot = scene.initial.mu_dot = 0.0;
  ASSERT_TRUE(validate_scene(scene).empty()) << validate_scene(scene).front().reason;
  Simulation run = start_simulation(scene);
  ASSERT_EQ(run.state.y.size(), 10);
  const double E0 = embedded_energy_parts(*run.embedded, run.state.y).kinetic +
                    embedded_energy_parts(*run.embedded, run.state.y).potential;
  const double s0 = embedded_spin_of(*run.embedded, run.state.y);
  advance_to(run, 5.0);
  const EnergyParts e = embedded_energy_parts(*run.embedded, run.state.y);
  EXPECT_NEAR(e.kinetic + e.potential, E0, 1e-11);
  EXPECT_EQ(embedded_spin_of(*run.embedded, run.state.y), s0);  // ṡ = 0 exactly without friction
  Scene heavier = scene;
  heavier.body.inertia = 0.6;
  retune(run, heavier);
  EXPECT_NEAR(embedded_spin_of(*run.embedded, run.state.y), 2.0 * s0, 1e-15);
}

// What does not belong on a surface whose curvature varies, and its own rules, refused naming the
// field.
TEST(EmbeddedRun, RefusalsNameTheField) {
  const auto first_field = [](const Scene& s) {
    const std::vector<FieldError> e = validate_scene(s);
    return e.empty() ? std::string("(accepted)") : e.front().field;
  };
  Scene s = ws1_scene();
  s.surface.center_radius = 1.0;  // = a
  EXPECT_EQ(first_field(s), "surface.center_radius");
  s = ws1_scene();
  s.surface.kind = SurfaceKind::spheroid;
  s.initial.u = 3.5;  // past the south pole
  EXPECT_EQ(first_field(s), "initial.u");
  s = ws1_scene();
  s.surface.kind = SurfaceKind::bump;
  s.initial.u = -0.1;
  EXPECT_EQ(first_field(s), "initial.u");
  s = ws1_scene();
  s.body.model = BodyModel::incompressible;
  s.initial.mu_dot = -s.initial.lambda_dot * s.initial.mu / s.initial.lambda;
  s.integrator.name = "auto";
  EXPECT_EQ(first_field(s), "body.model");
  s = ws1_scene();
  s.potential.radial = RadialPotential{0.1};
  EXPECT_EQ(first_field(s), "potential.radial");
  // The height potential needs an embedded height: the sphere has one, the plane (z = 0) and the
  // pseudosphere have not; friction acts on every surface (dynamics_test).
  Scene flat;
  flat.surface = Surface(SurfaceKind::plane, 1.0);
  flat.initial.r = 0.5;
  flat.potential.height = GravityPotential{1.0};
  EXPECT_EQ(first_field(flat), "potential.height");
  flat.surface.kind = SurfaceKind::pseudosphere;
  EXPECT_EQ(first_field(flat), "potential.height");
  flat.surface.kind = SurfaceKind::sphere;
  EXPECT_EQ(first_field(flat), "(accepted)");
  flat.friction = Friction{0.1, 0.0};
  EXPECT_EQ(first_field(flat), "(accepted)");
  s = ws1_scene();
  s.surface.width = 0.0;
  s.surface.kind = SurfaceKind::bump;
  EXPECT_EQ(first_field(s), "surface.width");
}

}  // namespace
}  // namespace spinfold
