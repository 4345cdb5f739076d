// Invariants far out on H²: computed in the body's chart, or null with a reason (issue 22).
#include "engine/invariants.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/dynamics.h"
#include "engine/paper_coordinates.h"
#include "engine/readout.h"
#include "engine/scene_fields.h"
#include "engine/simulation.h"
#include "engine/surface.h"
#include "revolution_examples.h"
#include "test_support.h"

namespace spinfold {
namespace {

// A spinning rigid body moving round the pole at r0 (tangential velocity v): the casimir is
// m²R²v² − s² (physics.md §6), whatever r0.
Scene circling(double r0, double v, double spin, const char* integrator) {
  Scene scene = test::rigid_scene(SurfaceKind::pseudosphere, 1.0, 1.0, 0.5, 1.0);
  scene.initial.r = r0;
  test::set_rigid_motion(scene, v, 1.2, spin);
  scene.integrator = {integrator, 0.01, 1e-12};
  return scene;
}

TEST(Invariants, CasimirFarOutOnThePseudosphereIsExact) {
  const double v = 0.5, s = 0.3;
  const double expected = v * v - s * s;  // m = R = 1
  for (const double r0 : {1.0, 10.0, 20.0, 30.0}) {
    for (const char* integrator : {"exact", "dop853"}) {
      Simulation run = start_simulation(circling(r0, v, s, integrator));
      advance_to(run, 2.0);
      ASSERT_EQ(run.state.status, Status::ok) << r0 << integrator;
      const Readout r = readout(run);
      ASSERT_TRUE(r.casimir) << r0 << integrator;
      EXPECT_NEAR(*r.casimir, expected, 1e-9) << r0 << integrator;  // read ±2e20 at 30R before
    }
  }
}

// p_φ and M: the same in every integrator to 8 digits, or null with the reason under `undefined`.
TEST(Invariants, MomentaFarOutAgreeOrAreUndefined) {
  for (const double r0 : {1.0, 10.0, 20.0, 30.0}) {
    Simulation exact = start_simulation(circling(r0, 0.5, 0.3, "exact"));
    Simulation dop = start_simulation(circling(r0, 0.5, 0.3, "dop853"));
    advance_to(exact, 2.0);
    advance_to(dop, 2.0);
    const Readout a = readout(exact), b = readout(dop);
    const auto defined = [](const Readout& r) {
      for (const UndefinedValue& u : r.coordinates.undefined)
        if (u.field == "p_phi") return u.reason.empty();
      return std::isfinite(r.coordinates.p_phi);
    };
    const bool a_defined = defined(a), b_defined = defined(b);
    for (const Readout* r : {&a, &b}) {
      bool m_listed = false;
      for (const UndefinedValue& u : r->undefined)
        m_listed = m_listed || (u.field == "M" && !u.reason.empty());
      EXPECT_EQ(m_listed, !r->momentum_map.has_value()) << r0;
    }
    if (a_defined && b_defined) {
      EXPECT_NEAR(a.coordinates.p_phi, b.coordinates.p_phi, 1e-7 * (1.0 + std::abs(b.coordinates.p_phi)))
          << r0;
    }
    if (a.momentum_map && b.momentum_map) {
      EXPECT_LT((*a.momentum_map - *b.momentum_map).norm(), 1e-7 * (1.0 + b.momentum_map->norm())) << r0;
    }
    if (r0 <= 10.0) {  // near enough: everything defined
      EXPECT_TRUE(a_defined && b_defined && a.momentum_map && b.momentum_map) << r0;
    }
    if (r0 >= 20.0) {  // M's components are e^{r/R}·ε‖A‖² wrong there (p_φ of all three differed)
      EXPECT_FALSE(a.momentum_map || b.momentum_map || a_defined || b_defined) << r0;
    }
  }
}

// Near the origin the chart-computed momentum map is the global formula m X × V + K R s ηX.
TEST(Invariants, MomentumMapFromTheChartIsTheGlobalOne) {
  Scene scene = circling(0.1, 0.5, 0.3, "dop853");  // starts in a moved chart (near the pole)
  Simulation run = start_simulation(scene);
  advance_to(run, 3.0);
  const GlobalBody g = global_body(scene, run.state);
  const Vec3 direct = g.X.cross(g.V) - 1.0 * g.spin * Vec3(g.X.x(), g.X.y(), -g.X.z());
  const Vec3 M = *momentum_map(scene, run.state);
  EXPECT_LT((M - direct).norm(), 1e-12);
  EXPECT_NEAR(angular_momentum(scene, run.state), direct.z(), 1e-12);
}

// Far out on H² the start's chart is a Lorentz matrix with entries ~1e5 whose 3×3 determinant cancels
// to noise (it read −3.1 here): p_φ = mS²φ̇ + Cs of the start must not take its orientation from it
// (the orbital part came out flipped, and `exact` stopped `inconsistent` at t = 0; oracle far_h2 1231).
TEST(AngularMomentum, FarOutOnH2MatchesThePolarFormula) {
  Scene scene;
  scene.surface = {SurfaceKind::pseudosphere, 1.282257};
  scene.body = {1.0923, 0.3942, BodyModel::affine};
  scene.potential.radial = RadialPotential{0.0546};
  int checked = 0;
  for (double r = 12.0; r <= 19.0; r += 0.125) {
    for (const double phi : {-2.771, -0.4, 0.0, 1.3, 2.9}) {
      scene.initial = {r, phi, -1.432, 2.008, 1.25, 1.25, 0.5067, 2.4e-7, -0.06, 0.03, 0.0, 0.0};
      const State start = initial_state(scene);
      ASSERT_FALSE(start.chart.global) << r;
      const double m = scene.body.mass, S = polar_S(scene.surface, r), C = polar_C(scene.surface, r);
      const double s = spin_of(scene, start.y), orbital = m * S * S * scene.initial.phi_dot;
      const double rounding = angular_momentum_rounding(scene, start);
      if (!std::isfinite(rounding)) continue;  // reported undefined there, not wrong
      ++checked;
      EXPECT_NEAR(angular_momentum(scene, start), orbital + C * s,
                  1e-8 * (std::abs(orbital) + C * std::abs(s)) + rounding)
          << "r = " << r << ", phi = " << phi;
    }
  }
  EXPECT_GT(checked, 100);
}

// Where the curvature varies the internal motion is the flat one in a transported frame
// (physics-surfaces.md §4), so physics.md §6's C_x and C_y separate there too: each is conserved
// along a run, stepped in full or orbit-only (the closed form), and C_x + C_y is the deformation
// energy (computed from the embedded state by another path).
TEST(SeparatedEnergies, AreConservedWhereTheCurvatureVaries) {
  for (const SurfaceKind kind : {SurfaceKind::torus, SurfaceKind::spheroid, SurfaceKind::bump}) {
    for (const Stepping stepping : {Stepping::full, Stepping::automatic}) {
      Scene scene = test::ws1_scene();
      scene.surface.kind = kind;
      scene.surface.equatorial_radius = 1.5, scene.surface.polar_radius = 0.8;
      scene.surface.height = 0.7, scene.surface.width = 1.0;
      scene.initial.u = 0.7;
      scene.body.inertia_matrix.reset();
      scene.body.inertia = 0.3;
      scene.integrator.stepping = stepping;
      Simulation run = start_simulation(scene);
      const SeparatedEnergies start = *separated_energies(scene, run.state);
      EXPECT_NEAR(start.C_x + start.C_y, deformation_energy(scene, run.state), 1e-12);
      EXPECT_GT(std::abs(start.C_x - start.C_y), 1e-3);  // two different numbers
      advance_to(run, 5.0);
      ASSERT_EQ(run.state.status, Status::ok);
      const SeparatedEnergies end = *separated_energies(scene, run.state);
      EXPECT_NEAR(end.C_x, start.C_x, 1e-9) << enum_name(kind) << " " << enum_name(stepping);
      EXPECT_NEAR(end.C_y, start.C_y, 1e-9) << enum_name(kind) << " " << enum_name(stepping);
      EXPECT_NEAR(end.C_x + end.C_y, deformation_energy(scene, run.state), 1e-12);
    }
  }
  // The same numbers as the constant-curvature chart's (x and y not swapped: the frame is
  // right-handed about n): a sphere against a spheroid with a = b.
  Scene sphere;
  sphere.initial.r = 0.7, sphere.initial.r_dot = 0.3, sphere.initial.phi_dot = 0.5;
  sphere.initial.lambda = 1.3, sphere.initial.mu = 0.6, sphere.initial.alpha_dot = 0.4;
  sphere.initial.beta = 0.3, sphere.initial.lambda_dot = 0.2;
  sphere.potential.deformation = AbcPotential{0.02, 0.05, 0.3};
  Scene spheroid = sphere;
  spheroid.surface = Surface(SurfaceKind::spheroid, 1.0);
  spheroid.surface.equatorial_radius = spheroid.surface.polar_radius = 1.0;
  spheroid.initial.u = 0.7, spheroid.initial.u_dot = 0.3;
  Simulation a = start_simulation(sphere), b = start_simulation(spheroid);
  for (const double t : {0.0, 3.0}) {
    advance_to(a, t), advance_to(b, t);
    const SeparatedEnergies x = *separated_energies(sphere, a.state),
                            y = *separated_energies(spheroid, b.state);
    EXPECT_NEAR(x.C_x, y.C_x, 1e-9) << t;
    EXPECT_NEAR(x.C_y, y.C_y, 1e-9) << t;
    EXPECT_GT(std::abs(x.C_x - x.C_y), 1e-2);
  }
  Scene anisotropic = test::ws1_scene();  // J anisotropic: they do not separate
  EXPECT_FALSE(separated_energies(anisotropic, start_simulation(anisotropic).state));
}

}  // namespace
}  // namespace spinfold
