// The engine's formula reader (engine/formula.h: a postfix program over a second-order jet in double)
// against the oracle's (oracle/formula.h: a tree over hyper-dual numbers in 50 digits), which share no
// code: the same verdict on random token strings, and the same F, ∇F and Hess F on random formulas
// over the whole grammar, within what double rounding allows.
#include "oracle/formula.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "engine/formula.h"
#include "tests/engine/formula_examples.h"

namespace spinfold::oracle {
namespace {

// 30,000 random strings of the language's tokens, right and wrong: both readers accept the same ones.
TEST(OracleFormula, BothReadersAcceptAndRefuseTheSameTexts) {
  const std::vector<std::string> tokens = {"x",    "y",      "z",     "a",    "pi", "2",     "0.5",  "3",
                                           "0",    "1e-400", "1e400", "+",    "-",  "*",     "/",    "^",
                                           "**",   "(",      ")",     ",",    " ",  "sqrt(", "exp(", "log(",
                                           "sin(", "atan2(", "tanh(", "abs(", "q",  "2x",    ".5",   "$"};
  std::mt19937_64 rng(49);
  std::uniform_int_distribution<std::size_t> pick(0, tokens.size() - 1), length(1, 9);
  int accepted = 0, refused = 0;
  for (int trial = 0; trial < 30000; ++trial) {
    std::string text;
    for (std::size_t n = length(rng), i = 0; i < n; ++i) text += tokens[pick(rng)];
    const bool engine = parse_formula(text, {{"a", 1.5}}).formula.has_value();
    std::string why;
    const bool oracle = OracleFormula::read(text, {{"a", 1.5}}, false, &why).has_value();
    EXPECT_EQ(engine, oracle) << "'" << text << "' (oracle: " << (oracle ? "accepted" : why) << ")";
    (engine ? accepted : refused) += 1;
  }
  EXPECT_GT(accepted, 1000);  // the strings reach both verdicts
  EXPECT_GT(refused, 1000);
}

// 300 random formulas at random points: the engine's double jet against the oracle's 50 digits. The
// bound is round-off's: 1e-12 of the formula's own scale (|F| + |∇F| + |Hess F| + 1).
TEST(OracleFormula, TheEnginesJetIsTheOraclesToRoundOff) {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> coordinate(-1.5, 1.5);
  double worst = 0.0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::string text = test::random_formula(rng, 3);
    const FormulaParse engine = parse_formula(text, {{"a", 0.7}});
    std::string why;
    const std::optional<OracleFormula> oracle = OracleFormula::read(text, {{"a", 0.7}}, false, &why);
    ASSERT_TRUE(engine.formula) << text << ": " << engine.error.reason;
    ASSERT_TRUE(oracle) << text << ": " << why;
    const Eigen::Vector3d X(coordinate(rng), coordinate(rng), coordinate(rng));
    const FormulaJet j = engine.formula->jet(X);
    const FormulaValue o = oracle->at({Big(X.x()), Big(X.y()), Big(X.z())});
    double scale = 1.0 + std::abs(j.value) + j.gradient.norm() + j.hessian.norm(), error = 0.0;
    error = std::max(error, std::abs(j.value - o.F.convert_to<double>()));
    for (int i = 0; i < 3; ++i) {
      error = std::max(error, std::abs(j.gradient(i) - o.gradient[i].convert_to<double>()));
      for (int k = 0; k < 3; ++k)
        error = std::max(error, std::abs(j.hessian(i, k) - o.hessian[i][k].convert_to<double>()));
    }
    EXPECT_LT(error / scale, 1e-12) << text << " at " << X.transpose();
    worst = std::max(worst, error / scale);
  }
  std::printf("largest difference, relative to the formula's scale: %.2g\n", worst);
}

// physics-anysurface.md's surfaces (WF1's ellipsoid, WF2's graph, WF3's genus-2) at a point of each.
TEST(OracleFormula, TheWorkedSurfacesAgree) {
  struct Case {
    std::string text;
    std::map<std::string, double> parameters;
    Eigen::Vector3d X;
  };
  const Case cases[] = {
      {"x^2/a^2 + y^2/b^2 + z^2/c^2 - 1", {{"a", 2}, {"b", 1.5}, {"c", 1}}, {1.0571675914981962, 0.88, 0.61}},
      {"z - (0.3*x^2*y - 0.2*y^2 + 0.1*x)", {}, {0.4, -0.3, 0.0076}},
      {"((x^2 + y^2)^2 - 2*a^2*(x^2 - y^2))^2 + (z/c)^2 - r^2",
       {{"a", 1}, {"c", 0.5}, {"r", 0.7}},
       {1.17, 0.26, 0.23}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    FormulaParameters p(c.parameters.begin(), c.parameters.end());
    const FormulaJet j = parse_formula(c.text, p).formula->jet(c.X);
    const FormulaValue o = OracleFormula::read(c.text, c.parameters, false, nullptr)
                               ->at({Big(c.X.x()), Big(c.X.y()), Big(c.X.z())});
    EXPECT_NEAR(j.value, o.F.convert_to<double>(), 1e-15);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(j.gradient(i), o.gradient[i].convert_to<double>(), 1e-14);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(j.hessian(i, k), o.hessian[i][k].convert_to<double>(), 1e-13);
    }
  }
}

}  // namespace
}  // namespace spinfold::oracle
