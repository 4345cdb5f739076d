// physics.md §10: every worked number, from the JSON file beside physics.md.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/invariants.h"
#include "engine/paper_coordinates.h"
#include "engine/potentials.h"
#include "test_support.h"

namespace spinfold {
namespace {

using nlohmann::json;

const json& examples() {
  static const json data = [] {
    std::ifstream in(SPINFOLD_WORKED_EXAMPLES);
    return json::parse(in);
  }();
  return data;
}

Scene scene_from(const json& params, const json& gen) {
  Scene s;
  s.surface = {params["geometry"] == "sphere" ? SurfaceKind::sphere : SurfaceKind::pseudosphere,
               params["R"].get<double>()};
  s.body = {params["m"].get<double>(), params["J"].get<double>(), BodyModel::affine};
  s.potential.radial = RadialPotential{params["gamma_r"].get<double>()};
  const json& p = params["potential"];
  s.potential.deformation = AbcPotential{p["A"].get<double>(), p["B"].get<double>(), p["C"].get<double>()};
  InitialState& q = s.initial;
  double* fields[] = {&q.r,     &q.phi,     &q.alpha,     &q.beta,     &q.lambda,     &q.mu,
                      &q.r_dot, &q.phi_dot, &q.alpha_dot, &q.beta_dot, &q.lambda_dot, &q.mu_dot};
  for (int i = 0; i < 12; ++i) *fields[i] = gen[i].get<double>();
  s.integrator = {"dop853", 0.01, 1e-13};
  return s;
}

// Embedding state [X, V, e1, e2, W1, W2] as 18 numbers.
Eigen::Matrix<double, 18, 1> embedding_vector(const Scene& scene, const State& state) {
  const EmbeddedBody b = global_embedding(scene, state);
  Eigen::Matrix<double, 18, 1> v;
  v << b.X, b.V, b.e[0], b.e[1], b.W[0], b.W[1];
  return v;
}

// d/dt of a function of the state along the flow, by a central difference in the canonical
// coordinates (exact chart dynamics, no integrator).
template <typename F>
auto flow_derivative(const Scene& scene, const State& state, F f) {
  Coords dydt;
  vector_field(scene, state.chart, state.y, dydt);
  const double h = 1e-6;
  State plus = state, minus = state;
  plus.y += h * dydt;
  minus.y -= h * dydt;
  return ((f(plus) - f(minus)) / (2.0 * h)).eval();
}

class WorkedState : public ::testing::TestWithParam<std::string> {};

TEST_P(WorkedState, InvariantsMomentaAndRightHandSides) {
  const json& w = examples()[GetParam()];
  const Scene scene = scene_from(w["params"], w["gen"]);
  for (bool moved_chart : {false, true}) {
    SCOPED_TRACE(moved_chart ? "moved chart" : "scene chart");
    State state = initial_state(scene);
    if (moved_chart) recentre(scene, state);  // the same physical state in another chart
    EXPECT_EQ(state.chart.global, !moved_chart);

    EXPECT_NEAR(energy(scene, state), w["H"].get<double>(), 1e-13);
    EXPECT_NEAR(orbital_energy(scene, state), w["E_orb"].get<double>(), 1e-13);
    const auto sep = separated_energies(scene, state);
    ASSERT_TRUE(sep);
    EXPECT_NEAR(sep->C_x, w["C_x"].get<double>(), 1e-13);
    EXPECT_NEAR(sep->C_y, w["C_y"].get<double>(), 1e-13);
    EXPECT_NEAR(angular_momentum(scene, state), w["p_phi"].get<double>(), 1e-13);
    EXPECT_NEAR(spin(scene, state), w["p_alpha"].get<double>(), 1e-13);
    EXPECT_NEAR(vorticity(scene, state), w["p_beta"].get<double>(), 1e-13);

    Scene no_radial = scene;
    no_radial.potential.radial.reset();
    const auto M = momentum_map(no_radial, state);
    ASSERT_TRUE(M);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR((*M)[i], w["M"][i].get<double>(), 1e-13);
    if (w.contains("MetaM")) {
      EXPECT_NEAR(casimir(scene.surface, *M), w["MetaM"].get<double>(), 1e-13);
    }

    // Velocities ↔ momenta: the paper coordinates read back from the state.
    const PaperCoordinates c = paper_coordinates(scene, state);
    const json& gen = w["gen"];
    const json& can = w["canonical"];
    EXPECT_NEAR(c.r, gen[0].get<double>(), 1e-13);
    EXPECT_NEAR(*c.phi, gen[1].get<double>(), 1e-13);
    EXPECT_NEAR(*c.alpha, gen[2].get<double>(), 1e-13);
    EXPECT_NEAR(*c.beta, gen[3].get<double>(), 1e-13);
    EXPECT_NEAR(c.lambda, gen[4].get<double>(), 1e-13);
    EXPECT_NEAR(c.mu, gen[5].get<double>(), 1e-13);
    EXPECT_NEAR(*c.r_dot, gen[6].get<double>(), 1e-13);
    EXPECT_NEAR(*c.phi_dot, gen[7].get<double>(), 1e-13);
    EXPECT_NEAR(*c.alpha_dot, gen[8].get<double>(), 1e-13);
    EXPECT_NEAR(*c.beta_dot, gen[9].get<double>(), 1e-13);
    EXPECT_NEAR(c.lambda_dot, gen[10].get<double>(), 1e-13);
    EXPECT_NEAR(c.mu_dot, gen[11].get<double>(), 1e-13);
    EXPECT_NEAR(*c.p_r, can[6].get<double>(), 1e-13);
    EXPECT_NEAR(c.p_phi, can[7].get<double>(), 1e-13);
    EXPECT_NEAR(c.p_lambda, can[10].get<double>(), 1e-13);
    EXPECT_NEAR(c.p_mu, can[11].get<double>(), 1e-13);

    // Right-hand side of Hamilton's equations in the paper's chart: ṗ_r, ṗ_λ, ṗ_μ along the flow.
    const json& rhs = w["rhs_can"];
    const auto momenta = [&](const State& s) {
      const PaperCoordinates q = paper_coordinates(scene, s);
      return Eigen::Vector3d(*q.p_r, q.p_lambda, q.p_mu);
    };
    const Eigen::Vector3d p_dot = flow_derivative(scene, state, momenta);
    EXPECT_NEAR(p_dot[0], rhs[6].get<double>(), 1e-8);
    EXPECT_NEAR(p_dot[1], rhs[10].get<double>(), 1e-8);
    EXPECT_NEAR(p_dot[2], rhs[11].get<double>(), 1e-8);
    if (!moved_chart) {
      Coords dydt;
      vector_field(scene, state.chart, state.y, dydt);
      EXPECT_NEAR(dydt[coord::p_r], rhs[6].get<double>(), 1e-13);  // exact in the scene's chart
      EXPECT_EQ(dydt[coord::p_phi], 0.0);
    }

    // Embedding state and its right-hand side (physics.md §7).
    const Eigen::Matrix<double, 18, 1> emb = embedding_vector(scene, state);
    const auto emb_dot =
        flow_derivative(scene, state, [&](const State& s) { return embedding_vector(scene, s); });
    for (int i = 0; i < 18; ++i) {
      EXPECT_NEAR(emb[i], w["emb"][i].get<double>(), 1e-13) << "emb[" << i << "]";
      EXPECT_NEAR(emb_dot[i], w["rhs_emb"][i].get<double>(), 1e-8) << "rhs_emb[" << i << "]";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(PhysicsMd, WorkedState,
                         ::testing::Values("W1_sphere_state", "W2_pseudosphere_state"));

TEST(WorkedExamples, W5ClosedFormStateAtTwo) {
  const json& w = examples()["W5_closed_form_at_t2"];
  const Scene scene = scene_from(w["params"], w["gen0"]);
  const Simulation run = test::run_to(scene, 2.0);
  ASSERT_EQ(run.state.status, Status::ok);
  const PaperCoordinates c = paper_coordinates(scene, run.state);
  const json& g = w["gen_t2"];
  const double got[] = {c.r,      *c.phi,     *c.alpha,     *c.beta,     c.lambda,     c.mu,
                        *c.r_dot, *c.phi_dot, *c.alpha_dot, *c.beta_dot, c.lambda_dot, c.mu_dot};
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(got[i], g[i].get<double>(), 1e-10) << "gen_t2[" << i << "]";
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) EXPECT_NEAR((*c.L)(i, j), w["L_t2"][i][j].get<double>(), 1e-10);
}

TEST(WorkedExamples, W6PolarPotentialBothForms) {
  const json& w = examples()["W6_polar_potential_at_x03_y08"];
  const double x = 0.3, y = 0.8;
  for (const auto& [key, form] : {std::pair{"literal", PolarForm::literal}, {"cot2", PolarForm::cot2}}) {
    const json& e = w[key];
    const json& p = w["params"]["potential"];
    const PolarPotential polar{p["ghat"].get<double>(), p["gtilde"].get<double>(), form};
    const DeformationEnergy v = deformation_potential(polar, x * x, y * y);
    EXPECT_NEAR(v.value, e["V"].get<double>(), 1e-14) << key;
    EXPECT_NEAR(v.dV_da, e["dV_da"].get<double>(), 1e-13) << key;
    EXPECT_NEAR(v.dV_db, e["dV_db"].get<double>(), 1e-13) << key;
  }
}

TEST(WorkedExamples, W6CotFormIsRegularAtDetZero) {
  // b = a (det L = 0): Q = 0 and its derivatives are finite (physics.md §5, "expand first").
  const PolarPotential polar{0.1, -1.0, PolarForm::cot2};
  const DeformationEnergy v = deformation_potential(polar, 0.5, 0.5);
  EXPECT_TRUE(std::isfinite(v.dV_da));
  EXPECT_TRUE(std::isfinite(v.dV_db));
  EXPECT_NEAR(v.value, -1.0, 1e-15);
}

}  // namespace
}  // namespace spinfold
