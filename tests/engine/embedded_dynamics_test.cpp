// The chart-free equations (engine/embedded_dynamics.h) against physics-surfaces.md §11 (WS1, WS2,
// WS4), against the chart form (another formulation: the push-forward of its flow), and integrated by
// an independent integrator (Boost.Odeint's Runge–Kutta–Fehlberg 7(8)) against the reference's
// 30-digit trajectory, its conservation laws and its friction balance.
#include "engine/embedded_dynamics.h"

#include <gtest/gtest.h>

#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <vector>

#include "engine/field_stepping.h"
#include "engine/integrator.h"
#include "engine/revolution_chart.h"
#include "tests/engine/revolution_examples.h"

namespace spinfold {
namespace {

namespace odeint = boost::numeric::odeint;
using test::inertia_matrix;
using test::matrix;
using test::ws1_model;
using test::ws1_rates;
using test::ws1_state;

void expect_close(const Eigen::VectorXd& got, const Eigen::VectorXd& want, double tolerance) {
  ASSERT_EQ(got.size(), want.size());
  for (Eigen::Index i = 0; i < want.size(); ++i)
    EXPECT_NEAR(got(i), want(i), tolerance * (1.0 + std::abs(want(i)))) << "entry " << i;
}

// Integrates dY/dt from 0 to T with RKF78 at `tolerance` (absolute and relative).
template <int N, class Field>
Eigen::Matrix<double, N, 1> integrate(const Field& field, Eigen::Matrix<double, N, 1> Y, double T,
                                      double tolerance) {
  using State = std::vector<double>;  // (std::array trips GCC's -Wuninitialized inside Odeint's copies)
  State x(N);
  for (int i = 0; i < N; ++i) x[i] = Y(i);
  auto rhs = [&](const State& in, State& out, double) {
    Eigen::Matrix<double, N, 1> y, dy;
    for (int i = 0; i < N; ++i) y(i) = in[i];
    field(y, dy);
    for (int i = 0; i < N; ++i) out[i] = dy(i);
  };
  odeint::integrate_adaptive(
      odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_fehlberg78<State>()), rhs, x, 0.0, T,
      1e-3);
  for (int i = 0; i < N; ++i) Y(i) = x[i];
  return Y;
}

TEST(EmbeddedDynamics, WorkedNumbersWS1) {
  const RevolutionModel model = ws1_model();
  const RevolutionImplicit torus(model.surface);
  const EmbeddedModel em{torus, model.body};
  const Embedded Y = embed(model, revolution_coords(model, ws1_rates()));
  expect_close(Y, ws1_state(), 1e-15);
  Embedded dY;
  embedded_vector_field(em, Y, dY);
  Embedded want;
  want << -0.02366047717658104, -0.7954899610894152, -0.3059368749137954, -0.43723340026348256,
      -0.1346725531905884, -0.11601289475723439, -0.43585190662201934, -0.07765933932821628,
      0.2709823805098672, -0.10481172523590875, 0.19041497222513115, -0.20368394869583895, -0.947286027456003,
      -0.17153255528743286, -1.1005314985479733, 2.024380581254423, -3.4647808835616605, 1.144175051897484;
  expect_close(dY, want, 1e-13);
  EXPECT_NEAR(embedded_spin(em, Y), 0.013627619086836, 1e-15);
  EXPECT_NEAR(embedded_axial_momentum(em, Y), -5.678393831313499, 1e-14);
  EXPECT_NEAR(embedded_energy(em, Y).total(), 0.7726449045081352, 1e-14);
  EXPECT_NEAR(embedded_energy(em, Y).orbital, 0.08274378056859111, 1e-14);
}

// WS1's trajectory (the reference's 30-digit solution) by an integrator that is not the engine's.
TEST(EmbeddedDynamics, TrajectoryWS1) {
  const RevolutionModel model = ws1_model();
  const RevolutionImplicit torus(model.surface);
  const EmbeddedModel em{torus, model.body};
  const auto field = [&](const Embedded& y, Embedded& dy) { embedded_vector_field(em, y, dy); };
  const Embedded Y1 = integrate<18>(field, ws1_state(), 1.0, 1e-14);
  expect_close(Y1.segment<3>(embedded::X),
               Eigen::Vector3d(3.350568512996648, 0.2646701387724223, -0.9325635900151183), 1e-11);
  const Embedded Y2 = integrate<18>(field, Y1, 1.0, 1e-14);
  expect_close(Y2.segment<3>(embedded::X),
               Eigen::Vector3d(2.8242096200506657, -0.6183870861207411, -0.9940546679244858), 1e-11);
  expect_close(Y2.segment<3>(embedded::e1),
               Eigen::Vector3d(-1.0396884457026114, -0.10316245548821772, 0.10882812074818082), 1e-11);
  expect_close(Y2.segment<3>(embedded::W2),
               Eigen::Vector3d(0.29627443020240224, 0.9694076688365609, -0.008989320225909238), 1e-11);
  // The invariants of §6 and the constraint F = 0 hold along it.
  EXPECT_NEAR(embedded_energy(em, Y2).total(), 0.7726449045081352, 1e-12);
  EXPECT_NEAR(embedded_spin(em, Y2), 0.013627619086836, 1e-12);
  EXPECT_NEAR(embedded_axial_momentum(em, Y2), -5.678393831313499, 1e-11);
  EXPECT_LT(std::abs(torus.at(Y2.segment<3>(embedded::X)).F), 1e-11);
}

// Friction (§13): WS1's R and, along a run, E(T) − E(0) = −∫2R dt; for isotropic J, s = s₀e^{−γ_i t/J}.
TEST(EmbeddedDynamics, FrictionBalance) {
  RevolutionModel model = ws1_model();
  model.body.friction = {0.1, 0.05};
  const RevolutionImplicit torus(model.surface);
  const EmbeddedModel em{torus, model.body};
  EXPECT_NEAR(embedded_rayleigh(em, ws1_state()), 0.03854592750192314, 1e-15);
  using Augmented = Eigen::Matrix<double, 19, 1>;
  const auto field = [&](const Augmented& y, Augmented& dy) {
    Embedded d;
    embedded_vector_field(em, y.head<18>(), d);
    dy.head<18>() = d;
    dy(18) = 2.0 * embedded_rayleigh(em, y.head<18>());
  };
  Augmented start;
  start << ws1_state(), 0.0;
  const Augmented end = integrate<19>(field, start, 5.0, 1e-13);
  const double E0 = embedded_energy(em, ws1_state()).total(),
               E1 = embedded_energy(em, end.head<18>()).total();
  EXPECT_LT(E1, E0 - 0.1);  // it does lose energy
  EXPECT_NEAR(E1 - E0, -end(18), 1e-11);

  model.body.inertia = inertia_matrix(0.4, 0.0, 0.4);
  const EmbeddedModel iso{torus, model.body};
  const auto iso_field = [&](const Embedded& y, Embedded& dy) { embedded_vector_field(iso, y, dy); };
  const double s0 = embedded_spin(iso, ws1_state());
  const Embedded later = integrate<18>(iso_field, ws1_state(), 3.0, 1e-13);
  EXPECT_NEAR(embedded_spin(iso, later), s0 * std::exp(-0.05 * 3.0 / 0.4), 1e-12);
}

// The two formulations (§4 chart, §7 embedding) give one flow: the embedding's field equals the
// push-forward of the chart's, on every surface, with anisotropic J, both height potentials, abc
// and friction (central differences along the chart's field).
TEST(EmbeddedDynamics, ChartFlowPushesForwardToTheEmbeddedField) {
  RevolutionModel model = ws1_model();
  model.body.friction = {0.07, 0.03};
  for (const RevolutionEntry& entry : revolution_catalog())
    for (const HeightPotential height :
         {HeightPotential{GravityPotential{0.4}}, HeightPotential{SpringPotential{0.9}}}) {
      model.surface = test::off_default_surface(entry.kind);
      model.body.height = height;
      RevolutionRates rates;
      rates.u = 0.6;
      rates.phi = -0.4;
      rates.L = matrix(1.0, 0.3, -0.2, 0.8);
      rates.u_dot = -0.3;
      rates.phi_dot = 0.5;
      rates.L_dot = matrix(0.1, -0.2, 0.3, 0.05);
      const RevolutionCoords w = revolution_coords(model, rates);
      RevolutionCoords dw;
      revolution_vector_field(model, w, dw);
      const double h = 1e-5;
      const Embedded pushed = (embed(model, w + h * dw) - embed(model, w - h * dw)) / (2 * h);
      const RevolutionImplicit implicit(model.surface);
      Embedded dY;
      embedded_vector_field({implicit, model.body}, embed(model, w), dY);
      SCOPED_TRACE(std::string(entry.name));
      EXPECT_LT((pushed - dY).norm(), 1e-8 * (1.0 + dY.norm()));
    }
}

// WS2 (rigid, spring, oblate spheroid): the embedded rigid field and the path's geodesic curvature.
TEST(EmbeddedDynamics, WorkedNumbersWS2Rigid) {
  const RevolutionModel model = test::ws2_model();
  const RevolutionImplicit spheroid(model.surface);
  const EmbeddedModel em{spheroid, model.body};
  EmbeddedRigid Y;
  Y << 1.682941969615793, 0, 0.5403023058681398, 0.3768792838318358, 0.14776010333066983, -0.2934773539510542,
      0.7267152709784253, 0.3894183423086505, -0.56589598832324, 1.5;
  EmbeddedRigid dY;
  embedded_rigid_vector_field(em, Y, dY);
  EmbeddedRigid want;
  want << 0.3768792838318358, 0.14776010333066983, -0.2934773539510542, 0.01960959286395185,
      0.2036357128996074, -0.2505026689707879, -0.6842177945451293, 1.3815914910043272, 0.07207251693790273,
      0.0;
  expect_close(dY, want, 1e-14);
  const Vec3 V = Y.segment<3>(embedded::V), a = dY.segment<3>(embedded::V);
  const Vec3 n = embedded_normal(spheroid, Y.segment<3>(embedded::X));
  EXPECT_NEAR(a.dot(n.cross(V)) / std::pow(V.norm(), 3), 0.5779419979460954, 1e-14);
  EXPECT_NEAR(embedded_rigid_energy(em, Y), 1.35217430360425, 1e-14);
}

// WS4: a body on the north pole of an oblate spheroid (an axis point): the field is regular there.
TEST(EmbeddedDynamics, WorkedNumbersWS4OnTheAxis) {
  SurfaceBody body;
  body.mass = 1.5;
  body.inertia = inertia_matrix(0.3, 0.0, 0.3);
  RevolutionSurface surface;
  surface.kind = SurfaceKind::spheroid;
  surface.equatorial_radius = 2.0;
  surface.polar_radius = 1.0;
  const RevolutionImplicit spheroid(surface);
  const EmbeddedModel em{spheroid, body};
  Embedded Y;
  Y << 0, 0, 1, 0.4, 0.3, 0, 1.1, -0.2, 0, 0.1, 0.7, 0, 0.2, 0.5, 0, -0.3, 0.1, 0;
  EXPECT_NEAR(embedded_spin(em, Y), 0.243, 1e-15);
  EXPECT_NEAR(embedded_axial_momentum(em, Y), 0.243, 1e-15);
  EXPECT_NEAR(embedded_energy(em, Y).total(), 0.246, 1e-15);
  Embedded dY;
  embedded_vector_field(em, Y, dY);
  Embedded want;
  want << 0.4, 0.3, 0, -0.0030375, 0.00405, -0.0625, 0.2, 0.5, -0.095, -0.3, 0.1, -0.0625, 0, 0, -0.0575, 0,
      0, 0.0225;
  expect_close(dY, want, 1e-15);
}

// Over an axis point: a body launched at the north pole of an oblate spheroid passes over it and
// the invariants hold through the pass (the chart would be singular there, §8).
TEST(EmbeddedDynamics, PassesOverAnAxisPoint) {
  RevolutionModel model;
  model.surface = {.kind = SurfaceKind::spheroid, .equatorial_radius = 1.0, .polar_radius = 0.6};
  model.body.mass = 1.0;
  model.body.inertia = inertia_matrix(0.3, 0.05, 0.2);
  model.body.deformation = AbcPotential{0.01, 0.02, 0.3};
  RevolutionRates rates;
  rates.u = 0.4;
  rates.phi = 0.0;
  rates.L = matrix(1.0, 0.2, -0.1, 0.6);
  rates.u_dot = -0.8;  // towards the pole
  rates.L_dot = matrix(0.0, 0.3, -0.2, 0.1);
  const RevolutionCoords w = revolution_coords(model, rates);
  const RevolutionImplicit spheroid(model.surface);
  const EmbeddedModel em{spheroid, model.body};
  const Embedded Y0 = embed(model, w);
  // p_φ = C(0) s is what makes the orbit reach the axis exactly (§8); this start has p_φ = C(u₀) s.
  const auto field = [&](const Embedded& y, Embedded& dy) { embedded_vector_field(em, y, dy); };
  const Embedded Y1 = integrate<18>(field, Y0, 1.5, 1e-13);
  // It went over: u decreased through 0 and φ jumped by about π.
  EXPECT_GT(std::abs(std::remainder(std::atan2(Y1(1), Y1(0)) - 0.0, 2 * M_PI)), 2.0);
  EXPECT_NEAR(embedded_energy(em, Y1).total(), embedded_energy(em, Y0).total(), 1e-12);
  EXPECT_NEAR(embedded_spin(em, Y1), embedded_spin(em, Y0), 1e-12);
  EXPECT_NEAR(embedded_axial_momentum(em, Y1), embedded_axial_momentum(em, Y0), 1e-12);
  EXPECT_LT(std::abs(spheroid.at(Y1.segment<3>(embedded::X)).F), 1e-12);
}

// Decoupling (§4): two bodies with different (L, P) but equal spin follow the same orbit.
TEST(EmbeddedDynamics, OrbitSeesTheBodyOnlyThroughItsSpin) {
  RevolutionModel model = ws1_model();
  model.body.height = {};
  RevolutionRates a;
  a.u = 1.9;
  a.phi = 0.2;
  a.L = matrix(1.1, 0.1, -0.2, 0.8);  // (not L = I: abc's A/x² needs x² = ‖L‖²/2 − det L > 0)
  a.u_dot = 0.3;
  a.phi_dot = 0.1;
  a.L_dot = matrix(0.0, -0.2, 0.2, 0.0);
  RevolutionCoords wa = revolution_coords(model, a);
  RevolutionRates b = a;
  b.L = matrix(0.7, 0.3, -0.4, 1.3);
  b.L_dot = matrix(0.2, 0.1, -0.3, -0.1);
  RevolutionCoords wb = revolution_coords(model, b);
  // Scale b's internal momentum so that its spin equals a's (s is linear in P).
  const double scale = revolution_spin(wa) / revolution_spin(wb);
  wb.segment<4>(revolution_coord::P) *= scale;
  wb(revolution_coord::p_phi) = wa(revolution_coord::p_phi);
  const RevolutionImplicit torus(model.surface);
  const EmbeddedModel em{torus, model.body};
  const auto field = [&](const Embedded& y, Embedded& dy) { embedded_vector_field(em, y, dy); };
  const Embedded ya = integrate<18>(field, embed(model, wa), 4.0, 1e-13);
  const Embedded yb = integrate<18>(field, embed(model, wb), 4.0, 1e-13);
  EXPECT_LT((ya.head<6>() - yb.head<6>()).norm(), 1e-11);
  EXPECT_GT((ya.segment<6>(embedded::e1) - yb.segment<6>(embedded::e1)).norm(), 0.1);  // bodies differ
}

// Every catalog method that asks only for f steps the chart-free equations (StepProblem::field): WS1
// to T = 2 against the reference's 30-digit X(2), within a bound per method (its order at the step
// used); the splitting methods, which compose the constant-curvature chart's flows, refuse.
TEST(EmbeddedDynamics, CatalogMethodsStepTheChartFreeEquations) {
  const RevolutionModel model = ws1_model();
  const RevolutionImplicit torus(model.surface);
  const EmbeddedModel em{torus, model.body};
  const VectorField field = [&](const Coords& y, Coords& dy) {
    Embedded d;
    embedded_vector_field(em, y, d);
    dy = d;
  };
  const Scene unused_scene;
  const Chart unused_chart;
  const StepProblem problem{unused_scene, unused_chart, &field};
  const Eigen::Vector3d X2(2.8242096200506657, -0.6183870861207411, -0.9940546679244858);
  struct Bound {
    std::string_view name;
    double h, error;  // fixed step (adaptive: the first trial) [time], and the bound on |X(2) − X_ref|
  };
  // About 10× what was measured (2026-11-27): dop853 1.1e-15 (tolerance 1e-13), rk4 1.1e-13,
  // gauss4 4.5e-13, gauss6 2.5e-14, implicit midpoint 6.7e-8 (second order).
  const Bound bounds[] = {{"dop853", 0.01, 1e-13},
                          {"rk4", 1e-3, 1e-12},
                          {"gauss4", 4e-3, 5e-12},
                          {"gauss6", 0.02, 5e-13},
                          {"implicit_midpoint", 1e-3, 1e-6}};
  int stepped = 0;
  for (const CatalogEntry& entry : integrator_catalog()) {
    if (!entry.make) continue;  // the exact solution does not step
    SCOPED_TRACE(std::string(entry.info.name));
    std::unique_ptr<Integrator> integrator = entry.make();
    Coords y = ws1_state(), increment;
    if (entry.info.chart_flows_only) {
      EXPECT_THROW(integrator->try_step(problem, y, 0.01, 1e-12, increment), std::logic_error);
      continue;
    }
    const Bound* bound = nullptr;
    for (const Bound& b : bounds)
      if (b.name == entry.info.name) bound = &b;
    ASSERT_NE(bound, nullptr) << "a catalog method with no bound here";
    const FieldRun run = step_field(*integrator, problem, y, 2.0, bound->h, 1e-13);
    ASSERT_TRUE(run.ok);
    y = run.y;
    EXPECT_LT((y.head<3>() - X2).norm(), bound->error);
    EXPECT_NEAR(embedded_energy(em, y).total(), 0.7726449045081352, 100 * bound->error);
    ++stepped;
  }
  EXPECT_EQ(stepped, 5);
}

}  // namespace
}  // namespace spinfold
