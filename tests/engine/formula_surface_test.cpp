// Formula surfaces (engine/formula_surface.h): the built-in surfaces of revolution written as formulas
// give the same F, ∇F and Hess F to round-off and the same path (integrated by Boost.Odeint); a graph's
// F = z − f and the closed forms of K for graphs and the triaxial ellipsoid (physics-anysurface.md §1).
#include "engine/formula_surface.h"

#include <gtest/gtest.h>

#include <random>

#include "engine/embedded_dynamics.h"
#include "tests/engine/formula_examples.h"
#include "tests/engine/revolution_examples.h"

namespace spinfold {
namespace {

FormulaSurface surface(FormulaSurfaceForm form, std::string_view text, const FormulaParameters& p = {}) {
  FormulaSurfaceParse parsed = parse_formula_surface(form, text, p);
  EXPECT_TRUE(parsed.surface) << parsed.error.reason;
  return std::move(*parsed.surface);
}

struct Written {
  RevolutionSurface built_in;
  FormulaSurfaceForm form;
  std::string_view text;
  FormulaParameters parameters;
};

std::vector<Written> written_out() {
  return {
      {{.kind = SurfaceKind::torus, .tube_radius = 1.0, .center_radius = 3.0},
       FormulaSurfaceForm::implicit,
       "(x^2 + y^2 + z^2 + c^2 - a^2)^2 - 4*c^2*(x^2 + y^2)",
       {{"a", 1.0}, {"c", 3.0}}},
      {{.kind = SurfaceKind::spheroid, .equatorial_radius = 1.3, .polar_radius = 0.7},
       FormulaSurfaceForm::implicit,
       "(x^2 + y^2)/a^2 + z^2/b^2 - 1",
       {{"a", 1.3}, {"b", 0.7}}},
      {{.kind = SurfaceKind::bump, .height = 0.8, .width = 0.6},
       FormulaSurfaceForm::graph,
       "h*exp(-(x^2 + y^2)/(2*w^2))",
       {{"h", 0.8}, {"w", 0.6}}},
      {{.kind = SurfaceKind::catenoid, .neck_radius = 1.2},
       FormulaSurfaceForm::implicit,
       "x^2 + y^2 - c^2*cosh(z/c)^2",
       {{"c", 1.2}}},
  };
}

double relative(double got, double want) {
  return std::abs(got - want) / (1.0 + std::abs(want));
}

// 200 random points of ℝ³ each: F, ∇F, Hess F of the formula equal the built-in kind's to 1e-13.
TEST(FormulaSurface, TheBuiltInSurfacesWrittenAsFormulasAreTheSameFunctions) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  for (const Written& w : written_out()) {
    SCOPED_TRACE(std::string(w.text));
    const FormulaSurface formula = surface(w.form, w.text, w.parameters);
    const RevolutionImplicit built_in(w.built_in);
    for (int i = 0; i < 200; ++i) {
      const Vec3 X(coordinate(rng), coordinate(rng), coordinate(rng));
      const ImplicitPoint a = formula.at(X), b = built_in.at(X);
      const double scale = 1.0 + std::abs(b.F) + b.gradient.norm() + b.hessian.norm();
      EXPECT_LT(std::abs(a.F - b.F), 1e-13 * scale);
      EXPECT_LT((a.gradient - b.gradient).norm(), 1e-13 * scale);
      EXPECT_LT((a.hessian - b.hessian).norm(), 1e-13 * scale);
      EXPECT_EQ(formula.value(X), a.F);
    }
  }
}

// WS1's affine body (anisotropic J, gravity, abc) on the formula torus and on the built-in torus, the
// same start, integrated by RKF78 at 1e-13 to t = 5: the same path within 1e-12.
TEST(FormulaSurface, TheFormulaTorusGivesTheBuiltInTorussPath) {
  const RevolutionModel m = test::ws1_model();
  const std::vector<Written> all = written_out();  // kept: w refers into it
  const Written& w = all[0];
  ASSERT_EQ(w.built_in.center_radius, m.surface.center_radius);
  const FormulaSurface formula = surface(w.form, w.text, w.parameters);
  const RevolutionImplicit built_in(m.surface);
  const auto run = [&](const ImplicitSurface& s) {
    const EmbeddedModel model{s, m.body};
    return test::rkf78<18>([&](const Embedded& y, Embedded& d) { embedded_vector_field(model, y, d); },
                           test::ws1_state(), 5.0, 1e-13);
  };
  const Embedded a = run(formula), b = run(built_in);
  EXPECT_LT((a - b).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_GT((a - test::ws1_state()).norm(), 1.0);  // it moved
}

// K from the bordered Hessian (§1) against the closed forms of a graph, (f_xx f_yy − f_xy²)/(1 + |∇f|²)²,
// and of the triaxial ellipsoid, 1/(a²b²c² (x²/a⁴ + y²/b⁴ + z²/c⁴)²).
TEST(FormulaSurface, CurvatureFromTheFormulaMatchesTheClosedForms) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coordinate(-1.5, 1.5);
  const FormulaSurface crate =
      surface(FormulaSurfaceForm::graph, "h*sin(x/w)*cos(y/w)", {{"h", 0.3}, {"w", 0.7}});
  const double a = 2.0, b = 1.5, c = 1.0;
  const FormulaSurface ellipsoid = surface(FormulaSurfaceForm::implicit, "x^2/a^2 + y^2/b^2 + z^2/c^2 - 1",
                                           {{"a", a}, {"b", b}, {"c", c}});
  std::normal_distribution<double> normal;
  for (int i = 0; i < 200; ++i) {
    const double x = coordinate(rng), y = coordinate(rng), h = 0.3, w = 0.7;
    const double fx = h / w * std::cos(x / w) * std::cos(y / w),
                 fy = -h / w * std::sin(x / w) * std::sin(y / w);
    const double fxx = -h / (w * w) * std::sin(x / w) * std::cos(y / w), fyy = fxx;
    const double fxy = -h / (w * w) * std::cos(x / w) * std::sin(y / w);
    const double z = crate.height(x, y);
    EXPECT_NEAR(z, h * std::sin(x / w) * std::cos(y / w), 1e-16);
    const ImplicitPoint p = crate.at(Vec3(x, y, z));
    EXPECT_EQ(p.F, 0.0);
    EXPECT_EQ(p.gradient.z(), 1.0);
    const double q = 1 + fx * fx + fy * fy;
    EXPECT_LT(relative(bordered_hessian_curvature(p), (fxx * fyy - fxy * fxy) / (q * q)), 1e-13);

    const Vec3 d = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    const Vec3 X(a * d.x(), b * d.y(), c * d.z());
    const double s =
        X.x() * X.x() / std::pow(a, 4) + X.y() * X.y() / std::pow(b, 4) + X.z() * X.z() / std::pow(c, 4);
    EXPECT_LT(relative(bordered_hessian_curvature(ellipsoid.at(X)), 1.0 / (a * a * b * b * c * c * s * s)),
              1e-13);
  }
}

TEST(FormulaSurface, AGraphRefusesZAndAnImplicitSurfaceHasNoHeight) {
  const FormulaSurfaceParse parsed = parse_formula_surface(FormulaSurfaceForm::graph, "x + z");
  EXPECT_FALSE(parsed.surface);
  EXPECT_EQ(parsed.error.position, 4u);
  const FormulaSurface sphere = surface(FormulaSurfaceForm::implicit, "x^2 + y^2 + z^2 - 1");
  EXPECT_THROW((void)sphere.height(0, 0), std::logic_error);
}

}  // namespace
}  // namespace spinfold
