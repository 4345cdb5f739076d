// The constant-curvature chart's equations (engine/dynamics.h) with what physics-surfaces.md adds on
// every surface: the height potential (§5; the sphere's embedded height) and Rayleigh friction (§13).
// The Hamiltonian part is pinned by worked_examples_test and anisotropic_inertia_test; here the new
// terms are checked against the energy they must take (dE/dt = −2R, and 0 without friction), and the
// whole run against the chart-free equations of a spheroid with a = b (another formulation, itself
// checked against the oracle).
#include "engine/dynamics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/body_forces.h"
#include "engine/inertia.h"
#include "engine/invariants.h"
#include "engine/scene_fields.h"
#include "engine/simulation.h"

namespace spinfold {
namespace {

// A state of `scene` with every number drawn (r away from the poles).
Coords random_state(const Scene& scene, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Coords y = initial_state(scene).y;
  for (int i = 0; i < y.size(); ++i) y[i] += 0.3 * u(rng);
  y[coord::r] = scene.surface.radius * (0.4 + 0.25 * (u(rng) + 1.0));  // 0.4R to 0.9R
  return y;
}

// ∇H · f by a fourth-order central difference along f: the rate at which the field changes H.
double energy_rate(const Scene& scene, const Chart& chart, const Coords& y) {
  Coords f;
  vector_field(scene, chart, y, f);
  const double h = 1e-5;
  const auto H = [&](double k) { return hamiltonian(scene, chart, y + k * h * f); };
  return (8.0 * (H(1) - H(-1)) - (H(2) - H(-2))) / (12.0 * h);
}

// R = γ_t/2 |V|² + γ_i/2 Σ|W_A|²: |V|² = ṙ² + S²φ̇², Σ|W_A|² = ‖M‖² (M's columns are the W_A).
double rayleigh(const Scene& scene, const Coords& y) {
  Coords f;
  vector_field(scene, Chart{}, y, f);
  const double S = polar_S(scene.surface, y[coord::r]);
  const double v2 = f[coord::r] * f[coord::r] + S * S * f[coord::phi] * f[coord::phi];
  return 0.5 * scene.friction->translational * v2 +
         0.5 * scene.friction->internal * internal_state(scene, y).M.squaredNorm();
}

std::vector<Scene> bodies_on(SurfaceKind kind) {
  Scene affine;
  affine.surface = Surface(kind, 1.3);
  affine.initial.r = 0.6, affine.initial.r_dot = 0.4, affine.initial.phi_dot = 0.7;
  affine.initial.lambda = 1.2, affine.initial.mu = 0.8, affine.initial.alpha_dot = 0.9;
  affine.potential.deformation = AbcPotential{0.3, 0.1, 0.2};
  Scene anisotropic = affine;
  anisotropic.body.inertia_matrix = InertiaMatrix{0.7, 0.2, 0.2, 0.4};
  Scene rigid = affine;
  rigid.body.model = BodyModel::rigid;
  rigid.initial.mu = rigid.initial.lambda;
  rigid.potential.deformation = std::monostate{};
  return {affine, anisotropic, rigid};
}

TEST(Dynamics, FrictionTakesEnergyAtTwiceTheRayleighRateOnEveryConstantSurface) {
  std::mt19937_64 rng(7);
  for (const SurfaceKind kind : {SurfaceKind::sphere, SurfaceKind::pseudosphere, SurfaceKind::plane})
    for (Scene scene : bodies_on(kind)) {
      scene.friction = Friction{0.3, 0.2};
      for (int i = 0; i < 20; ++i) {
        const Coords y = random_state(scene, rng);
        const double two_R = 2.0 * rayleigh(scene, y);
        ASSERT_GT(two_R, 1e-3);
        EXPECT_NEAR(energy_rate(scene, Chart{}, y), -two_R, 1e-7 * (1.0 + two_R))
            << enum_name(kind) << " " << enum_name(scene.body.model);
      }
      // Without friction the same field keeps H (the friction terms are the only loss).
      scene.friction.reset();
      const Coords y = random_state(scene, rng);
      EXPECT_NEAR(energy_rate(scene, Chart{}, y), 0.0, 1e-7) << enum_name(kind);
    }
}

// On the sphere V_h = V_h(z) of the embedded height z = (A X + b)_z: in the global chart z = R cos(r/R),
// in a moved chart the height of the global point; the force is its gradient (H is kept).
TEST(Dynamics, TheSpheresHeightPotentialIsThatOfTheEmbeddedHeightInEveryChart) {
  std::mt19937_64 rng(11);
  Scene scene = bodies_on(SurfaceKind::sphere).front();
  const double R = scene.surface.radius, m = scene.body.mass;
  Chart moved;
  moved.global = false;
  moved.A = Eigen::AngleAxisd(0.7, Vec3(0.3, 0.9, 0.1).normalized()).toRotationMatrix();
  for (const HeightPotential height :
       {HeightPotential{GravityPotential{0.8}}, HeightPotential{SpringPotential{1.7}}})
    for (const Chart& chart : {Chart{}, moved}) {
      const Coords y = random_state(scene, rng);
      Scene without = scene;
      scene.potential.height = height;
      const double z = (chart.A * chart_point(scene.surface, y[coord::r], y[coord::phi]).X).z();
      if (chart.global) {
        EXPECT_NEAR(z, R * std::cos(y[coord::r] / R), 1e-14);
      }
      EXPECT_NEAR(hamiltonian(scene, chart, y) - hamiltonian(without, chart, y), height_energy(height, m, z),
                  1e-13);
      EXPECT_NEAR(energy_rate(scene, chart, y), 0.0, 1e-7);
      scene.potential.height = {};
    }
}

// The whole run, two formulations: the sphere's chart (engine/dynamics.h, r = R u) against the
// chart-free equations on a spheroid with a = b = R (engine/embedded_dynamics.h), with gravity, the
// abc potential and both frictions, for the affine (isotropic and anisotropic J) and rigid bodies.
TEST(Dynamics, GravityAndFrictionOnTheSphereFollowTheSpheroidOfEqualRadii) {
  for (Scene sphere : bodies_on(SurfaceKind::sphere)) {
    sphere.potential.height = GravityPotential{0.9};
    sphere.friction = Friction{0.15, 0.1};
    sphere.integrator.name = "dop853";
    sphere.integrator.tolerance = 1e-12;
    Scene spheroid = sphere;
    const double R = sphere.surface.radius;
    spheroid.surface = Surface(SurfaceKind::spheroid, 1.0);
    spheroid.surface.equatorial_radius = spheroid.surface.polar_radius = R;
    spheroid.initial.u = sphere.initial.r / R, spheroid.initial.u_dot = sphere.initial.r_dot / R;
    Simulation a = start_simulation(sphere), b = start_simulation(spheroid);
    const double E0 = energy(sphere, a.state);
    EXPECT_NEAR(E0, energy(spheroid, b.state), 1e-12);
    for (const double t : {1.0, 3.0, 6.0}) {
      advance_to(a, t);
      advance_to(b, t);
      ASSERT_EQ(a.state.status, Status::ok);
      ASSERT_EQ(b.state.status, Status::ok);
      const Vec3 X = global_body(sphere, a.state).X, Y = b.state.y.segment<3>(0);
      EXPECT_LT((X - Y).norm(), 1e-8) << enum_name(sphere.body.model) << " t = " << t;
      EXPECT_NEAR(energy(sphere, a.state), energy(spheroid, b.state), 1e-8);
      EXPECT_NEAR(spin(sphere, a.state), spin(spheroid, b.state), 1e-8);
    }
    EXPECT_LT(energy(sphere, a.state), E0 - 0.05);  // friction took a visible part
  }
}

// Closed forms of friction along a run (dop853 at 1e-12): on the plane a body with no spin slides
// straight and stops at m v₀/γ_t (|V| = v₀ e^{−γ_t t/m}); on H² the spin of an isotropic body decays
// as s₀ e^{−γ_i t/J} wherever the orbit goes (physics-surfaces.md §13).
TEST(Dynamics, FrictionFollowsItsClosedFormsOnThePlaneAndOnH2) {
  Scene plane = bodies_on(SurfaceKind::plane).front();
  plane.initial.alpha_dot = 0.0, plane.initial.phi_dot = 0.0, plane.initial.r_dot = 0.8;
  plane.potential.deformation = std::monostate{};
  plane.friction = Friction{0.4, 0.0};
  plane.integrator.name = "dop853", plane.integrator.tolerance = 1e-12;
  Simulation run = start_simulation(plane);
  const double m = plane.body.mass, v0 = 0.8, r0 = plane.initial.r;
  for (const double t : {1.0, 4.0}) {
    advance_to(run, t);
    const GlobalBody g = global_body(plane, run.state);
    EXPECT_NEAR(g.r, r0 + m * v0 / 0.4 * (1.0 - std::exp(-0.4 * t / m)), 1e-10) << t;
    EXPECT_NEAR(g.V.norm(), v0 * std::exp(-0.4 * t / m), 1e-10) << t;
  }
  Scene h2 = bodies_on(SurfaceKind::pseudosphere).front();
  h2.friction = Friction{0.2, 0.05};
  h2.integrator.name = "gauss6", h2.integrator.dt = 0.01;
  run = start_simulation(h2);
  const double s0 = spin(h2, run.state), J = h2.body.inertia;
  advance_to(run, 3.0);
  EXPECT_NEAR(spin(h2, run.state), s0 * std::exp(-0.05 * 3.0 / J), 1e-9 * std::abs(s0));
}

}  // namespace
}  // namespace spinfold
