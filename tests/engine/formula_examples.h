// Formulas for the tests of the formula language (tests/engine/formula_test.cpp, the oracle's
// tests/oracle/formula_test.cpp): a random one over the whole grammar, and Boost.Odeint's RKF78 as the
// independent integrator the formula-surface tests compare with.
#pragma once

#include <Eigen/Dense>
#include <boost/numeric/odeint.hpp>
#include <random>
#include <string>
#include <vector>

namespace spinfold::test {

// A random formula over the whole grammar (every operator and function, the parameter a, nesting to
// `depth`), each function's argument kept where it is smooth (sqrt(1.5 + cos …), log(2 + sin …)).
inline std::string random_formula(std::mt19937_64& rng, int depth) {
  std::uniform_int_distribution<int> pick(0, depth <= 0 ? 4 : 22);
  std::uniform_real_distribution<double> number(-2.0, 2.0);
  const auto sub = [&] { return random_formula(rng, depth - 1); };
  switch (pick(rng)) {
    case 0: return "x";
    case 1: return "y";
    case 2: return "z";
    case 3: return std::to_string(number(rng));
    case 4: return "a";
    case 5: return "(" + sub() + " + " + sub() + ")";
    case 6: return "(" + sub() + " - " + sub() + ")";
    case 7: return "(" + sub() + " * " + sub() + ")";
    case 8: return "(" + sub() + ") / (2.5 + sin(" + sub() + "))";
    case 9: return "(" + sub() + ")^2";
    case 10: return "(" + sub() + ")**3";
    case 11: return "-(" + sub() + ")";
    case 12: return "sqrt(1.5 + cos(" + sub() + "))";
    case 13: return "exp(sin(" + sub() + "))";
    case 14: return "log(2 + sin(" + sub() + "))";
    case 15: return "sin(" + sub() + ")";
    case 16: return "cos(" + sub() + ")";
    case 17: return "tan(0.4*sin(" + sub() + "))";
    case 18: return "sinh(sin(" + sub() + "))";
    case 19: return "cosh(sin(" + sub() + "))";
    case 20: return "tanh(" + sub() + ")";
    case 21: return "atan(" + sub() + ") + asinh(" + sub() + ")";
    default:
      return "atan2(" + sub() + ", 3 + cos(" + sub() + ")) + (1.5 + sin(" + sub() + "))^(0.5 + 0.1*" + sub() +
             ")";
  }
}

// Y(T) from Y0 by Boost.Odeint's Runge–Kutta–Fehlberg 7(8) at `tolerance` (absolute and relative).
template <int N, class Field>
Eigen::Matrix<double, N, 1> rkf78(const Field& field, const Eigen::Matrix<double, N, 1>& Y0, double T,
                                  double tolerance) {
  using State = std::vector<double>;  // (std::array trips GCC's -Wuninitialized inside Odeint's copies)
  State x(Y0.data(), Y0.data() + N);
  auto rhs = [&](const State& in, State& out, double) {
    Eigen::Matrix<double, N, 1> y, d;
    for (int i = 0; i < N; ++i) y(i) = in[i];
    field(y, d);
    out.assign(d.data(), d.data() + N);
  };
  namespace odeint = boost::numeric::odeint;
  odeint::integrate_adaptive(
      odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_fehlberg78<State>()), rhs, x, 0.0, T,
      1e-3);
  return Eigen::Map<Eigen::Matrix<double, N, 1>>(x.data());
}

}  // namespace spinfold::test
