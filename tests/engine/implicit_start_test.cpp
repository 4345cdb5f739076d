// Starting a body on a surface known only by its formula (engine/implicit_start.h) against
// physics-anysurface.md §11: WF1 (Newton, the start frame, K), WF2 (an affine body on a graph: the
// start state, the vector field, its invariants, and its trajectory integrated by Boost.Odeint against
// the reference's 34-digit X(1)), WF3 (a rigid body on a genus-2 surface), WF4 (a singular start),
// and random starts near a triaxial ellipsoid.
#include "engine/implicit_start.h"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/formula_surface.h"
#include "tests/engine/formula_examples.h"
#include "tests/engine/revolution_examples.h"

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

Eigen::VectorXd vec(const json& j) {
  Eigen::VectorXd v(j.size());
  for (std::size_t i = 0; i < j.size(); ++i) v(static_cast<Eigen::Index>(i)) = j[i].get<double>();
  return v;
}

void expect_close(const Eigen::VectorXd& got, const Eigen::VectorXd& want, double tolerance) {
  ASSERT_EQ(got.size(), want.size());
  for (Eigen::Index i = 0; i < want.size(); ++i)
    EXPECT_NEAR(got(i), want(i), tolerance * (1.0 + std::abs(want(i)))) << "entry " << i;
}

FormulaSurface surface(FormulaSurfaceForm form, std::string_view text, const FormulaParameters& p = {}) {
  FormulaSurfaceParse parsed = parse_formula_surface(form, text, p);
  EXPECT_TRUE(parsed.surface) << parsed.error.reason;
  return std::move(*parsed.surface);
}

FormulaSurface wf1_ellipsoid() {
  return surface(FormulaSurfaceForm::implicit, "x^2/a^2 + y^2/b^2 + z^2/c^2 - 1",
                 {{"a", 2}, {"b", 1.5}, {"c", 1}});
}

// U(α) diag(λ, μ) U(β)ᵀ and its rate α̇εL − β̇Lε + U(α) diag(λ̇, μ̇) U(β)ᵀ (§5.5, §5.6).
std::pair<Mat2, Mat2> internal(const json& s) {
  const Mat2 Ua = rotation2(s["alpha"].get<double>()), Ub = rotation2(s["beta"].get<double>()),
             eps = epsilon();
  const Mat2 L =
      Ua * Eigen::Vector2d(s["lambda"].get<double>(), s["mu"].get<double>()).asDiagonal() * Ub.transpose();
  const Mat2 L_dot =
      s["alpha_dot"].get<double>() * eps * L - s["beta_dot"].get<double>() * L * eps +
      Ua * Eigen::Vector2d(s["lambda_dot"].get<double>(), s["mu_dot"].get<double>()).asDiagonal() *
          Ub.transpose();
  return {L, L_dot};
}

TEST(ImplicitStart, NewtonTheFrameAndTheCurvatureWF1) {
  const FormulaSurface ellipsoid = wf1_ellipsoid();
  for (const char* branch : {"generic", "fallback"}) {
    SCOPED_TRACE(branch);
    const json& w = examples()["WF1"][branch];
    const SurfaceFoot foot = project_onto_surface(ellipsoid, vec(w["guess"]), 1.0, 1.0);
    ASSERT_TRUE(foot.X) << foot.refusal;
    // The first iterates are the reference's (later ones are round-off in double).
    for (std::size_t k = 0; k < 3; ++k)
      EXPECT_NEAR(foot.F_iterates[k], w["F_iterates"][k].get<double>(),
                  1e-12 * (1 + std::abs(foot.F_iterates[k])));
    EXPECT_LE(foot.iterations, 5);
    expect_close(*foot.X, vec(w["X0"]), 1e-15);
    const StartFrame f = start_frame(ellipsoid, *foot.X);
    expect_close(f.n, vec(w["n"]), 1e-15);
    expect_close(f.E1, vec(w["E1"]), 1e-14);
    expect_close(f.E2, vec(w["E2"]), 1e-14);
    EXPECT_NEAR(f.x_projection, w["|projection of x-axis|"].get<double>(), 1e-15);
    EXPECT_NEAR(bordered_hessian_curvature(ellipsoid.at(*foot.X)), w["K"].get<double>(), 1e-14);
  }
}

// An affine body on the graph z = 0.3x²y − 0.2y² + 0.1x with every force: the start, dY/dt, the
// invariants, then the trajectory to t = 1 against the reference.
TEST(ImplicitStart, AnAffineBodyOnAGraphWF2) {
  const json& w = examples()["WF2"];
  const FormulaSurface graph = surface(FormulaSurfaceForm::graph, w["surface"].get<std::string>());
  const json& s = w["start"];
  const Vec3 X0 = vec(s["X0"]);
  EXPECT_NEAR(graph.height(X0.x(), X0.y()), X0.z(), 1e-16);
  const SurfaceFoot foot = project_onto_surface(graph, X0, 1.0, 1.0);
  ASSERT_TRUE(foot.X);
  EXPECT_EQ(foot.iterations, 0);  // already on the graph
  const StartFrame f = start_frame(graph, *foot.X);
  expect_close(f.n, vec(w["n, E1, E2"][0]), 1e-15);
  expect_close(f.E1, vec(w["n, E1, E2"][1]), 1e-15);
  expect_close(f.E2, vec(w["n, E1, E2"][2]), 1e-15);
  const auto [L, L_dot] = internal(s);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      EXPECT_NEAR(L(i, j), w["L"][i][j].get<double>(), 1e-15);
      EXPECT_NEAR(L_dot(i, j), w["Ldot"][i][j].get<double>(), 1e-15);
    }
  const Embedded Y0 =
      affine_start_in_frame(f, *foot.X, s["speed"].get<double>(), s["heading"].get<double>(), L, L_dot);
  expect_close(Y0, vec(w["Y0"]), 1e-15);

  const json& b = w["body"];
  const SurfaceBody body{.mass = b["m"].get<double>(),
                         .inertia = test::inertia_matrix(0.5, 0.1, 0.35),
                         .height = GravityPotential{b["height"]["g"].get<double>()},
                         .deformation = AbcPotential{0.01, 0.2, 0.3},
                         .friction = {0.1, 0.05}};
  const EmbeddedModel model{graph, body};
  Embedded dY;
  embedded_vector_field(model, Y0, dY);
  expect_close(dY, vec(w["Ydot0"]), 1e-14);
  const EmbeddedEnergy E = embedded_energy(model, Y0);
  EXPECT_NEAR(E.total(), w["H"].get<double>(), 1e-14);
  EXPECT_NEAR(E.orbital, w["E_orb"].get<double>(), 1e-14);
  EXPECT_NEAR(embedded_spin(model, Y0), w["s"].get<double>(), 1e-14);
  EXPECT_NEAR(embedded_det_L(model, Y0), w["detL"].get<double>(), 1e-14);
  EXPECT_NEAR(embedded_rayleigh(model, Y0), w["R"].get<double>(), 1e-14);
  EXPECT_NEAR(bordered_hessian_curvature(graph.at(X0)), w["K"].get<double>(), 1e-15);

  const Embedded Y1 = test::rkf78<18>(
      [&](const Embedded& y, Embedded& d) { embedded_vector_field(model, y, d); }, Y0, 1.0, 1e-14);
  expect_close(Y1.segment<3>(embedded::X), vec(w["X(1)"]), 1e-12);
  expect_close(Y1.segment<3>(embedded::e1), vec(w["e1(1)"]), 1e-12);
  EXPECT_NEAR(embedded_energy(model, Y1).total(), w["H(1)"].get<double>(), 1e-12);
  EXPECT_LT(std::abs(graph.at(Y1.segment<3>(embedded::X)).F), 1e-12);
}

// A spinning rigid body on the genus-2 surface: Newton from the guess, the state, dY/dt, E and K.
TEST(ImplicitStart, ARigidBodyOnAGenusTwoSurfaceWF3) {
  const json& w = examples()["WF3"];
  const FormulaSurface genus2 = surface(FormulaSurfaceForm::implicit, w["surface"].get<std::string>(),
                                        {{"a", 1.0}, {"c", 0.5}, {"r", 0.7}});
  const json& s = w["start"];
  const SurfaceFoot foot = project_onto_surface(genus2, vec(s["guess"]), 1.0, 1.0);
  ASSERT_TRUE(foot.X) << foot.refusal;
  EXPECT_LE(foot.iterations, w["Newton iterations"].get<int>());
  const StartFrame f = start_frame(genus2, *foot.X);
  const double lambda0 = w["body"]["lam0"].get<double>();
  const Mat2 L = lambda0 * rotation2(s["theta"].get<double>());
  const EmbeddedRigid Y0 = rigid_start_in_frame(f, *foot.X, s["speed"].get<double>(),
                                                s["heading"].get<double>(), L, s["spin"].get<double>());
  expect_close(Y0, vec(w["Y0"]), 1e-14);
  SurfaceBody body;
  body.inertia = test::inertia_matrix(0.25, 0.0, 0.25);  // m = 1, no potential, no friction
  const EmbeddedModel model{genus2, body};
  EmbeddedRigid dY;
  embedded_rigid_vector_field(model, Y0, dY);
  expect_close(dY, vec(w["Ydot0"]), 1e-13);
  EXPECT_NEAR(embedded_rigid_energy(model, Y0), w["H"].get<double>(), 1e-14);
  const double K = bordered_hessian_curvature(genus2.at(*foot.X));
  EXPECT_NEAR(K, w["K"].get<double>(), 1e-13);
  EXPECT_NEAR(K * 0.6 / (1.0 * 0.5), w["kappa_g = K s/(m v)"].get<double>(), 1e-13);
}

// WF4 and §7: a start at a singular point, a squared formula, a point where the formula is undefined,
// and a jump to another sheet are refused with the reason.
TEST(ImplicitStart, RefusesWhatHasNoTangentPlane) {
  const FormulaSurface cone = surface(FormulaSurfaceForm::implicit, "x^2 + y^2 - z^2");
  SurfaceFoot foot = project_onto_surface(cone, Vec3::Zero(), 1.0, 1.0);
  EXPECT_FALSE(foot.X);
  EXPECT_NE(foot.refusal.find("singular point of the surface: |grad F| = 0.000e+00 at X = (0, 0, 0)"),
            std::string::npos)
      << foot.refusal;
  const FormulaSurface squared = surface(FormulaSurfaceForm::implicit, "(x^2 + y^2 + z^2 - 1)^2");
  foot = project_onto_surface(squared, Vec3(1.2, 0.1, 0.0), 1.0, 1.0);
  EXPECT_FALSE(foot.X);
  EXPECT_NE(foot.refusal.find("singular point"), std::string::npos) << foot.refusal;
  const FormulaSurface logarithm = surface(FormulaSurfaceForm::implicit, "log(x) - z");
  foot = project_onto_surface(logarithm, Vec3(-1.0, 0.0, 0.0), 1.0, 1.0);
  EXPECT_FALSE(foot.X);
  EXPECT_NE(foot.refusal.find("undefined at X = (-1, 0, 0)"), std::string::npos) << foot.refusal;
  const FormulaSurface sheets = surface(FormulaSurfaceForm::implicit, "x^2 + y^2 - z^2 + 1");
  foot = project_onto_surface(sheets, Vec3(0.0, 0.0, 0.2), 1.0, 0.5);
  EXPECT_FALSE(foot.X);
  EXPECT_NE(foot.refusal.find("farther than"), std::string::npos) << foot.refusal;
}

// Random guesses near a triaxial ellipsoid: the foot is on the surface to round-off, the frame is
// orthonormal and right-handed with n, E₁ comes from the x-axis unless its projection is short.
TEST(ImplicitStart, RandomStartsLandOnTheSurfaceWithTheConventionsFrame) {
  const FormulaSurface ellipsoid = wf1_ellipsoid();
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> off(-0.2, 0.2);
  int fallback = 0;
  for (int trial = 0; trial < 500; ++trial) {
    // Every tenth near a tip on the x-axis, where the frame comes from the y-axis.
    const double spread = trial % 10 == 0 ? 0.01 : 1.0;
    const Vec3 d = Vec3(normal(rng), spread * normal(rng), spread * normal(rng)).normalized();
    const Vec3 on(2 * d.x(), 1.5 * d.y(), d.z());
    const Vec3 guess = on + off(rng) * d;
    const SurfaceFoot foot = project_onto_surface(ellipsoid, guess, 1.0, 1.0);
    ASSERT_TRUE(foot.X) << foot.refusal;
    const ImplicitPoint p = ellipsoid.at(*foot.X);
    EXPECT_LT(std::abs(p.F) / p.gradient.norm(), 2e-15);
    EXPECT_LE(foot.iterations, 8);
    const StartFrame f = start_frame(ellipsoid, *foot.X);
    EXPECT_NEAR(f.E1.norm(), 1.0, 1e-15);
    EXPECT_NEAR(f.E1.dot(f.n), 0.0, 1e-15);
    EXPECT_NEAR(f.E2.dot(f.E1), 0.0, 1e-15);
    EXPECT_NEAR(f.E1.cross(f.E2).dot(f.n), 1.0, 1e-15);
    if (f.x_projection < 0.1) {
      ++fallback;
      EXPECT_NEAR(f.E2.y(), 0.0, 1e-15);  // E₁ in the plane of ŷ and n: E₂ ⊥ ŷ
    } else {
      EXPECT_NEAR(f.E2.x(), 0.0, 1e-15);  // E₁ in the plane of x̂ and n: E₂ ⊥ x̂
    }
  }
  EXPECT_GE(fallback, 40);
}

}  // namespace
}  // namespace spinfold
