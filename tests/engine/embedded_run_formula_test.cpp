// A scene on a formula surface (surface.kind implicit or graph), run as every scene runs: the
// scene's initial values reach physics-anysurface.md's worked states WF2 (an affine body on a graph,
// anisotropic J, gravity, abc, friction) and WF3 (a rigid body on a genus-2 surface, Newton from a
// guess), WF2's 34-digit trajectory is reproduced, the formula torus runs as the built-in torus does,
// the read-out at t = 0 gives back the scene's own values, projection keeps the body on F = 0, and
// the refusals (WF4) name the field, the position and the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "engine/embedded_run.h"
#include "engine/initial_rates.h"
#include "engine/readout.h"
#include "engine/simulation.h"
#include "engine/validation.h"
#include "formula_surfaces.h"

namespace spinfold {
namespace {

using nlohmann::json;

const json& examples() {
  static const json data = [] {
    std::ifstream in(SPINFOLD_ANYSURFACE_EXAMPLES);
    return json::parse(in);
  }();
  return data;
}

Coords vec(const json& j) {
  Coords v(static_cast<Eigen::Index>(j.size()));
  for (std::size_t i = 0; i < j.size(); ++i) v(static_cast<Eigen::Index>(i)) = j[i].get<double>();
  return v;
}

void expect_close(const Coords& got, const Coords& want, double tolerance) {
  ASSERT_EQ(got.size(), want.size());
  for (Eigen::Index i = 0; i < want.size(); ++i)
    EXPECT_NEAR(got(i), want(i), tolerance * (1.0 + std::abs(want(i)))) << "entry " << i;
}

// WF2 as a scene: the graph, its body and start as physics-anysurface.md §11 gives them.
Scene wf2_scene() {
  const json& w = examples()["WF2"];
  const json& s = w["start"];
  Scene scene;
  scene.surface.kind = SurfaceKind::graph;
  scene.surface.z = w["surface"].get<std::string>();
  scene.body.mass = 1.5;
  scene.body.inertia_matrix = InertiaMatrix{0.5, 0.1, 0.1, 0.35};
  scene.potential.height = GravityPotential{0.8};
  scene.potential.deformation = AbcPotential{0.01, 0.2, 0.3};
  scene.friction = Friction{0.1, 0.05};
  scene.initial.X = {s["X0"][0].get<double>(), s["X0"][1].get<double>(), 123.0};  // z is the graph's
  scene.initial.speed = s["speed"].get<double>();
  scene.initial.heading = s["heading"].get<double>();
  for (const auto& [key, slot] : {std::pair{"lambda", &InitialState::lambda},
                                  {"mu", &InitialState::mu},
                                  {"alpha", &InitialState::alpha},
                                  {"beta", &InitialState::beta},
                                  {"lambda_dot", &InitialState::lambda_dot},
                                  {"mu_dot", &InitialState::mu_dot},
                                  {"alpha_dot", &InitialState::alpha_dot},
                                  {"beta_dot", &InitialState::beta_dot}})
    scene.initial.*slot = s[key].get<double>();
  scene.integrator.tolerance = 1e-12;
  return scene;
}

// WF3: a rigid body on the genus-2 surface, started from a guess off it.
Scene wf3_scene() {
  const json& w = examples()["WF3"];
  Scene scene;
  scene.surface.kind = SurfaceKind::implicit;
  scene.surface.F = w["surface"].get<std::string>();
  scene.surface.parameters = {{"a", 1.0}, {"c", 0.5}, {"r", 0.7}};
  scene.body.model = BodyModel::rigid;
  scene.body.inertia = 0.25;
  scene.initial.X = {1.2, 0.3, 0.2};
  scene.initial.lambda = scene.initial.mu = 0.8;
  scene.initial.alpha = 0.4;  // θ = α − β
  scene.initial.speed = 0.5;
  scene.initial.heading = 1.0;
  scene.initial.spin = 0.6;
  EXPECT_TRUE(resolve_initial_rates(scene).empty());
  return scene;
}

TEST(EmbeddedRunFormula, TheGraphScenesStartIsWF2sState) {
  const Scene scene = wf2_scene();
  const auto errors = validate_scene(scene);
  ASSERT_TRUE(errors.empty()) << errors.front().field << ": " << errors.front().reason;
  const Simulation run = start_simulation(scene);
  ASSERT_NE(run.embedded, nullptr);
  EXPECT_FALSE(run.surface->profile);
  EXPECT_TRUE(run.embedded->project);  // the formula surfaces' default
  expect_close(run.state.y, vec(examples()["WF2"]["Y0"]), 1e-14);
}

TEST(EmbeddedRunFormula, TheReadoutOfWF2sStartHasItsNumbersAndGivesTheScenesValuesBack) {
  const Scene scene = wf2_scene();
  const Readout r = readout(start_simulation(scene));
  const json& w = examples()["WF2"];
  EXPECT_NEAR(r.energy, w["H"].get<double>(), 1e-14);
  EXPECT_NEAR(r.spin, w["s"].get<double>(), 1e-14);
  EXPECT_NEAR(r.vorticity, w["p_beta"].get<double>(), 1e-14);
  EXPECT_NEAR(r.det_L, w["detL"].get<double>(), 1e-14);
  ASSERT_TRUE(r.curvature && r.embedded);
  EXPECT_NEAR(*r.curvature, w["K"].get<double>(), 1e-14);
  EXPECT_NEAR(r.embedded->drift, 0.0, 1e-16);
  const Coords nE = vec(w["n, E1, E2"][0]);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(r.embedded->n[i], nE(i), 1e-14);
  // The convention's frame at X reads L back: α, β, λ, μ and their rates as the scene gave them.
  const PaperCoordinates& c = r.coordinates;
  EXPECT_NEAR(*c.alpha, 0.2, 1e-13);
  EXPECT_NEAR(*c.beta, -0.3, 1e-13);
  EXPECT_NEAR(c.lambda, 1.1, 1e-13);
  EXPECT_NEAR(c.mu, 0.6, 1e-13);
  EXPECT_NEAR(*c.alpha_dot, 0.4, 1e-12);
  EXPECT_NEAR(*c.beta_dot, 0.2, 1e-12);
  EXPECT_NEAR(c.lambda_dot, 0.1, 1e-12);
  EXPECT_NEAR(c.mu_dot, -0.05, 1e-12);
  EXPECT_NEAR(*r.speed, 0.7, 1e-14);
  EXPECT_FALSE(c.phi.has_value());  // no chart
}

TEST(EmbeddedRunFormula, WF2sRunReachesItsReferenceAtTOne) {
  Simulation run = start_simulation(wf2_scene());
  ASSERT_TRUE(advance_to(run, 1.0));
  ASSERT_EQ(run.state.status, Status::ok);
  const json& w = examples()["WF2"];
  const Coords X_ref = vec(w["X(1)"]), e1_ref = vec(w["e1(1)"]);
  const Readout r = readout(run);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(r.coordinates.X[i], X_ref(i), 2e-11) << i;
    EXPECT_NEAR(r.embedded->e1[i], e1_ref(i), 2e-11) << i;
  }
  EXPECT_NEAR(r.energy, w["H(1)"].get<double>(), 2e-11);
  EXPECT_LT(r.embedded->drift, 1e-15);  // projected after every step
}

TEST(EmbeddedRunFormula, TheImplicitScenesStartIsWF3sStateFromAGuessOffTheSurface) {
  const Scene scene = wf3_scene();
  const auto errors = validate_scene(scene);
  ASSERT_TRUE(errors.empty()) << errors.front().field << ": " << errors.front().reason;
  const Simulation run = start_simulation(scene);
  expect_close(run.state.y, vec(examples()["WF3"]["Y0"]), 1e-13);
  const Readout r = readout(run);
  EXPECT_NEAR(r.energy, examples()["WF3"]["H"].get<double>(), 1e-13);
  EXPECT_NEAR(*r.curvature, examples()["WF3"]["K"].get<double>(), 1e-11);
  EXPECT_NEAR(r.spin, 0.6, 1e-14);
}

// The torus a = 1, c = 2.5 as a formula and as the built-in kind, from the same point: at φ = 0 and
// u ∈ (−π, 0) the convention's E₁ (the x-axis's tangential part) is the profile's X_u/f, so the two
// scenes start in the same state and run the same equations, with projection and without.
TEST(EmbeddedRunFormula, TheFormulaTorusRunsAsTheBuiltInTorus) {
  for (const BodyModel model : {BodyModel::affine, BodyModel::rigid}) {
    Scene torus;
    torus.surface.kind = SurfaceKind::torus;
    torus.body.model = model;
    torus.initial.u = -0.7;
    torus.initial.phi = 0.0;
    torus.initial.lambda = torus.initial.mu = 0.9;
    torus.initial.alpha = 0.3;
    torus.initial.speed = 0.8;
    torus.initial.heading = 0.9;
    torus.initial.spin = 0.35;
    torus.integrator.tolerance = 1e-13;
    torus.integrator.projection = Projection::off;
    Scene formula = torus;
    formula.surface.kind = SurfaceKind::implicit;
    formula.surface.F = "(x^2 + y^2 + z^2 + c^2 - a^2)^2 - 4*c^2*(x^2 + y^2)";  // the built-in's F
    formula.surface.parameters = {{"a", 1.0}, {"c", 2.5}};
    formula.initial.X = {2.5 + std::cos(-0.7), 0.0, -std::sin(-0.7)};
    formula.integrator.projection = Projection::off;
    ASSERT_TRUE(resolve_initial_rates(torus).empty());
    ASSERT_TRUE(resolve_initial_rates(formula).empty());
    ASSERT_TRUE(validate_scene(formula).empty()) << validate_scene(formula).front().reason;
    Simulation a = start_simulation(torus), b = start_simulation(formula);
    expect_close(b.state.y, a.state.y, 1e-15);
    ASSERT_TRUE(advance_to(a, 20.0));
    ASSERT_TRUE(advance_to(b, 20.0));
    expect_close(b.state.y, a.state.y, 1e-12);
    EXPECT_NEAR(readout(b).curvature.value(), readout(a).curvature.value(), 1e-11);
    // With projection (the default on both) the two agree again, and so does the same torus written
    // another way, F = (ρ − c)² + z² − a²; each agrees with the unprojected run to its error.
    torus.integrator.projection = formula.integrator.projection = Projection::automatic;
    Simulation projected = start_simulation(torus), c = start_simulation(formula);
    ASSERT_TRUE(advance_to(projected, 20.0));
    ASSERT_TRUE(advance_to(c, 20.0));
    expect_close(c.state.y, projected.state.y, 1e-12);
    expect_close(c.state.y, a.state.y, 1e-9);
    formula.surface.F = "(sqrt(x^2 + y^2) - c)^2 + z^2 - a^2";
    Simulation d = start_simulation(formula);
    expect_close(d.state.y, start_simulation(torus).state.y, 1e-15);
    ASSERT_TRUE(advance_to(d, 20.0));
    expect_close(d.state.y, projected.state.y, 1e-12);
  }
}

TEST(EmbeddedRunFormula, ProjectionKeepsTheBodyOnTheSurfaceWhereWithoutItItDrifts) {
  Scene scene = wf3_scene();
  scene.integrator.tolerance = 1e-8;
  Simulation on = start_simulation(scene);
  scene.integrator.projection = Projection::off;
  Simulation off = start_simulation(scene);
  ASSERT_TRUE(advance_to(on, 30.0));
  ASSERT_TRUE(advance_to(off, 30.0));
  const double drift_on = readout(on).embedded->drift, drift_off = readout(off).embedded->drift;
  EXPECT_LT(drift_on, 1e-14);
  EXPECT_GT(drift_off, 100.0 * drift_on);
  EXPECT_GT(drift_off, 1e-12);
}

TEST(EmbeddedRunFormula, RefusalsNameTheFieldThePositionAndTheReason) {
  Scene scene;
  scene.surface.kind = SurfaceKind::implicit;
  scene.surface.F = "abs(x) + y^2 + z^2 - 1";
  auto errors = validate_scene(scene);
  ASSERT_FALSE(errors.empty());
  EXPECT_EQ(errors.front().field, "surface.F");
  EXPECT_NE(errors.front().reason.find("at position 0"), std::string::npos) << errors.front().reason;
  EXPECT_NE(errors.front().reason.find("abs"), std::string::npos) << errors.front().reason;

  scene.surface.F = "x^2 + y^2 - z^2";  // a cone: singular at its apex
  scene.initial.X = {0.0, 0.0, 0.0};
  errors = validate_scene(scene);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors.front().field, "initial.X");
  EXPECT_NE(errors.front().reason.find("singular"), std::string::npos) << errors.front().reason;

  scene.surface.F = "x^2 + y^2 + z^2 - R^2";
  scene.surface.parameters = {{"R", std::numeric_limits<double>::infinity()}, {"2b", 1.0}};
  scene.initial.X = {1.0, 0.0, 0.0};
  errors = validate_scene(scene);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0].field, "surface.parameters.2b");
  EXPECT_EQ(errors[1].field, "surface.parameters.R");

  Scene graph;
  graph.surface.kind = SurfaceKind::graph;
  graph.surface.z = "log(x)";  // undefined for x <= 0
  graph.initial.X = {-1.0, 0.0, 0.0};
  errors = validate_scene(graph);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors.front().field, "initial.X");
  graph.initial.X = {2.0, 0.0, 0.0};
  EXPECT_TRUE(validate_scene(graph).empty());

  Scene bounded = graph;
  bounded.surface.bounds = SurfaceBounds{{{0.0, 1.0}, {2.0, 1.0}, {0.0, 1.0}}};
  errors = validate_scene(bounded);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors.front().field, "surface.bounds[1]");
}

// The hemisphere z = √(1 − x² − y²) as a graph: its slope is infinite on the rim, reached at t = π/2
// from the top at unit speed, beyond which the formula is undefined.
TEST(EmbeddedRunFormula, ABodyThatLeavesTheFormulasDomainStopsWithItsLastGoodState) {
  Scene scene;
  scene.surface.kind = SurfaceKind::graph;
  scene.surface.z = "sqrt(1 - x^2 - y^2)";
  scene.initial.X = {0.0, 0.0, 0.0};
  scene.initial.speed = 1.0;
  scene.initial.heading = 0.0;
  scene.body.model = BodyModel::rigid;
  ASSERT_TRUE(validate_scene(scene).empty()) << validate_scene(scene).front().reason;
  Simulation run = start_simulation(scene);
  advance_to(run, 5.0);
  EXPECT_NE(run.state.status, Status::ok);
  EXPECT_TRUE(run.state.y.allFinite());
  EXPECT_LT(run.state.y(0), 1.0);
  EXPECT_LE(run.state.t, 0.5 * std::numbers::pi + 1e-6);
}

// Joachimsthal's integral on the triaxial ellipsoid x²/a² + y²/b² + z²/c² = 1: along a geodesic the
// distance p from the centre to the tangent plane times the semi-diameter D parallel to the velocity
// is constant. A body without spin (s = 0, no potentials) follows a geodesic and keeps it; a spinning
// one is pushed off the geodesic by K s (physics-anysurface.md §2) and does not.
double joachimsthal(const Readout& r, double a, double b, double c) {
  return test::joachimsthal_integral(r.coordinates.X, r.embedded->V, a, b, c);
}

TEST(EmbeddedRunFormula, OnTheTriaxialEllipsoidJoachimsthalsIntegralHoldsWithoutSpinAndNotWithIt) {
  const double a = 2.0, b = 1.4, c = 0.9;
  for (const double spin : {0.0, 0.5}) {
    Scene scene;
    scene.surface.kind = SurfaceKind::implicit;
    scene.surface.F = "x^2/a^2 + y^2/b^2 + z^2/c^2 - 1";
    scene.surface.parameters = {{"a", a}, {"b", b}, {"c", c}};
    scene.body.model = BodyModel::rigid;
    scene.initial.X = {1.2, 0.9, 0.4};
    scene.initial.speed = 0.8;
    scene.initial.heading = 0.7;
    scene.initial.spin = spin;
    scene.integrator.tolerance = 1e-12;
    ASSERT_TRUE(resolve_initial_rates(scene).empty());
    ASSERT_TRUE(validate_scene(scene).empty()) << validate_scene(scene).front().reason;
    Simulation run = start_simulation(scene);
    const double first = joachimsthal(readout(run), a, b, c);
    double spread = 0.0;
    for (int k = 1; k <= 40; ++k) {
      ASSERT_TRUE(advance_to(run, 0.5 * k));
      spread = std::max(spread, std::abs(joachimsthal(readout(run), a, b, c) / first - 1.0));
    }
    if (spin == 0.0)
      EXPECT_LT(spread, 1e-9);
    else
      EXPECT_GT(spread, 1e-2);
  }
}

// The headline on a surface with no symmetry, measured from the path alone: a spinning rigid body's
// geodesic curvature κ_g = n·(V × A)/|V|³ (V and A by central differences of the sampled X) is
// K s/(m v) with K from F at the body (physics-anysurface.md §2), over the monkey saddle's K < 0.
TEST(EmbeddedRunFormula, TheMonkeySaddleBendsThePathByKsOverMv) {
  Scene scene;
  scene.surface.kind = SurfaceKind::graph;
  scene.surface.z = "k*(x^3 - 3*x*y^2)";
  scene.surface.parameters = {{"k", 0.4}};
  scene.body.model = BodyModel::rigid;
  scene.body.mass = 1.3;
  scene.initial.X = {0.3, -0.2, 0.0};
  scene.initial.speed = 0.6;
  scene.initial.heading = 2.0;
  scene.initial.spin = 0.7;
  scene.integrator.tolerance = 1e-13;
  ASSERT_TRUE(resolve_initial_rates(scene).empty());
  Simulation run = start_simulation(scene);
  const double h = 1e-3;
  int checked = 0;
  for (double t = 0.5; t <= 4.0; t += 0.5) {
    // The run lands on any time exactly, whatever the times asked before (simulation.h).
    Vec3 X[3];
    Readout r;
    for (int i = 0; i < 3; ++i) {
      ASSERT_TRUE(advance_to(run, t + (i - 1) * h));
      const Readout here = readout(run);
      X[i] = here.coordinates.X;
      if (i == 1) r = here;
    }
    const Vec3 V = (X[2] - X[0]) / (2 * h), A = (X[2] - 2 * X[1] + X[0]) / (h * h);
    const double kappa = r.embedded->n.dot(V.cross(A)) / std::pow(V.norm(), 3);
    const double predicted = *r.curvature * r.spin / (scene.body.mass * *r.speed);
    EXPECT_NEAR(kappa, predicted, 1e-5 * (1.0 + std::abs(predicted))) << "t = " << t;
    EXPECT_LT(*r.curvature, 0.0);
    ++checked;
  }
  EXPECT_EQ(checked, 8);
}

}  // namespace
}  // namespace spinfold
