// A formula in x, y, z and named parameters, in the language of docs/formula-language.md
// (physics-anysurface.md §9): parsed once into a flat postfix program, then evaluated in double or
// with its exact first and second derivatives by forward-mode differentiation (a second-order jet:
// value, gradient, Hessian). The parser is the safety boundary for text from the network: a
// whitelist of characters and names, caps on length and nesting, and nothing evaluated but
// arithmetic on numbers.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace spinfold {

// The caps of the language: a formula is evaluated at every step of a run, so its size is bounded.
inline constexpr std::size_t kMaxFormulaLength = 4096;  // characters
inline constexpr int kMaxFormulaDepth = 48;             // nested parentheses, calls, signs and powers
inline constexpr std::size_t kMaxFormulaStack = 64;     // values held at once by the program
inline constexpr std::size_t kMaxFormulaParameters = 32;
inline constexpr std::size_t kMaxFormulaNameLength = 32;  // characters of a parameter's name

// Why a formula is refused, and where: `position` is the 0-based offset in the text of the
// character the reason is about (the length of the text for "ends too early").
struct FormulaError {
  std::size_t position = 0;
  std::string reason;
};

// A set where the formula is not smooth (accepted: the body must keep away from it), and where in
// the text the function or operator that has it is.
struct FormulaWarning {
  std::size_t position = 0;
  std::string reason;
};

// F with its gradient ∂F/∂(x, y, z) and Hessian ∂²F/∂(x, y, z)² at a point.
struct FormulaJet {
  double value = 0.0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
};

using FormulaParameters = std::map<std::string, double, std::less<>>;

// The variables a formula may use: x, y, z for F(x, y, z) = 0, x, y for a graph z = f(x, y).
enum class FormulaVariables { xyz, xy };

// One instruction of the compiled program (a stack machine over doubles or jets).
enum class FormulaOp : std::uint8_t {
  constant,
  x,
  y,
  z,  // push
  add,
  sub,
  mul,
  div,
  atan2,  // pop two, push one
  pow,    // a^b for a non-constant exponent: exp(b log a)
  neg,
  power_int,
  power_real,  // pop one, push one (the exponent in the instruction)
  // pop one, push one, with the number c in the instruction: u + c, u − c, c − u, c·u, u/c, c/u
  add_c,
  sub_c,
  rsub_c,
  mul_c,
  div_c,
  rdiv_c,
  sqrt,
  exp,
  log,
  sin,
  cos,
  tan,
  sinh,
  cosh,
  tanh,
  atan,
  asinh,
};
struct FormulaInstruction {
  FormulaOp op = FormulaOp::constant;
  double number = 0.0;  // constant: its value; power_int, power_real: the exponent; add_c …: c
};

class Formula {
 public:
  // F at X = (x, y, z) (a graph's formula ignores z).
  double value(const Eigen::Vector3d& X) const;
  // F, ∇F and Hess F at X: exact to round-off (no finite differences).
  FormulaJet jet(const Eigen::Vector3d& X) const;

  // The text as given.
  const std::string& text() const { return text_; }
  // Where the formula is not smooth; empty for a polynomial.
  const std::vector<FormulaWarning>& warnings() const { return warnings_; }
  // The program; two formulas with the same program are the same function (a cache's key).
  const std::vector<FormulaInstruction>& program() const { return program_; }
  // The program as text, every number exact (%a): an identity for caches.
  std::string identity() const;

 private:
  friend struct FormulaCompiler;
  std::string text_;
  std::vector<FormulaInstruction> program_;
  std::vector<FormulaWarning> warnings_;
};

// The result of parse_formula: the formula, or why not.
struct FormulaParse {
  std::optional<Formula> formula;
  FormulaError error;  // meaningful when formula is empty
};

// Parses `text` with these parameters' values (each name must be a valid parameter name; a
// parameter not used is allowed) into a program. Refuses, naming the position: an unknown name or
// character, a function that is not C² (abs, min, max, floor, …: a surface needs F of class C²),
// a malformed expression, a number out of range, a formula longer or deeper than the caps.
FormulaParse parse_formula(std::string_view text, const FormulaParameters& parameters = {},
                           FormulaVariables variables = FormulaVariables::xyz);

// Why `name` cannot name a parameter (a letter then letters, digits or underscores, at most
// kMaxFormulaNameLength; not x, y, z, pi or a function's name), or nothing when it can.
std::optional<std::string> parameter_name_problem(std::string_view name);

// The functions the language knows, in the order the documentation lists them.
const std::vector<std::string_view>& formula_functions();

}  // namespace spinfold
