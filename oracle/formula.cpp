#include "oracle/formula.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <set>
#include <stdexcept>
#include <vector>

namespace spinfold::oracle {

namespace mp = boost::multiprecision;

struct OracleFormula::Node {
  enum Type {
    number,
    variable,
    negate,
    add,
    subtract,
    multiply,
    divide,
    power,
    function,
    arctan2
  } type = number;
  Big value = 0;     // number: its exact decimal value
  int index = 0;     // variable: 0, 1, 2 for x, y, z
  std::string name;  // function
  std::shared_ptr<const Node> a, b;
  bool constant = true;  // no variable below
};

namespace {

using Node = OracleFormula::Node;
using NodePtr = std::shared_ptr<const Node>;

// ---- hyper-dual numbers over Big: a + b₁ε₁ + b₂ε₂ + b₁₂ε₁ε₂ with ε₁² = ε₂² = 0 (ε₁ε₂ ≠ 0).
struct Hyper {
  Big a = 0, b1 = 0, b2 = 0, b12 = 0;
};
Hyper operator+(const Hyper& p, const Hyper& q) {
  return {p.a + q.a, p.b1 + q.b1, p.b2 + q.b2, p.b12 + q.b12};
}
Hyper operator-(const Hyper& p, const Hyper& q) {
  return {p.a - q.a, p.b1 - q.b1, p.b2 - q.b2, p.b12 - q.b12};
}
Hyper operator*(const Hyper& p, const Hyper& q) {
  return {p.a * q.a, p.a * q.b1 + p.b1 * q.a, p.a * q.b2 + p.b2 * q.a,
          p.a * q.b12 + p.b1 * q.b2 + p.b2 * q.b1 + p.b12 * q.a};
}
// f(p) from f, f′, f″ at p's real part (Taylor: the ε₁ε₂ part collects f″ b₁ b₂).
Hyper lift(const Hyper& p, const Big& f0, const Big& f1, const Big& f2) {
  return {f0, f1 * p.b1, f1 * p.b2, f1 * p.b12 + f2 * p.b1 * p.b2};
}
Hyper reciprocal(const Hyper& p) {
  const Big r = 1 / p.a;
  return lift(p, r, -r * r, 2 * r * r * r);
}

Hyper apply_function(const std::string& f, const Hyper& p) {
  const Big& x = p.a;
  if (f == "sqrt") {
    const Big s = mp::sqrt(x);
    return lift(p, s, 1 / (2 * s), -1 / (4 * x * s));
  }
  if (f == "exp") {
    const Big e = mp::exp(x);
    return lift(p, e, e, e);
  }
  if (f == "log") return lift(p, mp::log(x), 1 / x, -1 / (x * x));
  if (f == "sin") return lift(p, mp::sin(x), mp::cos(x), -mp::sin(x));
  if (f == "cos") return lift(p, mp::cos(x), -mp::sin(x), -mp::cos(x));
  if (f == "tan") {
    const Big c = mp::cos(x), sec2 = 1 / (c * c);
    return lift(p, mp::tan(x), sec2, 2 * mp::tan(x) * sec2);
  }
  if (f == "sinh") return lift(p, mp::sinh(x), mp::cosh(x), mp::sinh(x));
  if (f == "cosh") return lift(p, mp::cosh(x), mp::sinh(x), mp::cosh(x));
  if (f == "tanh") {
    const Big c = mp::cosh(x), sech2 = 1 / (c * c);
    return lift(p, mp::tanh(x), sech2, -2 * mp::tanh(x) * sech2);
  }
  if (f == "atan") {
    const Big q = 1 / (1 + x * x);
    return lift(p, mp::atan(x), q, -2 * x * q * q);
  }
  if (f == "asinh") {
    const Big q = 1 / mp::sqrt(1 + x * x);
    return lift(p, mp::asinh(x), q, -x * q * q * q);
  }
  throw std::logic_error("oracle formula: no function " + f);
}

Hyper evaluate(const Node& n, const std::array<Hyper, 3>& X) {
  switch (n.type) {
    case Node::number: return {n.value, 0, 0, 0};
    case Node::variable: return X[static_cast<std::size_t>(n.index)];
    case Node::negate: return Hyper{} - evaluate(*n.a, X);
    case Node::add: return evaluate(*n.a, X) + evaluate(*n.b, X);
    case Node::subtract: return evaluate(*n.a, X) - evaluate(*n.b, X);
    case Node::multiply: return evaluate(*n.a, X) * evaluate(*n.b, X);
    case Node::divide: return evaluate(*n.a, X) * reciprocal(evaluate(*n.b, X));
    case Node::function: return apply_function(n.name, evaluate(*n.a, X));
    case Node::arctan2: {
      // atan2(y, x) = θ₀ + atan((x₀y − y₀x)/(x₀x + y₀y)) near (x₀, y₀): the angle turned from there.
      const Hyper y = evaluate(*n.a, X), x = evaluate(*n.b, X);
      const Hyper x0{x.a, 0, 0, 0}, y0{y.a, 0, 0, 0};
      Hyper turn = (x0 * y - y0 * x) * reciprocal(x0 * x + y0 * y);
      turn = lift(turn, 0, 1, 0);  // atan at 0: 0, 1, 0 (the real part is 0 exactly)
      turn.a = mp::atan2(y.a, x.a);
      return turn;
    }
    case Node::power: {
      const Hyper base = evaluate(*n.a, X);
      if (n.b->constant) {
        const Big p = n.b->value;
        if (p == mp::floor(p) && mp::abs(p) <= 1024) {
          Hyper r{1, 0, 0, 0};
          for (long k = 0; k < mp::abs(p).convert_to<long>(); ++k) r = r * base;
          return p < 0 ? reciprocal(r) : r;
        }
        return lift(base, mp::pow(base.a, p), p * mp::pow(base.a, p - 1),
                    p * (p - 1) * mp::pow(base.a, p - 2));
      }
      const Hyper logarithm = apply_function("log", base);
      return apply_function("exp", evaluate(*n.b, X) * logarithm);
    }
  }
  throw std::logic_error("oracle formula: a node of no type");
}

// ---- the reader.
struct Refused {
  std::string why;
};

const std::set<std::string, std::less<>> kOneArgument = {"sqrt", "exp",  "log",  "sin",  "cos",  "tan",
                                                         "sinh", "cosh", "tanh", "atan", "asinh"};
const std::set<std::string, std::less<>> kNotC2 = {
    "abs", "min",  "max",       "sign", "sgn",       "floor", "ceil", "round", "trunc", "mod",   "fmod",
    "rem", "frac", "heaviside", "step", "piecewise", "if",    "re",   "im",    "int",   "clamp", "fabs"};

class Reader {
 public:
  Reader(std::string_view text, const std::map<std::string, double>& parameters, bool graph)
      : text_(text), parameters_(parameters), graph_(graph) {}

  NodePtr formula() {
    if (text_.size() > 4096) throw Refused{"longer than 4096 characters"};
    NodePtr n = sum();
    skip();
    if (at_ != text_.size()) throw Refused{"text after the formula"};
    return n;
  }

 private:
  void skip() {
    while (at_ < text_.size() && std::string_view(" \t\r\n").find(text_[at_]) != std::string_view::npos)
      ++at_;
  }
  bool take(std::string_view s) {
    skip();
    if (text_.substr(at_, s.size()) != s) return false;
    if (s == "*" && text_.substr(at_, 2) == "**") return false;  // a power, not a product
    at_ += s.size();
    return true;
  }
  struct Level {
    explicit Level(Reader& r) : reader(r) {
      if (++reader.depth_ > 48) throw Refused{"nested deeper than 48 levels"};
    }
    ~Level() { --reader.depth_; }
    Reader& reader;
  };

  // A node of two children (or one): constant when they are, its value checked then.
  NodePtr make(Node::Type type, NodePtr a, NodePtr b = nullptr, std::string name = "") {
    auto n = std::make_shared<Node>();
    n->type = type;
    n->a = a;
    n->b = b;
    n->name = std::move(name);
    n->constant = a->constant && (!b || b->constant);
    if (type == Node::divide && b->constant && b->value == 0) throw Refused{"division by zero"};
    if (n->constant) {
      const std::array<Hyper, 3> none{};
      n->value = evaluate(*n, none).a;
      const double as_double = n->value.convert_to<double>();
      if (!std::isfinite(as_double)) throw Refused{"a constant that is not a finite double"};
    }
    return n;
  }

  NodePtr sum() {
    NodePtr n = product();
    for (;;) {
      if (take("+"))
        n = make(Node::add, n, product());
      else if (take("-"))
        n = make(Node::subtract, n, product());
      else
        return n;
    }
  }
  NodePtr product() {
    NodePtr n = signed_();
    for (;;) {
      if (take("*"))
        n = make(Node::multiply, n, signed_());
      else if (take("/"))
        n = make(Node::divide, n, signed_());
      else
        return n;
    }
  }
  NodePtr signed_() {
    skip();
    if (at_ < text_.size() && (text_[at_] == '-' || text_[at_] == '+')) {
      const bool minus = text_[at_] == '-';
      Level level(*this);
      ++at_;
      NodePtr inner = signed_();
      return minus ? make(Node::negate, inner) : inner;
    }
    NodePtr base = primary();
    if (take("^") || take("**")) {
      Level level(*this);
      return make(Node::power, base, signed_());
    }
    return base;
  }
  // After an operand, another operand straight after it is a missing operator.
  void operand_ends() {
    skip();
    if (at_ < text_.size()) {
      const char c = text_[at_];
      if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '(')
        throw Refused{"an operator is missing"};
    }
  }
  NodePtr primary() {
    skip();
    if (at_ == text_.size()) throw Refused{"the formula ends early"};
    const char c = text_[at_];
    if (std::isdigit(static_cast<unsigned char>(c)) ||
        (c == '.' && at_ + 1 < text_.size() && std::isdigit(static_cast<unsigned char>(text_[at_ + 1])))) {
      NodePtr n = number();
      operand_ends();
      return n;
    }
    if (c == '(') {
      Level level(*this);
      ++at_;
      NodePtr n = sum();
      if (!take(")")) throw Refused{"a '(' not closed"};
      operand_ends();
      return n;
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      const std::size_t start = at_;
      while (at_ < text_.size() &&
             (std::isalnum(static_cast<unsigned char>(text_[at_])) || text_[at_] == '_'))
        ++at_;
      NodePtr n = name(std::string(text_.substr(start, at_ - start)));
      operand_ends();
      return n;
    }
    throw Refused{"a character or operator where an operand belongs"};
  }
  NodePtr number() {
    const std::size_t start = at_;
    while (at_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[at_]))) ++at_;
    if (at_ < text_.size() && text_[at_] == '.') {
      ++at_;
      while (at_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[at_]))) ++at_;
    }
    if (at_ < text_.size() && (text_[at_] == 'e' || text_[at_] == 'E')) {
      std::size_t e = at_ + 1;
      if (e < text_.size() && (text_[e] == '+' || text_[e] == '-')) ++e;
      if (e < text_.size() && std::isdigit(static_cast<unsigned char>(text_[e]))) {
        at_ = e;
        while (at_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[at_]))) ++at_;
      }
    }
    std::string digits(text_.substr(start, at_ - start));
    errno = 0;
    const double nearest = std::strtod(digits.c_str(), nullptr);
    if (errno == ERANGE || !std::isfinite(nearest)) throw Refused{"a number beyond double range"};
    if (digits[0] == '.') digits = "0" + digits;
    auto n = std::make_shared<Node>();
    n->value = Big(digits);  // the decimal as written
    return n;
  }
  NodePtr name(const std::string& word) {
    if (kNotC2.count(word)) throw Refused{word + " is not smooth"};
    if (kOneArgument.count(word) || word == "atan2") {
      if (!take("(")) throw Refused{word + " without its argument"};
      Level level(*this);
      NodePtr first = sum();
      NodePtr n;
      if (word == "atan2") {
        if (!take(",")) throw Refused{"atan2 needs two arguments"};
        NodePtr second = sum();
        n = make(Node::arctan2, first, second);
      } else {
        n = make(Node::function, first, nullptr, word);
      }
      if (!take(")")) throw Refused{word + "( not closed"};
      return n;
    }
    auto n = std::make_shared<Node>();
    if (word == "x" || word == "y" || (word == "z" && !graph_)) {
      n->type = Node::variable;
      n->index = word[0] - 'x';
      n->constant = false;
    } else if (word == "pi") {
      n->value = mp::acos(Big(-1));
    } else if (auto p = parameters_.find(word); p != parameters_.end()) {
      n->value = Big(p->second);
    } else {
      throw Refused{"unknown name " + word};
    }
    return n;
  }

  std::string_view text_;
  const std::map<std::string, double>& parameters_;
  bool graph_;
  std::size_t at_ = 0;
  int depth_ = 0;
};

}  // namespace

std::optional<OracleFormula> OracleFormula::read(std::string_view text,
                                                 const std::map<std::string, double>& parameters, bool graph,
                                                 std::string* why) {
  for (char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (!(std::isalnum(u) || std::string_view("_.+-*/^(), \t\r\n").find(c) != std::string_view::npos)) {
      if (why) *why = "a character outside the language";
      return std::nullopt;
    }
  }
  try {
    OracleFormula f;
    f.root_ = Reader(text, parameters, graph).formula();
    return f;
  } catch (const Refused& r) {
    if (why) *why = r.why;
    return std::nullopt;
  }
}

FormulaValue OracleFormula::at(const std::array<Big, 3>& X) const {
  FormulaValue out;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      std::array<Hyper, 3> seeded;
      for (int k = 0; k < 3; ++k)
        seeded[static_cast<std::size_t>(k)] = {X[static_cast<std::size_t>(k)], 0, 0, 0};
      seeded[static_cast<std::size_t>(i)].b1 = 1;
      seeded[static_cast<std::size_t>(j)].b2 = 1;
      const Hyper h = evaluate(*root_, seeded);
      out.F = h.a;
      if (i == j) out.gradient[static_cast<std::size_t>(i)] = h.b1;
      out.hessian[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = h.b12;
      out.hessian[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)] = h.b12;
    }
  return out;
}

}  // namespace spinfold::oracle
