// The formula language (engine/formula.h): its grammar and precedence, every refusal with its
// position (physics-anysurface.md §11 WF4), the caps, and the jet's derivatives: each function's
// against a table of calculus written here, and random formulas over the whole grammar against
// central differences of the double evaluation.
#include "engine/formula.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <string>

#include "tests/engine/formula_examples.h"

namespace spinfold {
namespace {

double eval(std::string_view text, const Eigen::Vector3d& X = Eigen::Vector3d(0.3, -0.7, 1.1),
            const FormulaParameters& p = {}) {
  const FormulaParse parsed = parse_formula(text, p);
  EXPECT_TRUE(parsed.formula) << text << ": " << parsed.error.reason;
  return parsed.formula ? parsed.formula->value(X) : std::nan("");
}

FormulaError refusal(std::string_view text, const FormulaParameters& p = {},
                     FormulaVariables v = FormulaVariables::xyz) {
  const FormulaParse parsed = parse_formula(text, p, v);
  EXPECT_FALSE(parsed.formula) << text << " was accepted";
  return parsed.error;
}

TEST(Formula, PrecedenceAndAssociativityAreTheUsualOnes) {
  EXPECT_EQ(eval("-2^2"), -4.0);  // −(2²)
  EXPECT_EQ(eval("2^3^2"), 512.0);
  EXPECT_EQ(eval("2**3**2"), 512.0);
  EXPECT_EQ(eval("1 - 2 - 3"), -4.0);
  EXPECT_EQ(eval("8 / 4 / 2"), 1.0);
  EXPECT_EQ(eval("2 * 3 + 4 * 5"), 26.0);
  EXPECT_EQ(eval("2^-1"), 0.5);
  EXPECT_EQ(eval("--3"), 3.0);
  EXPECT_EQ(eval("+3"), 3.0);
  EXPECT_EQ(eval(".5 + 1e-3 + 1.5E+2 + 2e2"), 0.5 + 1e-3 + 150.0 + 200.0);
  EXPECT_DOUBLE_EQ(eval("pi"), std::numbers::pi);
  const Eigen::Vector3d X(0.3, -0.7, 1.1);
  EXPECT_DOUBLE_EQ(eval("x^2 + y*z - x/y", X), 0.09 - 0.77 - 0.3 / -0.7);
  EXPECT_DOUBLE_EQ(eval("atan2(y, x) + sqrt(z) * exp(-x^2)", X),
                   std::atan2(-0.7, 0.3) + std::sqrt(1.1) * std::exp(-0.09));
  EXPECT_DOUBLE_EQ(eval("a*x^2 + b", X, {{"a", 2.0}, {"b", 1.3}}), 2.0 * 0.09 + 1.3);
}

// WF4: what is refused and what is accepted with a warning.
TEST(Formula, WorkedRefusalsWF4) {
  FormulaError e = refusal("abs(x) + y^2 + z^2 - 1");
  EXPECT_EQ(e.position, 0u);
  EXPECT_NE(e.reason.find("abs is not smooth"), std::string::npos) << e.reason;
  e = refusal("max(x, y) - z");
  EXPECT_NE(e.reason.find("max is not smooth"), std::string::npos) << e.reason;
  e = refusal("__import__('os')");
  EXPECT_EQ(e.position, 0u);
  EXPECT_NE(e.reason.find("unknown name '__import__'"), std::string::npos) << e.reason;
  const FormulaParse cone = parse_formula("sqrt(x^2 + y^2) - z");
  ASSERT_TRUE(cone.formula);
  ASSERT_EQ(cone.formula->warnings().size(), 1u);
  EXPECT_EQ(cone.formula->warnings()[0].position, 0u);
  EXPECT_NE(cone.formula->warnings()[0].reason.find("sqrt(u)"), std::string::npos);
  const FormulaParse saddle = parse_formula("x^2 + y^2 - z^2");
  ASSERT_TRUE(saddle.formula);
  EXPECT_TRUE(saddle.formula->warnings().empty());
}

// Every refusal names the position of the character it is about.
TEST(Formula, RefusalsNameThePosition) {
  struct Case {
    std::string_view text;
    std::size_t position;
    std::string_view words;
  };
  const Case cases[] = {
      {"x + * y", 4, "expected a number"},
      {"2x", 1, "an operator is missing before 'x'"},
      {"x (y)", 2, "an operator is missing"},
      {"sin x", 4, "sin needs its argument in parentheses"},
      {"(x + y", 6, "expected ')'"},
      {"x + y)", 5, "a ')' with no '('"},
      {"foo(x)", 0, "unknown name 'foo' (the functions: sqrt"},
      {"x + q", 4, "unknown name 'q'"},
      {"1e999 * x", 0, "out of the range"},
      {"x / 0", 2, "division by zero"},
      {"x / (1 - 1)", 2, "division by zero"},
      {"sqrt(-1) + x", 0, "not a finite number"},
      {"log(0) + x", 0, "not a finite number"},
      {"x $ y", 2, "a character the language does not use: '$'"},
      {"x + \xc3\xa9", 4, "byte 0xc3"},
      {"atan2(x) + 1", 7, "two arguments"},
      {"sin(x, y)", 5, "takes one argument"},
      {"x +", 3, "the formula ends"},
      {"", 0, "the formula ends"},
      {"floor(x) - z", 0, "floor is not smooth"},
      {"x; y", 1, "a character the language does not use"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.text));
    const FormulaError e = refusal(c.text);
    EXPECT_EQ(e.position, c.position) << e.reason;
    EXPECT_NE(e.reason.find(c.words), std::string::npos) << e.reason;
  }
}

TEST(Formula, AGraphUsesXAndYOnly) {
  const FormulaError e = refusal("x^2 + z", {}, FormulaVariables::xy);
  EXPECT_EQ(e.position, 6u);
  EXPECT_NE(e.reason.find("z is not a variable of a graph"), std::string::npos);
  EXPECT_TRUE(parse_formula("x^2 - y^2", {}, FormulaVariables::xy).formula);
}

TEST(Formula, ParametersAreNamedValues) {
  EXPECT_NE(refusal("a * x", {{"b", 1.0}})
                .reason.find("unknown name 'a' (the variables and parameters: x, y, z, b"),
            std::string::npos);
  EXPECT_NE(refusal("x", {{"sin", 1.0}}).reason.find("function"), std::string::npos);
  EXPECT_NE(refusal("x", {{"z", 1.0}}).reason.find("variables"), std::string::npos);
  EXPECT_NE(refusal("x", {{"1a", 1.0}}).reason.find("starts with a letter"), std::string::npos);
  EXPECT_NE(refusal("x", {{"a", std::nan("")}}).reason.find("not a finite number"), std::string::npos);
  EXPECT_FALSE(parameter_name_problem("tube_radius2"));
  EXPECT_TRUE(parameter_name_problem(std::string(kMaxFormulaNameLength + 1, 'a')));
  // A parameter's value is folded into the program: the same program as the number written out.
  EXPECT_EQ(parse_formula("a*x", {{"a", 2.5}}).formula->identity(),
            parse_formula("2.5*x").formula->identity());
  EXPECT_NE(parse_formula("a*x", {{"a", 2.5}}).formula->identity(),
            parse_formula("a*x", {{"a", 2.6}}).formula->identity());
}

TEST(Formula, TheCapsBoundTheTextTheNestingAndTheStack) {
  std::string long_text = "x";
  while (long_text.size() <= kMaxFormulaLength) long_text += " + x";
  EXPECT_EQ(refusal(long_text).position, kMaxFormulaLength);
  // A long flat sum is fine: its stack holds two values.
  std::string sum = "x";
  for (int i = 0; i < 800; ++i) sum += "+y";
  EXPECT_TRUE(parse_formula(sum).formula);
  const std::string deep =
      std::string(kMaxFormulaDepth + 1, '(') + "x" + std::string(kMaxFormulaDepth + 1, ')');
  EXPECT_NE(refusal(deep).reason.find("nests deeper"), std::string::npos);
  EXPECT_TRUE(
      parse_formula(std::string(kMaxFormulaDepth - 1, '(') + "x" + std::string(kMaxFormulaDepth - 1, ')'))
          .formula);
  EXPECT_NE(refusal(std::string(200, '-') + "x").reason.find("nests deeper"), std::string::npos);
  // Held values: x + x*(x + x*(…)) keeps two values a level, so 40 levels fit the depth, not the stack.
  std::string stacked = "x", held = "x";
  for (int i = 0; i < 40; ++i) stacked = "x+x*(" + stacked + ")";
  for (int i = 0; i < 30; ++i) held = "x+x*(" + held + ")";
  EXPECT_NE(refusal(stacked).reason.find("more than 64 values"), std::string::npos);
  EXPECT_TRUE(parse_formula(held).formula);
}

// Each function's jet against its derivatives from a table of calculus: f(u) with u a quadratic in
// x, y, z, so that the chain rule is exercised (∇f = f′∇u, Hess f = f′ Hess u + f″ ∇u∇uᵀ).
TEST(Formula, EachFunctionsJetIsExact) {
  struct Row {
    std::string_view name;
    std::function<double(double)> f, f1, f2;
  };
  const Row rows[] = {
      {"sqrt", [](double u) { return std::sqrt(u); }, [](double u) { return 0.5 / std::sqrt(u); },
       [](double u) { return -0.25 * std::pow(u, -1.5); }},
      {"exp", [](double u) { return std::exp(u); }, [](double u) { return std::exp(u); },
       [](double u) { return std::exp(u); }},
      {"log", [](double u) { return std::log(u); }, [](double u) { return 1 / u; },
       [](double u) { return -1 / (u * u); }},
      {"sin", [](double u) { return std::sin(u); }, [](double u) { return std::cos(u); },
       [](double u) { return -std::sin(u); }},
      {"cos", [](double u) { return std::cos(u); }, [](double u) { return -std::sin(u); },
       [](double u) { return -std::cos(u); }},
      {"tan", [](double u) { return std::tan(u); }, [](double u) { return 1 / std::pow(std::cos(u), 2); },
       [](double u) { return 2 * std::sin(u) / std::pow(std::cos(u), 3); }},
      {"sinh", [](double u) { return std::sinh(u); }, [](double u) { return std::cosh(u); },
       [](double u) { return std::sinh(u); }},
      {"cosh", [](double u) { return std::cosh(u); }, [](double u) { return std::sinh(u); },
       [](double u) { return std::cosh(u); }},
      {"tanh", [](double u) { return std::tanh(u); }, [](double u) { return 1 / std::pow(std::cosh(u), 2); },
       [](double u) { return -2 * std::sinh(u) / std::pow(std::cosh(u), 3); }},
      {"atan", [](double u) { return std::atan(u); }, [](double u) { return 1 / (1 + u * u); },
       [](double u) { return -2 * u / std::pow(1 + u * u, 2); }},
      {"asinh", [](double u) { return std::asinh(u); }, [](double u) { return 1 / std::hypot(1.0, u); },
       [](double u) { return -u / std::pow(1 + u * u, 1.5); }},
      {"power 3", [](double u) { return u * u * u; }, [](double u) { return 3 * u * u; },
       [](double u) { return 6 * u; }},
      {"power -2", [](double u) { return 1 / (u * u); }, [](double u) { return -2 / (u * u * u); },
       [](double u) { return 6 / (u * u * u * u); }},
      {"power 2.5", [](double u) { return std::pow(u, 2.5); },
       [](double u) { return 2.5 * std::pow(u, 1.5); }, [](double u) { return 3.75 * std::sqrt(u); }},
  };
  const std::string u = "(0.6 + 0.3*x + 0.2*y^2 - 0.1*x*z)";
  const Eigen::Vector3d X(0.4, -0.9, 0.7);
  const double uv = 0.6 + 0.3 * X.x() + 0.2 * X.y() * X.y() - 0.1 * X.x() * X.z();
  const Eigen::Vector3d ug(0.3 - 0.1 * X.z(), 0.4 * X.y(), -0.1 * X.x());
  Eigen::Matrix3d uh;
  uh << 0, 0, -0.1, 0, 0.4, 0, -0.1, 0, 0;
  for (const Row& r : rows) {
    SCOPED_TRACE(std::string(r.name));
    std::string text;
    if (r.name.starts_with("power"))
      text = u + "^(" + std::string(r.name.substr(6)) + ")";
    else
      text = std::string(r.name) + u;
    const FormulaParse parsed = parse_formula(text);
    ASSERT_TRUE(parsed.formula) << parsed.error.reason;
    const FormulaJet j = parsed.formula->jet(X);
    const double f1 = r.f1(uv), f2 = r.f2(uv);
    EXPECT_NEAR(j.value, r.f(uv), 1e-15 * std::abs(r.f(uv)));
    EXPECT_EQ(j.value, parsed.formula->value(X));
    const Eigen::Vector3d g = f1 * ug;
    const Eigen::Matrix3d h = f1 * uh + f2 * ug * ug.transpose();
    EXPECT_LT((j.gradient - g).norm(), 1e-14 * (1 + g.norm()));
    EXPECT_LT((j.hessian - h).norm(), 1e-14 * (1 + h.norm()));
  }
  // atan2(a, b) and a variable power a^b, two arguments each.
  const FormulaJet t = parse_formula("atan2(x*y, z + 2)").formula->jet(X);
  const double a = X.x() * X.y(), b = X.z() + 2, r2 = a * a + b * b;
  const Eigen::Vector3d ga(X.y(), X.x(), 0), gb(0, 0, 1);
  EXPECT_LT((t.gradient - (b / r2 * ga - a / r2 * gb)).norm(), 1e-15);
  const FormulaJet p = parse_formula("(x + 2)^y").formula->jet(X);
  const double base = X.x() + 2, e = X.y();
  const Eigen::Vector3d gp(e * std::pow(base, e - 1), std::pow(base, e) * std::log(base), 0);
  EXPECT_LT((p.gradient - gp).norm(), 1e-14);
  EXPECT_NEAR(p.hessian(0, 1), std::pow(base, e - 1) * (1 + e * std::log(base)), 1e-14);
}

// 300 random formulas: the jet's value is the double evaluation's, its gradient and Hessian agree
// with central differences of the value and of the gradient (step 1e-5: error ~1e-9 relative).
TEST(Formula, RandomFormulasJetsAgreeWithDifferences) {
  std::mt19937_64 rng(20261202);
  std::uniform_real_distribution<double> coordinate(-1.5, 1.5);
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::string text = test::random_formula(rng, 4);
    const FormulaParse parsed = parse_formula(text, {{"a", 0.7}});
    ASSERT_TRUE(parsed.formula) << text << ": " << parsed.error.reason;
    const Formula& f = *parsed.formula;
    const Eigen::Vector3d X(coordinate(rng), coordinate(rng), coordinate(rng));
    const FormulaJet j = f.jet(X);
    if (!std::isfinite(j.value) || !j.gradient.allFinite() || !j.hessian.allFinite()) continue;
    SCOPED_TRACE(text);
    EXPECT_EQ(j.value, f.value(X));
    const double h = 1e-5;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d d = h * Eigen::Vector3d::Unit(i);
      const double derivative = (f.value(X + d) - f.value(X - d)) / (2 * h);
      const double scale = 1 + std::abs(j.value) + j.gradient.norm() + j.hessian.norm();
      EXPECT_NEAR(j.gradient(i), derivative, 1e-6 * scale) << "∂/∂x" << i;
      const Eigen::Vector3d column = (f.jet(X + d).gradient - f.jet(X - d).gradient) / (2 * h);
      EXPECT_LT((j.hessian.col(i) - column).norm(), 1e-5 * scale) << "Hessian column " << i;
    }
    EXPECT_LT((j.hessian - j.hessian.transpose()).norm(), 1e-12 * (1 + j.hessian.norm()));
    ++checked;
  }
  EXPECT_GT(checked, 250);
}

TEST(Formula, FunctionsAreListedInTheDocumentedOrder) {
  const std::vector<std::string_view> want = {"sqrt", "exp",  "log",  "sin",  "cos",   "tan",
                                              "sinh", "cosh", "tanh", "atan", "asinh", "atan2"};
  EXPECT_EQ(formula_functions(), want);
}

}  // namespace
}  // namespace spinfold
