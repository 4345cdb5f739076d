// The chart form on surfaces of revolution (engine/revolution_chart.h) against physics-surfaces.md §11
// (WS1, WS2) and, on the sphere, against the constant-curvature engine (engine/dynamics.h).
#include "engine/revolution_chart.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/dynamics.h"
#include "tests/engine/revolution_examples.h"

namespace spinfold {
namespace {

using test::inertia_matrix;
using test::matrix;
using test::ws1_model;
using test::ws1_rates;

void expect_close(const Eigen::VectorXd& got, const std::vector<double>& want, double tolerance) {
  ASSERT_EQ(static_cast<std::size_t>(got.size()), want.size());
  for (std::size_t i = 0; i < want.size(); ++i)
    EXPECT_NEAR(got(static_cast<Eigen::Index>(i)), want[i], tolerance * (1.0 + std::abs(want[i])))
        << "entry " << i;
}

TEST(RevolutionChart, WorkedNumbersWS1) {
  const RevolutionModel model = ws1_model();
  const RevolutionCoords w = revolution_coords(model, ws1_rates());
  expect_close(w,
               {0.7, 0.3, 1.2, 0.1, -0.2, 0.9, 0.8, -5.678393831313499, 0.06386530612342614,
                0.081193197267837, 0.054055782336702884, 0.09061496599160612},
               1e-14);
  EXPECT_NEAR(revolution_spin(w), 0.013627619086836, 1e-15);
  const EmbeddedEnergy E = revolution_energy(model, w);
  EXPECT_NEAR(E.total(), 0.7726449045081352, 1e-14);
  EXPECT_NEAR(E.orbital, 0.08274378056859111, 1e-14);
  EXPECT_NEAR(E.deformation, 0.6899011239395439, 1e-14);
  RevolutionCoords dw;
  revolution_vector_field(model, w, dw);
  expect_close(dw,
               {0.4, -0.2, 0.05, 0.3, -0.1, 0.2, 0.5728965487458753, 0, 0.7352610345120594,
                -0.42713966205077075, -0.32941381714630014, -1.5621649224563756},
               1e-13);
}

// WS1 with friction (γ_t, γ_i) = (0.1, 0.05): ṗ_u, ṗ_φ and Ṗ.
TEST(RevolutionChart, WorkedNumbersWS1Friction) {
  RevolutionModel model = ws1_model();
  model.body.friction = {0.1, 0.05};
  const RevolutionCoords w = revolution_coords(model, ws1_rates());
  RevolutionCoords dw;
  revolution_vector_field(model, w, dw);
  EXPECT_NEAR(dw(revolution_coord::p_u), 0.5328965487458752, 1e-14);
  EXPECT_NEAR(dw(revolution_coord::p_phi), 0.28143019338950986, 1e-14);
  expect_close(dw.segment<4>(revolution_coord::P),
               {0.731472599137584, -0.4363417028656315, -0.3321444293931524, -1.5728091401436133}, 1e-14);
}

// WS2: oblate spheroid a = 2, b = 1; rigid m = 1, J = diag(0.5, 0.5), λ₀ = 1 (I = 1), spring k = 0.7.
TEST(RevolutionChart, WorkedNumbersWS2Rigid) {
  const RevolutionModel model = test::ws2_model();
  const ProfilePoint p = spheroid_entry.profile(model.surface, 1.0);
  const ProfileMetric m = profile_metric(p);
  EXPECT_NEAR(p.K, 0.284208011477352, 1e-15);
  EXPECT_NEAR(m.C, 0.7889979878750016, 1e-15);
  // Speed 0.5 at heading 0.3 from E₁ towards E₂, s = 1.5.
  const double v = 0.5, heading = 0.3, s = 1.5;
  RevolutionRigidCoords w;
  w << 1.0, 0.0, 0.4, m.f * v * std::cos(heading), p.rho * v * std::sin(heading) + m.C * s, s;
  expect_close(w, {1, 0, 0.4, 0.6542101702245572, 1.4321686611424531, 1.5}, 1e-15);
  RevolutionRigidCoords dw;
  revolution_rigid_vector_field(model, 1.0, w, dw);
  expect_close(dw, {0.3487670510921461, 0.08779869181371874, 1.4307270088209185, 0.08009148056366022, 0, 0},
               1e-14);
  const EmbeddedRigid Y = embed_rigid(model, 1.0, w);
  expect_close(Y.head<9>(),
               {1.682941969615793, 0, 0.5403023058681398, 0.3768792838318358, 0.14776010333066983,
                -0.2934773539510542, 0.7267152709784253, 0.3894183423086505, -0.56589598832324},
               1e-15);
}

// A spheroid with a = b = R is the sphere: its chart field equals the constant-curvature engine's
// (physics.md §4) with u = r/R, p_u = R p_r (physics-surfaces.md §9), to round-off.
TEST(RevolutionChart, SpheroidWithEqualRadiiIsTheSphere) {
  const double R = 1.3;
  Scene scene;
  scene.surface = {SurfaceKind::sphere, R};
  scene.body = {1.7, 0.3, BodyModel::affine};
  scene.potential.deformation = AbcPotential{0.02, 0.05, 0.3};
  RevolutionModel model;
  model.surface.kind = SurfaceKind::spheroid;
  model.surface.equatorial_radius = model.surface.polar_radius = R;
  model.body.mass = 1.7;
  model.body.inertia = inertia_of(scene.body);
  model.body.deformation = scene.potential.deformation;
  const double r = 0.9, phi = 0.4, p_r = 0.3, p_phi = -0.2;
  const Mat2 L = matrix(1.1, 0.2, -0.1, 0.7), P = matrix(0.05, -0.02, 0.04, 0.01);
  Coords y(12);
  y << r, phi, p_r, p_phi, L(0, 0), L(0, 1), L(1, 0), L(1, 1), P(0, 0), P(0, 1), P(1, 0), P(1, 1);
  RevolutionCoords w;
  w << r / R, phi, L(0, 0), L(0, 1), L(1, 0), L(1, 1), R * p_r, p_phi, P(0, 0), P(0, 1), P(1, 0), P(1, 1);
  Coords dy(12);
  vector_field(scene, Chart{}, y, dy);
  RevolutionCoords dw;
  revolution_vector_field(model, w, dw);
  EXPECT_NEAR(dw(revolution_coord::u), dy(coord::r) / R, 1e-15);
  EXPECT_NEAR(dw(revolution_coord::phi), dy(coord::phi), 1e-15);
  EXPECT_NEAR(dw(revolution_coord::p_u), R * dy(coord::p_r), 1e-14);
  EXPECT_NEAR(dw(revolution_coord::p_phi), dy(coord::p_phi), 1e-15);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(dw(revolution_coord::L + i), dy(coord::L + i), 1e-15);
    EXPECT_NEAR(dw(revolution_coord::P + i), dy(coord::P + i), 1e-15);
  }
  EXPECT_NEAR(revolution_energy(model, w).total(), hamiltonian(scene, Chart{}, y), 1e-15);
}

// Chart → embedding → chart gives the state back (away from axis points), on every surface.
TEST(RevolutionChart, EmbeddingRoundTrip) {
  RevolutionModel model = ws1_model();
  for (const RevolutionEntry& entry : revolution_catalog()) {
    model.surface = test::off_default_surface(entry.kind);
    RevolutionRates rates = ws1_rates();
    const RevolutionCoords w = revolution_coords(model, rates);
    const RevolutionCoords back = chart_of(model, embed(model, w));
    SCOPED_TRACE(std::string(entry.name));
    EXPECT_LT((back - w).norm(), 1e-13 * w.norm());
  }
}

}  // namespace
}  // namespace spinfold
