#include "engine/formula.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace spinfold {

namespace {

// ---- The names of the language (docs/formula-language.md).

struct FunctionName {
  std::string_view name;
  FormulaOp op;
  int arguments;
  std::string_view singular;  // the warning where the function is not smooth, or empty
};
constexpr std::array kFunctions = {
    FunctionName{"sqrt", FormulaOp::sqrt, 1,
                 "sqrt(u) is not differentiable where u = 0 and undefined where u < 0"},
    FunctionName{"exp", FormulaOp::exp, 1, ""},
    FunctionName{"log", FormulaOp::log, 1, "log(u) is undefined where u <= 0"},
    FunctionName{"sin", FormulaOp::sin, 1, ""},
    FunctionName{"cos", FormulaOp::cos, 1, ""},
    FunctionName{"tan", FormulaOp::tan, 1, "tan(u) is singular where u is an odd multiple of pi/2"},
    FunctionName{"sinh", FormulaOp::sinh, 1, ""},
    FunctionName{"cosh", FormulaOp::cosh, 1, ""},
    FunctionName{"tanh", FormulaOp::tanh, 1, ""},
    FunctionName{"atan", FormulaOp::atan, 1, ""},
    FunctionName{"asinh", FormulaOp::asinh, 1, ""},
    FunctionName{"atan2", FormulaOp::atan2, 2, "atan2(a, b) jumps where a = 0 and b < 0"},
};

// Functions a user may try that are not C² anywhere they bend: refused by name, with the reason.
constexpr std::array<std::string_view, 22> kNotSmooth = {
    "abs", "min",  "max",       "sign", "sgn",       "floor", "ceil", "round", "trunc", "mod",   "fmod",
    "rem", "frac", "heaviside", "step", "piecewise", "if",    "re",   "im",    "int",   "clamp", "fabs"};

const FunctionName* find_function(std::string_view name) {
  for (const FunctionName& f : kFunctions)
    if (f.name == name) return &f;
  return nullptr;
}

bool not_smooth(std::string_view name) {
  return std::find(kNotSmooth.begin(), kNotSmooth.end(), name) != kNotSmooth.end();
}

std::string function_list() {
  std::string list;
  for (const FunctionName& f : kFunctions) list += (list.empty() ? "" : ", ") + std::string(f.name);
  return list;
}

// ---- Tokens.

enum class Token { number, name, plus, minus, times, divide, power, open, close, comma, end };

struct Lexeme {
  Token token = Token::end;
  std::size_t position = 0;
  std::string_view text;
  double number = 0.0;
};

bool letter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool digit(char c) {
  return c >= '0' && c <= '9';
}

struct Refusal {
  FormulaError error;
};

[[noreturn]] void refuse(std::size_t position, std::string reason) {
  throw Refusal{{position, std::move(reason)}};
}

std::string shown(std::string_view text) {
  std::string quoted;
  quoted.reserve(text.size() + 2);
  quoted.push_back('\'');
  quoted.append(text);
  quoted.push_back('\'');
  return quoted;
}

class Lexer {
 public:
  explicit Lexer(std::string_view text) : text_(text) {}

  Lexeme next() {
    while (at_ < text_.size() &&
           (text_[at_] == ' ' || text_[at_] == '\t' || text_[at_] == '\n' || text_[at_] == '\r'))
      ++at_;
    Lexeme l;
    l.position = at_;
    if (at_ == text_.size()) return l;
    const char c = text_[at_];
    if (digit(c) || (c == '.' && at_ + 1 < text_.size() && digit(text_[at_ + 1]))) return number(l);
    if (letter(c)) {
      std::size_t end = at_;
      while (end < text_.size() && (letter(text_[end]) || digit(text_[end]))) ++end;
      l.token = Token::name;
      l.text = text_.substr(at_, end - at_);
      at_ = end;
      return l;
    }
    ++at_;
    l.text = text_.substr(l.position, 1);
    switch (c) {
      case '+': l.token = Token::plus; return l;
      case '-': l.token = Token::minus; return l;
      case '/': l.token = Token::divide; return l;
      case '^': l.token = Token::power; return l;
      case '(': l.token = Token::open; return l;
      case ')': l.token = Token::close; return l;
      case ',': l.token = Token::comma; return l;
      case '*':
        if (at_ < text_.size() && text_[at_] == '*') {
          ++at_;
          l.token = Token::power;
          l.text = text_.substr(l.position, 2);
        } else {
          l.token = Token::times;
        }
        return l;
      default: break;
    }
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 || u >= 0x7f) {
      char code[8];
      std::snprintf(code, sizeof code, "0x%02x", u);
      refuse(l.position, std::string("a character the language does not use (byte ") + code + ")");
    }
    refuse(l.position,
           "a character the language does not use: " + shown(l.text) +
               " (numbers, x, y, z, parameters, + - * / ^ **, parentheses, commas and functions)");
  }

 private:
  // A decimal number: digits, an optional fraction, an optional exponent (1, 1.5, .5, 2e-3, 1.5E+2).
  Lexeme number(Lexeme l) {
    std::size_t end = at_;
    while (end < text_.size() && digit(text_[end])) ++end;
    if (end < text_.size() && text_[end] == '.') {
      ++end;
      while (end < text_.size() && digit(text_[end])) ++end;
    }
    if (end < text_.size() && (text_[end] == 'e' || text_[end] == 'E')) {
      std::size_t exponent = end + 1;
      if (exponent < text_.size() && (text_[exponent] == '+' || text_[exponent] == '-')) ++exponent;
      if (exponent < text_.size() && digit(text_[exponent])) {
        end = exponent;
        while (end < text_.size() && digit(text_[end])) ++end;
      }
    }
    l.token = Token::number;
    l.text = text_.substr(at_, end - at_);
    const auto [ptr, ec] = std::from_chars(text_.data() + at_, text_.data() + end, l.number);
    if (ec != std::errc() || ptr != text_.data() + end || !std::isfinite(l.number))
      refuse(l.position, "the number " + shown(l.text) + " is out of the range of double precision");
    at_ = end;
    return l;
  }

  std::string_view text_;
  std::size_t at_ = 0;
};

// ---- Scalar functions shared by the double and the jet evaluation (so that value() and jet().value
// are the same number).

double integer_power(double a, double n) {
  // |n| ≤ 64: repeated squaring (exact for small n, as x*x is); beyond, the library's pow.
  if (std::abs(n) > 64) return std::pow(a, n);
  long k = static_cast<long>(std::abs(n));
  double result = 1.0, base = a;
  while (k) {
    if (k & 1) result *= base;
    base *= base;
    k >>= 1;
  }
  return n < 0 ? 1.0 / result : result;
}

double apply_unary(FormulaOp op, double a, double number) {
  switch (op) {
    case FormulaOp::neg: return -a;
    case FormulaOp::add_c: return a + number;
    case FormulaOp::sub_c: return a - number;
    case FormulaOp::rsub_c: return number - a;
    case FormulaOp::mul_c: return number * a;
    case FormulaOp::div_c: return a / number;
    case FormulaOp::rdiv_c: return number / a;
    case FormulaOp::power_int: return integer_power(a, number);
    case FormulaOp::power_real: return std::pow(a, number);
    case FormulaOp::sqrt: return std::sqrt(a);
    case FormulaOp::exp: return std::exp(a);
    case FormulaOp::log: return std::log(a);
    case FormulaOp::sin: return std::sin(a);
    case FormulaOp::cos: return std::cos(a);
    case FormulaOp::tan: return std::tan(a);
    case FormulaOp::sinh: return std::sinh(a);
    case FormulaOp::cosh: return std::cosh(a);
    case FormulaOp::tanh: return std::tanh(a);
    case FormulaOp::atan: return std::atan(a);
    case FormulaOp::asinh: return std::asinh(a);
    default: return std::nan("");
  }
}

double apply_binary(FormulaOp op, double a, double b) {
  switch (op) {
    case FormulaOp::add: return a + b;
    case FormulaOp::sub: return a - b;
    case FormulaOp::mul: return a * b;
    case FormulaOp::div: return a / b;
    case FormulaOp::atan2: return std::atan2(a, b);
    case FormulaOp::pow: return std::pow(a, b);
    default: return std::nan("");
  }
}

bool unary(FormulaOp op) {
  return op >= FormulaOp::neg;
}
bool binary(FormulaOp op) {
  return op >= FormulaOp::add && op <= FormulaOp::pow;
}

// ---- The second-order jet: a value with its gradient and Hessian in (x, y, z).

// No initialisers: the evaluation's stack of 64 is not cleared at every call (each entry is written
// when pushed).
struct Jet {
  double v;
  Eigen::Vector3d g;
  Eigen::Matrix3d h;
};

// f(a) by the chain rule: ∇f = f′∇a, Hess f = f′ Hess a + f″ ∇a∇aᵀ.
void chain(Jet& a, double f0, double f1, double f2) {
  a.h = f1 * a.h + f2 * (a.g * a.g.transpose());
  a.g *= f1;
  a.v = f0;
}

void unary_jet(FormulaOp op, Jet& a, double number) {
  const double x = a.v;
  const double f0 = apply_unary(op, x, number);
  switch (op) {
    case FormulaOp::neg: chain(a, f0, -1.0, 0.0); return;
    case FormulaOp::add_c:
    case FormulaOp::sub_c: a.v = f0; return;
    case FormulaOp::rsub_c: chain(a, f0, -1.0, 0.0); return;
    case FormulaOp::mul_c: a.v = f0, a.g *= number, a.h *= number; return;
    case FormulaOp::div_c: a.v = f0, a.g /= number, a.h /= number; return;
    case FormulaOp::rdiv_c: return chain(a, f0, -f0 / x, 2.0 * f0 / (x * x));  // c/u: −c/u², 2c/u³
    case FormulaOp::power_int: {
      const double n = number;
      if (n == 0.0) return chain(a, f0, 0.0, 0.0);
      if (n == 1.0) return chain(a, f0, 1.0, 0.0);
      const double f1 = n * integer_power(x, n - 1);
      return chain(a, f0, f1, n == 2.0 ? 2.0 : n * (n - 1) * integer_power(x, n - 2));
    }
    case FormulaOp::power_real: {
      const double p = number;
      return chain(a, f0, p * std::pow(x, p - 1), p * (p - 1) * std::pow(x, p - 2));
    }
    case FormulaOp::sqrt: return chain(a, f0, 0.5 / f0, -0.25 / (f0 * x));
    case FormulaOp::exp: return chain(a, f0, f0, f0);
    case FormulaOp::log: return chain(a, f0, 1.0 / x, -1.0 / (x * x));
    case FormulaOp::sin: return chain(a, f0, std::cos(x), -f0);
    case FormulaOp::cos: return chain(a, f0, -std::sin(x), -f0);
    case FormulaOp::tan: return chain(a, f0, 1.0 + f0 * f0, 2.0 * f0 * (1.0 + f0 * f0));
    case FormulaOp::sinh: return chain(a, f0, std::cosh(x), f0);
    case FormulaOp::cosh: return chain(a, f0, std::sinh(x), f0);
    case FormulaOp::tanh: return chain(a, f0, 1.0 - f0 * f0, -2.0 * f0 * (1.0 - f0 * f0));
    case FormulaOp::atan: {
      const double q = 1.0 / (1.0 + x * x);
      return chain(a, f0, q, -2.0 * x * q * q);
    }
    case FormulaOp::asinh: {
      const double q = 1.0 / std::sqrt(1.0 + x * x);
      return chain(a, f0, q, -x * q * q * q);
    }
    default: return chain(a, std::nan(""), 0.0, 0.0);
  }
}

// a ← a ∘ b for the binary operations.
void binary_jet(FormulaOp op, Jet& a, const Jet& b) {
  switch (op) {
    case FormulaOp::add: a.v += b.v, a.g += b.g, a.h += b.h; return;
    case FormulaOp::sub: a.v -= b.v, a.g -= b.g, a.h -= b.h; return;
    case FormulaOp::mul: {
      // Hess(ab) = a Hess b + b Hess a + ∇a∇bᵀ + ∇b∇aᵀ.
      const Eigen::Matrix3d cross = a.g * b.g.transpose();
      a.h = a.v * b.h + b.v * a.h + cross + cross.transpose();
      a.g = a.v * b.g + b.v * a.g;
      a.v *= b.v;
      return;
    }
    case FormulaOp::div: {
      // r = a/b from r b = a: ∇r = (∇a − r∇b)/b, Hess r = (Hess a − r Hess b − ∇r∇bᵀ − ∇b∇rᵀ)/b.
      const double r = a.v / b.v;
      const Eigen::Vector3d g = (a.g - r * b.g) / b.v;
      const Eigen::Matrix3d cross = g * b.g.transpose();
      a.h = (a.h - r * b.h - cross - cross.transpose()) / b.v;
      a.g = g;
      a.v = r;
      return;
    }
    case FormulaOp::atan2: {
      // θ = atan2(a, b): θ_a = b/ρ², θ_b = −a/ρ², θ_aa = −2ab/ρ⁴, θ_bb = 2ab/ρ⁴, θ_ab = (a² − b²)/ρ⁴.
      const double p = a.v, q = b.v, r2 = p * p + q * q, r4 = r2 * r2;
      const double fa = q / r2, fb = -p / r2, faa = -2 * p * q / r4, fbb = 2 * p * q / r4,
                   fab = (p * p - q * q) / r4;
      const Eigen::Matrix3d cross = a.g * b.g.transpose();
      a.h = fa * a.h + fb * b.h + faa * (a.g * a.g.transpose()) + fbb * (b.g * b.g.transpose()) +
            fab * (cross + cross.transpose());
      a.g = fa * a.g + fb * b.g;
      a.v = std::atan2(p, q);
      return;
    }
    case FormulaOp::pow: {
      // a^b = exp(b log a), its value the library's pow.
      const double value = std::pow(a.v, b.v);
      unary_jet(FormulaOp::log, a, 0.0);
      binary_jet(FormulaOp::mul, a, b);
      unary_jet(FormulaOp::exp, a, 0.0);
      a.v = value;
      return;
    }
    default: a.v = std::nan(""); return;
  }
}

}  // namespace

// ---- The parser: recursive descent over the grammar of docs/formula-language.md, emitting the
// postfix program as it goes; a sub-expression that is a number is folded into one constant.
//   formula := sum END
//   sum     := product (("+" | "-") product)*
//   product := signed (("*" | "/") signed)*
//   signed  := ("-" | "+") signed | power
//   power   := primary (("^" | "**") signed)?          (right-associative: 2^3^2 = 2^9)
//   primary := NUMBER | NAME | NAME "(" sum ("," sum)* ")" | "(" sum ")"
struct FormulaCompiler {
  FormulaCompiler(std::string_view text, const FormulaParameters& given, FormulaVariables allowed)
      : lexer(text), parameters(given), variables(allowed) {
    advance();
  }

  Lexer lexer;
  const FormulaParameters& parameters;
  FormulaVariables variables;
  Lexeme current;
  int depth = 0;
  Formula formula;

  void advance() { current = lexer.next(); }

  // The formula, once its text is read: its program's stack at its highest is bounded, so that
  // evaluation needs no allocation.
  Formula finish(std::string_view text) {
    std::size_t height = 0, highest = 0;
    for (const FormulaInstruction& i : program()) {
      if (!unary(i.op)) height = binary(i.op) ? height - 1 : height + 1;
      highest = std::max(highest, height);
    }
    if (highest > kMaxFormulaStack)
      refuse(0, "the formula holds more than " + std::to_string(kMaxFormulaStack) +
                    " values at once: write it with fewer nested sums");
    formula.text_ = std::string(text);
    return std::move(formula);
  }

  std::vector<FormulaInstruction>& program() { return formula.program_; }
  void emit(FormulaOp op, double number = 0.0) { program().push_back({op, number}); }
  void warn(std::size_t position, std::string_view reason) {
    for (const FormulaWarning& w : formula.warnings_)
      if (w.reason == reason) return;  // once per kind: the first place it occurs
    formula.warnings_.push_back({position, std::string(reason)});
  }

  // Whether the program from `start` on is one constant.
  bool constant_from(std::size_t start) {
    return program().size() == start + 1 && program()[start].op == FormulaOp::constant;
  }

  struct Deeper {
    explicit Deeper(FormulaCompiler& compiler) : c(compiler) {
      if (++c.depth > kMaxFormulaDepth)
        refuse(c.current.position,
               "the formula nests deeper than " + std::to_string(kMaxFormulaDepth) + " levels");
    }
    ~Deeper() { --c.depth; }
    FormulaCompiler& c;
  };

  std::string describe(const Lexeme& l) {
    return l.token == Token::end ? "the end of the formula" : shown(l.text);
  }

  // After an operand: another operand straight after it is a missing operator (2x, x(y)).
  void expect_operand_end() {
    if (current.token == Token::number || current.token == Token::name || current.token == Token::open)
      refuse(current.position,
             "an operator is missing before " + describe(current) + " (write 2*x for a product)");
  }

  // Folds a unary operation on a constant, refusing a result that is not a number.
  void unary_op(FormulaOp op, std::size_t start, std::size_t position, std::string_view name,
                double number = 0.0) {
    if (constant_from(start)) {
      double& c = program()[start].number;
      const double value = apply_unary(op, c, number);
      if (!std::isfinite(value))
        refuse(position, std::string(name) + " of the number " + format(c) + " is not a finite number");
      c = value;
      return;
    }
    emit(op, number);
  }

  void binary_op(FormulaOp op, std::size_t left, std::size_t right, std::size_t position,
                 std::string_view name) {
    const bool left_constant = right == left + 1 && program()[left].op == FormulaOp::constant;
    if (constant_from(right) && left_constant) {
      const double a = program()[left].number, b = program()[right].number;
      const double value = apply_binary(op, a, b);
      if (!std::isfinite(value))
        refuse(position, std::string(name) + " of the numbers " + format(a) + " and " + format(b) +
                             " is not a finite number");
      program().pop_back();
      program().back().number = value;
      return;
    }
    // One operand a number: an instruction that holds it (no jet of zeros pushed and combined).
    const auto immediate = [](FormulaOp o, bool number_on_left) -> std::optional<FormulaOp> {
      switch (o) {
        case FormulaOp::add: return FormulaOp::add_c;
        case FormulaOp::sub: return number_on_left ? FormulaOp::rsub_c : FormulaOp::sub_c;
        case FormulaOp::mul: return FormulaOp::mul_c;
        case FormulaOp::div: return number_on_left ? FormulaOp::rdiv_c : FormulaOp::div_c;
        default: return std::nullopt;
      }
    };
    if (constant_from(right)) {
      if (const auto o = immediate(op, false)) {
        const double c = program()[right].number;
        program().pop_back();
        emit(*o, c);
        return;
      }
    } else if (left_constant) {
      if (const auto o = immediate(op, true)) {
        const double c = program()[left].number;
        program().erase(program().begin() + static_cast<std::ptrdiff_t>(left));
        emit(*o, c);
        return;
      }
    }
    emit(op);
  }

  static std::string format(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", v);
    return text;
  }

  std::size_t sum() {
    const std::size_t start = program().size();
    product();
    while (current.token == Token::plus || current.token == Token::minus) {
      const Lexeme op = current;
      advance();
      const std::size_t right = program().size();
      product();
      binary_op(op.token == Token::plus ? FormulaOp::add : FormulaOp::sub, start, right, op.position,
                op.token == Token::plus ? "the sum" : "the difference");
    }
    return start;
  }

  std::size_t product() {
    const std::size_t start = program().size();
    signed_();
    while (current.token == Token::times || current.token == Token::divide) {
      const Lexeme op = current;
      advance();
      const std::size_t right = program().size();
      signed_();
      if (op.token == Token::divide) {
        if (constant_from(right) && program()[right].number == 0.0) refuse(op.position, "a division by zero");
        if (!constant_from(right)) warn(op.position, "a quotient is singular where its denominator is 0");
      }
      binary_op(op.token == Token::times ? FormulaOp::mul : FormulaOp::div, start, right, op.position,
                op.token == Token::times ? "the product" : "the quotient");
    }
    return start;
  }

  std::size_t signed_() {
    const std::size_t start = program().size();
    if (current.token == Token::minus || current.token == Token::plus) {
      const Lexeme op = current;
      Deeper deeper(*this);
      advance();
      signed_();
      if (op.token == Token::minus) unary_op(FormulaOp::neg, start, op.position, "the negative");
      return start;
    }
    power();
    return start;
  }

  void power() {
    const std::size_t start = program().size();
    primary();
    if (current.token != Token::power) return;
    const Lexeme op = current;
    Deeper deeper(*this);
    advance();
    const std::size_t exponent = program().size();
    signed_();
    if (constant_from(exponent)) {
      const double p = program()[exponent].number;
      program().pop_back();
      const bool integer = p == std::floor(p);
      if (!constant_from(start)) {
        if (!integer)
          warn(op.position, "a non-integer power u^p is not smooth at u = 0 and undefined for u < 0");
        else if (p < 0)
          warn(op.position, "a negative power u^n is singular where u = 0");
      }
      unary_op(integer ? FormulaOp::power_int : FormulaOp::power_real, start, op.position, "the power", p);
      return;
    }
    if (!(constant_from(start) && program()[start].number > 0))
      warn(op.position, "a^b with a variable exponent is defined only where a > 0");
    binary_op(FormulaOp::pow, start, exponent, op.position, "the power");
  }

  void primary() {
    const Lexeme l = current;
    switch (l.token) {
      case Token::number:
        emit(FormulaOp::constant, l.number);
        advance();
        expect_operand_end();
        return;
      case Token::open: {
        Deeper deeper(*this);
        advance();
        sum();
        if (current.token != Token::close)
          refuse(current.position, "expected ')' to close the '(' at " + std::to_string(l.position) +
                                       ", found " + describe(current));
        advance();
        expect_operand_end();
        return;
      }
      case Token::name: name_or_call(l); return;
      case Token::end: refuse(l.position, "the formula ends where a number, a name or '(' was expected");
      default: refuse(l.position, "expected a number, a name or '(' here, found " + describe(l));
    }
  }

  void name_or_call(const Lexeme& l) {
    advance();
    const std::string_view n = l.text;
    if (const FunctionName* f = find_function(n)) return call(l, *f);
    if (not_smooth(n))
      refuse(l.position,
             std::string(n) + " is not smooth: refused (a surface needs F of class C^2, its equations C^3)");
    if (n == "x")
      emit(FormulaOp::x);
    else if (n == "y")
      emit(FormulaOp::y);
    else if (n == "z") {
      if (variables == FormulaVariables::xy)
        refuse(l.position, "z is not a variable of a graph z = f(x, y): its formula uses x and y");
      emit(FormulaOp::z);
    } else if (n == "pi") {
      emit(FormulaOp::constant, std::numbers::pi);
    } else if (const auto p = parameters.find(n); p != parameters.end()) {
      emit(FormulaOp::constant, p->second);
    } else {
      if (current.token == Token::open)
        refuse(l.position, "unknown name " + shown(n) + " (the functions: " + function_list() + ")");
      std::string known = variables == FormulaVariables::xy ? "x, y" : "x, y, z";
      for (const auto& parameter : parameters) known += ", " + parameter.first;
      refuse(l.position, "unknown name " + shown(n) + " (the variables and parameters: " + known + ", pi)");
    }
    expect_operand_end();
  }

  void call(const Lexeme& l, const FunctionName& f) {
    if (current.token != Token::open)
      refuse(current.position,
             std::string(f.name) + " needs its argument in parentheses: " + std::string(f.name) + "(…)");
    Deeper deeper(*this);
    advance();
    const std::size_t first = program().size();
    sum();
    std::size_t second = first;
    if (f.arguments == 2) {
      if (current.token != Token::comma)
        refuse(current.position,
               std::string(f.name) + " takes two arguments separated by a comma, found " + describe(current));
      advance();
      second = program().size();
      sum();
    }
    if (current.token == Token::comma)
      refuse(current.position,
             std::string(f.name) + " takes " + (f.arguments == 1 ? "one argument" : "two arguments"));
    if (current.token != Token::close)
      refuse(current.position,
             "expected ')' to close " + std::string(f.name) + "(, found " + describe(current));
    advance();
    if (f.arguments == 2) {
      const bool constant =
          constant_from(second) && second == first + 1 && program()[first].op == FormulaOp::constant;
      if (!constant && !f.singular.empty()) warn(l.position, f.singular);
      binary_op(f.op, first, second, l.position, f.name);
    } else {
      if (!constant_from(first) && !f.singular.empty()) warn(l.position, f.singular);
      unary_op(f.op, first, l.position, f.name);
    }
    expect_operand_end();
  }
};

FormulaParse parse_formula(std::string_view text, const FormulaParameters& parameters,
                           FormulaVariables variables) {
  FormulaParse result;
  try {
    if (text.size() > kMaxFormulaLength)
      refuse(kMaxFormulaLength,
             "the formula is longer than " + std::to_string(kMaxFormulaLength) + " characters");
    if (parameters.size() > kMaxFormulaParameters)
      refuse(0, "more than " + std::to_string(kMaxFormulaParameters) + " parameters");
    for (const auto& [name, value] : parameters) {
      if (const auto problem = parameter_name_problem(name))
        refuse(0, "parameter " + shown(name) + ": " + *problem);
      if (!std::isfinite(value)) refuse(0, "parameter " + shown(name) + " is not a finite number");
    }
    FormulaCompiler compiler(text, parameters, variables);
    compiler.sum();
    if (compiler.current.token == Token::close)
      refuse(compiler.current.position, "a ')' with no '(' before it");
    if (compiler.current.token != Token::end)
      refuse(compiler.current.position,
             "expected an operator or the end of the formula, found " + compiler.describe(compiler.current));
    result.formula = compiler.finish(text);
  } catch (const Refusal& r) {
    result.error = r.error;
  }
  return result;
}

double Formula::value(const Eigen::Vector3d& X) const {
  std::array<double, kMaxFormulaStack> stack;
  std::size_t top = 0;
  for (const FormulaInstruction& i : program_) {
    switch (i.op) {
      case FormulaOp::constant: stack[top++] = i.number; break;
      case FormulaOp::x: stack[top++] = X.x(); break;
      case FormulaOp::y: stack[top++] = X.y(); break;
      case FormulaOp::z: stack[top++] = X.z(); break;
      default:
        if (binary(i.op)) {
          --top;
          stack[top - 1] = apply_binary(i.op, stack[top - 1], stack[top]);
        } else {
          stack[top - 1] = apply_unary(i.op, stack[top - 1], i.number);
        }
    }
  }
  return stack[0];
}

FormulaJet Formula::jet(const Eigen::Vector3d& X) const {
  std::array<Jet, kMaxFormulaStack> stack;
  std::size_t top = 0;
  const auto push = [&](double v, int variable) {
    Jet& j = stack[top++];
    j.v = v;
    j.g.setZero();
    j.h.setZero();
    if (variable >= 0) j.g(variable) = 1.0;
  };
  for (const FormulaInstruction& i : program_) {
    switch (i.op) {
      case FormulaOp::constant: push(i.number, -1); break;
      case FormulaOp::x: push(X.x(), 0); break;
      case FormulaOp::y: push(X.y(), 1); break;
      case FormulaOp::z: push(X.z(), 2); break;
      default:
        if (binary(i.op)) {
          --top;
          binary_jet(i.op, stack[top - 1], stack[top]);
        } else {
          unary_jet(i.op, stack[top - 1], i.number);
        }
    }
  }
  return {stack[0].v, stack[0].g, stack[0].h};
}

std::string Formula::identity() const {
  std::string key;
  char number[40];
  for (const FormulaInstruction& i : program_) {
    key += std::to_string(static_cast<int>(i.op));
    if (i.op == FormulaOp::constant || (i.op >= FormulaOp::power_int && i.op <= FormulaOp::rdiv_c)) {
      std::snprintf(number, sizeof number, ":%a", i.number);
      key += number;
    }
    key += ' ';
  }
  return key;
}

std::optional<std::string> parameter_name_problem(std::string_view name) {
  if (name.empty()) return "a name is needed";
  if (name.size() > kMaxFormulaNameLength)
    return "a name has at most " + std::to_string(kMaxFormulaNameLength) + " characters";
  if (!letter(name[0]) || name[0] == '_') return "a name starts with a letter";
  for (char c : name)
    if (!letter(c) && !digit(c)) return "a name has only letters, digits and underscores";
  if (name == "x" || name == "y" || name == "z") return "x, y and z are the variables";
  if (name == "pi") return "pi is the constant π";
  if (find_function(name) || not_smooth(name)) return std::string(name) + " is the name of a function";
  return std::nullopt;
}

const std::vector<std::string_view>& formula_functions() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> n;
    for (const FunctionName& f : kFunctions) n.push_back(f.name);
    return n;
  }();
  return names;
}

}  // namespace spinfold
