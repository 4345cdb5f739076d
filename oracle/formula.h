// The oracle's own reader of the formula language (docs/formula-language.md) and its own derivatives
// of a formula: a tree read by recursive descent, numbers taken as the exact decimals written, and
// evaluated in 50-digit arithmetic on hyper-dual numbers (a + b₁ε₁ + b₂ε₂ + b₁₂ε₁ε₂, ε₁² = ε₂² = 0:
// one evaluation seeded on x_i and x_j gives ∂²F/∂x_i∂x_j exactly, six give the Hessian). It shares no
// code with engine/formula.h (a postfix program over a second-order jet in double); the differential
// test, tests/oracle/formula_test.cpp, compares the two readers' verdicts and values.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "oracle/oracle.h"

namespace spinfold::oracle {

// F, ∇F and Hess F at a point, in 50 digits.
struct FormulaValue {
  Big F = 0;
  std::array<Big, 3> gradient{};
  std::array<std::array<Big, 3>, 3> hessian{};
};

class OracleFormula {
 public:
  struct Node;
  // Reads `text` with these parameters (x, y, z; `graph`: x, y only). Empty, with the reason in
  // `why`, where the language refuses it.
  static std::optional<OracleFormula> read(std::string_view text,
                                           const std::map<std::string, double>& parameters, bool graph,
                                           std::string* why);
  // F and its first and second derivatives at X.
  FormulaValue at(const std::array<Big, 3>& X) const;

 private:
  std::shared_ptr<const Node> root_;
};

}  // namespace spinfold::oracle
