#include "oracle/oracle.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

namespace spinfold::oracle {

__extension__ typedef __float128 Quad;

// ---- the scalar types' functions: one overload set for __float128 and Big -----------------------
namespace num {
// __float128 arithmetic is the compiler's (GCC and clang; soft float in libgcc). Its few functions are
// written here so that no libquadmath (whose header clang does not see) is needed: the square root by
// Newton from the double one (each step doubles the digits), the rest through the 50-digit type (they
// are used only to build the start).
inline double to_double(Quad x) {
  return static_cast<double>(x);
}
inline Quad from_big(const Big& x) {
  // three doubles carry the 113 bits
  const double hi = static_cast<double>(x);
  const Big r1 = x - Big(hi);
  const double mid = static_cast<double>(r1);
  const double lo = static_cast<double>(r1 - Big(mid));
  return Quad(hi) + Quad(mid) + Quad(lo);
}
inline Big to_big(Quad x) {
  const double hi = static_cast<double>(x);
  const Quad r1 = x - Quad(hi);
  const double mid = static_cast<double>(r1);
  const double lo = static_cast<double>(r1 - Quad(mid));
  return Big(hi) + Big(mid) + Big(lo);
}
inline Quad abs(Quad x) {
  return x < 0 ? -x : x;
}
inline bool finite(Quad x) {
  return x == x && x - x == 0;  // false for NaN and ±inf
}
inline Quad sqrt(Quad x) {
  if (!(x > 0)) return x == 0 ? Quad(0) : from_big(boost::multiprecision::sqrt(to_big(x)));  // NaN
  Quad y = std::sqrt(static_cast<double>(x));
  for (int i = 0; i < 2; ++i) y = (y + x / y) / 2;
  return y;
}
inline Quad sin(Quad x) {
  return from_big(boost::multiprecision::sin(to_big(x)));
}
inline Quad cos(Quad x) {
  return from_big(boost::multiprecision::cos(to_big(x)));
}
inline Quad sinh(Quad x) {
  return from_big(boost::multiprecision::sinh(to_big(x)));
}
inline Quad cosh(Quad x) {
  return from_big(boost::multiprecision::cosh(to_big(x)));
}
inline Big sqrt(const Big& x) {
  return boost::multiprecision::sqrt(x);
}
inline Big sin(const Big& x) {
  return boost::multiprecision::sin(x);
}
inline Big cos(const Big& x) {
  return boost::multiprecision::cos(x);
}
inline Big sinh(const Big& x) {
  return boost::multiprecision::sinh(x);
}
inline Big cosh(const Big& x) {
  return boost::multiprecision::cosh(x);
}
inline Big abs(const Big& x) {
  return boost::multiprecision::abs(x);
}
inline Big asin(const Big& x) {
  return boost::multiprecision::asin(x);
}
inline Big asinh(const Big& x) {
  return boost::multiprecision::asinh(x);
}
inline bool finite(const Big& x) {
  return boost::multiprecision::isfinite(x);
}
inline double to_double(const Big& x) {
  return static_cast<double>(x);
}
template <class T>
T convert(const Big& x) {
  if constexpr (std::is_same_v<T, Quad>)
    return from_big(x);
  else
    return x;
}
template <class T>
Big big(const T& x) {
  if constexpr (std::is_same_v<T, Quad>)
    return to_big(x);
  else
    return x;
}
}  // namespace num

template <class T>
using V3 = std::array<T, 3>;

template <class T>
V3<T> operator+(const V3<T>& a, const V3<T>& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
template <class T>
V3<T> operator-(const V3<T>& a, const V3<T>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
template <class T>
V3<T> operator*(const T& s, const V3<T>& a) {
  return {s * a[0], s * a[1], s * a[2]};
}
template <class T>
V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// ---- dual numbers: the potentials' derivatives without writing them out ----------------------
template <class T>
struct Dual {
  T v, d;
};
template <class T>
Dual<T> operator+(Dual<T> a, Dual<T> b) {
  return {a.v + b.v, a.d + b.d};
}
template <class T>
Dual<T> operator-(Dual<T> a, Dual<T> b) {
  return {a.v - b.v, a.d - b.d};
}
template <class T>
Dual<T> operator*(Dual<T> a, Dual<T> b) {
  return {a.v * b.v, a.d * b.v + a.v * b.d};
}
template <class T>
Dual<T> operator/(Dual<T> a, Dual<T> b) {
  return {a.v / b.v, (a.d * b.v - a.v * b.d) / (b.v * b.v)};
}
template <class T>
Dual<T> dsqrt(Dual<T> a) {
  const T s = num::sqrt(a.v);
  return {s, a.d / (2 * s)};
}
template <class T>
Dual<T> cst(const T& c) {
  return {c, T(0)};
}

// ---- the problem in the start frame --------------------------------------------------------
template <class T>
struct Problem {
  Kind kind;
  Model model;
  T R, K, m;
  T J[4], Jinv[4];  // row-major J^{AB} and its inverse
  T J_iso;          // tr J / 2 (the rigid body's)
  bool radial;
  T g;
  V3<T> O;  // the scene's pole (the radial potential's centre) in the start frame
  DefKind def;
  T A, B, C, ghat, gtilde;
  bool literal;
  T spin_rigid, omega_rigid;  // rigid: s and the rate s/(2Jλ₀²)
  T det_c;                    // incompressible: det L

  T eta() const { return kind == Kind::pseudosphere ? T(-1) : T(1); }
  T dot(const V3<T>& a, const V3<T>& b) const { return a[0] * b[0] + a[1] * b[1] + eta() * a[2] * b[2]; }
  // k = 1/⟨X,X⟩ (0 on the plane): the stabilised form of §7
  T kfac(const V3<T>& X) const { return kind == Kind::plane ? T(0) : T(1) / dot(X, X); }
  V3<T> normal(const V3<T>& X) const {
    if (kind == Kind::plane) return {T(0), T(0), T(1)};
    return (T(1) / R) * X;
  }
  V3<T> jrot(const V3<T>& X, const V3<T>& v) const {
    V3<T> w = cross(normal(X), v);
    w[2] = eta() * w[2];
    return w;
  }
  T omega(const V3<T>& X, const V3<T>& a, const V3<T>& b) const {
    const V3<T> c = cross(a, b), n = normal(X);
    return c[0] * n[0] + c[1] * n[1] + c[2] * n[2];
  }
  V3<T> P(const V3<T>& X, const V3<T>& w) const { return w - (kfac(X) * dot(w, X)) * X; }

  // V_r and its gradient (a vector) at X.
  T radial_potential(const V3<T>& X, V3<T>* grad) const {
    if (!radial) {
      if (grad) *grad = {T(0), T(0), T(0)};
      return T(0);
    }
    if (kind == Kind::plane) {
      const V3<T> d = X - O;
      const T rho2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (grad) *grad = (T(-2) * g / (rho2 * rho2)) * d;
      return g / rho2;
    }
    const Dual<T> u{K * dot(X, O), T(1)};  // u = C(r)
    const Dual<T> one = cst(T(1));
    const Dual<T> V =
        kind == Kind::sphere ? cst(g) / ((one - u) * (one + u)) : cst(g / (R * R)) / ((u - one) * (u + one));
    if (grad) *grad = (V.d * K) * O;
    return V.v;
  }
  // V(a, b), a = x², b = y²; dVa, dVb its partial derivatives.
  template <class S>
  S def_potential(S a, S b) const {
    S zero = a - a;
    if (def == DefKind::abc) {
      S v = zero;
      if (A != 0) v = v + S{A, T(0)} / a;
      if (B != 0) v = v + S{B, T(0)} / b;
      if (C != 0) v = v + S{C, T(0)} * (a + b);
      return v;
    }
    if (def == DefKind::polar) {
      const S sum = a + b, diff = b - a;
      S v = S{gtilde, T(0)} / dsqrt(sum);
      if (literal)
        v = v + S{ghat / 4, T(0)} * diff * diff / (a * a * b);
      else
        v = v + S{ghat / 4, T(0)} * diff * diff / (a * b * sum);
      return v;
    }
    return zero;
  }
  T deformation(const V3<T>& X, const V3<T>& e1, const V3<T>& e2, T* Va, T* Vb) const {
    if (def == DefKind::none) {
      if (Va) *Va = *Vb = T(0);
      return T(0);
    }
    const T h = (dot(e1, e1) + dot(e2, e2)) / 2, w = omega(X, e1, e2);
    const T a = h - w, b = h + w;
    const Dual<T> da = def_potential(Dual<T>{a, T(1)}, Dual<T>{b, T(0)});
    if (Va) {
      *Va = da.d;
      *Vb = def_potential(Dual<T>{a, T(0)}, Dual<T>{b, T(1)}).d;
    }
    return da.v;
  }
  T spin(const V3<T>& X, const V3<T>* e, const V3<T>* W) const {
    if (model == Model::rigid) return spin_rigid;
    T s = 0;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) s += J[b * 2 + a] * omega(X, e[a], W[b]);
    return s;
  }
  int size() const { return model == Model::rigid ? 9 : 18; }

  void field(const T* y, T* f) const {
    V3<T> X{y[0], y[1], y[2]}, V{y[3], y[4], y[5]};
    const T k = kfac(X);
    V3<T> gradr;
    radial_potential(X, &gradr);
    const V3<T> F = T(-1) * P(X, gradr);
    auto put = [&](int i, const V3<T>& v) { f[i] = v[0], f[i + 1] = v[1], f[i + 2] = v[2]; };
    put(0, V);
    if (model == Model::rigid) {
      const V3<T> e1{y[6], y[7], y[8]};
      put(3, (T(1) / m) * ((K * spin_rigid) * jrot(X, V) + F) - (k * dot(V, V)) * X);
      put(6, omega_rigid * jrot(X, e1) - (k * dot(e1, V)) * X);
      return;
    }
    const V3<T> e[2] = {{y[6], y[7], y[8]}, {y[9], y[10], y[11]}};
    const V3<T> W[2] = {{y[12], y[13], y[14]}, {y[15], y[16], y[17]}};
    const T s = spin(X, e, W);
    put(3, (T(1) / m) * ((K * s) * jrot(X, V) + F) - (k * dot(V, V)) * X);
    T Va, Vb;
    deformation(X, e[0], e[1], &Va, &Vb);
    const V3<T> je1 = jrot(X, e[0]), je2 = jrot(X, e[1]);
    const V3<T> G[2] = {P(X, Va * (e[0] + je2) + Vb * (e[0] - je2)),
                        P(X, Va * (e[1] - je1) + Vb * (e[1] + je1))};
    V3<T> acc[2];
    for (int a = 0; a < 2; ++a) acc[a] = T(-1) * (Jinv[0 * 2 + a] * G[0] + Jinv[1 * 2 + a] * G[1]);
    if (model == Model::incompressible) {
      // constraint force −ν ∂(det L)/∂e_A, ∂/∂e₁ = −je₂, ∂/∂e₂ = je₁; ν from d²(det L)/dt² = 0
      const V3<T> Cg[2] = {T(-1) * je2, je1};
      V3<T> c[2];
      for (int a = 0; a < 2; ++a) c[a] = T(-1) * (Jinv[0 * 2 + a] * Cg[0] + Jinv[1 * 2 + a] * Cg[1]);
      const T q0 = omega(X, acc[0], e[1]) + omega(X, e[0], acc[1]) + 2 * omega(X, W[0], W[1]);
      const T q1 = omega(X, c[0], e[1]) + omega(X, e[0], c[1]);
      const T nu = -q0 / q1;
      for (int a = 0; a < 2; ++a) acc[a] = acc[a] + nu * c[a];
    }
    for (int a = 0; a < 2; ++a) {
      put(6 + 3 * a, W[a] - (k * dot(e[a], V)) * X);
      put(12 + 3 * a, acc[a] - (k * dot(W[a], V)) * X);
    }
  }

  T energy(const V3<T>& X, const V3<T>& V, const V3<T>* e, const V3<T>* W) const {
    T H = m * dot(V, V) / 2 + radial_potential(X, nullptr);
    if (model == Model::rigid) return H + spin_rigid * spin_rigid / (4 * J_iso * dot(e[0], e[0]));
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) H += J[a * 2 + b] * dot(W[a], W[b]) / 2;
    return H + deformation(X, e[0], e[1], nullptr, nullptr);
  }
};

// ---- reading the scene ----------------------------------------------------------------------
namespace {

using nlohmann::json;

double number(const json& j, const char* key, double fallback, const std::string& path) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return fallback;
  if (!it->is_number()) throw std::runtime_error(path + "." + key + ": not a number");
  return it->get<double>();
}
std::optional<double> maybe(const json& j, const char* key, const std::string& path) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return std::nullopt;
  if (!it->is_number()) throw std::runtime_error(path + "." + key + ": not a number");
  return it->get<double>();
}
const json& block(const json& j, const char* key) {
  static const json empty = json::object();
  const auto it = j.find(key);
  return it != j.end() && it->is_object() ? *it : empty;
}

}  // namespace

OracleScene read_scene(std::string_view json_text) {
  const json j = json::parse(json_text);
  OracleScene s;
  const json& surface = block(j, "surface");
  if (const auto K = maybe(surface, "curvature", "surface")) {
    if (std::abs(*K) < 1e-24) {  // the scene format's flat limit
      s.kind = Kind::plane;
      s.R = 1.0;
    } else {
      s.kind = *K > 0 ? Kind::sphere : Kind::pseudosphere;
      s.R = 1.0 / std::sqrt(std::abs(*K));
    }
  } else {
    const std::string kind = surface.value("kind", std::string("sphere"));
    if (kind == "sphere")
      s.kind = Kind::sphere;
    else if (kind == "pseudosphere")
      s.kind = Kind::pseudosphere;
    else if (kind == "plane")
      s.kind = Kind::plane;
    else
      throw std::runtime_error("surface.kind: unknown '" + kind + "'");
    s.R = number(surface, "radius", 1.0, "surface");
  }
  const json& body = block(j, "body");
  s.mass = number(body, "mass", 1.0, "body");
  if (const auto it = body.find("inertia"); it != body.end() && it->is_array()) {
    s.J = {(*it)[0][0].get<double>(), (*it)[0][1].get<double>(), (*it)[1][0].get<double>(),
           (*it)[1][1].get<double>()};
  } else {
    const double J = number(body, "inertia", 0.1, "body");
    s.J = {J, 0.0, 0.0, J};
  }
  const std::string model = body.value("model", std::string("affine"));
  s.model = model == "rigid"            ? Model::rigid
            : model == "incompressible" ? Model::incompressible
                                        : Model::affine;
  const json& potential = block(j, "potential");
  if (const auto it = potential.find("radial"); it != potential.end() && it->is_object()) {
    s.radial = true;
    s.g = number(*it, "gamma", 0.0, "potential.radial");
  }
  if (const auto it = potential.find("deformation"); it != potential.end() && it->is_object()) {
    const std::string kind = it->value("kind", std::string());
    if (kind == "abc") {
      s.def = DefKind::abc;
      s.A = number(*it, "A", 0, "potential.deformation");
      s.B = number(*it, "B", 0, "potential.deformation");
      s.C = number(*it, "C", 0, "potential.deformation");
    } else if (kind == "polar") {
      s.def = DefKind::polar;
      s.ghat = number(*it, "ghat", 0, "potential.deformation");
      s.gtilde = number(*it, "gtilde", 0, "potential.deformation");
      s.literal = it->value("form", std::string("cot2")) == "literal";
    } else if (!kind.empty()) {
      throw std::runtime_error("potential.deformation.kind: unknown '" + kind + "'");
    }
  }
  const json& q = block(j, "initial");
  const std::string p = "initial";
  s.r = number(q, "r", 1.0, p), s.phi = number(q, "phi", 0.0, p);
  s.alpha = number(q, "alpha", 0.0, p), s.beta = number(q, "beta", 0.0, p);
  s.lambda = number(q, "lambda", 1.0, p), s.mu = number(q, "mu", 1.0, p);
  s.r_dot = number(q, "r_dot", 0.0, p), s.phi_dot = number(q, "phi_dot", 0.0, p);
  s.alpha_dot = number(q, "alpha_dot", 0.0, p), s.beta_dot = number(q, "beta_dot", 0.0, p);
  s.lambda_dot = number(q, "lambda_dot", 0.0, p), s.mu_dot = number(q, "mu_dot", 0.0, p);
  s.spin = maybe(q, "spin", p), s.speed = maybe(q, "speed", p), s.heading = maybe(q, "heading", p);
  return s;
}

// ---- the start isometry ---------------------------------------------------------------------
Isometry start_isometry(const OracleScene& s) {
  const Big phi(s.phi), c = num::cos(phi), sn = num::sin(phi);
  const std::array<std::array<Big, 3>, 3> Rz{{{c, -sn, Big(0)}, {sn, c, Big(0)}, {Big(0), Big(0), Big(1)}}};
  std::array<std::array<Big, 3>, 3> T2{};
  Isometry iso;
  iso.b = {Big(0), Big(0), Big(0)};
  if (s.kind == Kind::plane) {
    iso.M = Rz;
    iso.b = {Big(s.r) * c, Big(s.r) * sn, Big(0)};
    return iso;
  }
  const Big th = Big(s.r) / Big(s.R);
  if (s.kind == Kind::sphere)
    T2 = {{{num::cos(th), Big(0), num::sin(th)},
           {Big(0), Big(1), Big(0)},
           {-num::sin(th), Big(0), num::cos(th)}}};
  else
    T2 = {{{num::cosh(th), Big(0), num::sinh(th)},
           {Big(0), Big(1), Big(0)},
           {num::sinh(th), Big(0), num::cosh(th)}}};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      Big sum = 0;
      for (int l = 0; l < 3; ++l) sum += Rz[i][l] * T2[l][k];
      iso.M[i][k] = sum;
    }
  return iso;
}

std::array<Big, 3> to_start_vector(const OracleScene& s, const Isometry& iso, const std::array<Big, 3>& v) {
  // M⁻¹ = Mᵀ (rotations), ηMᵀη (Lorentz)
  const Big eta = s.kind == Kind::pseudosphere ? Big(-1) : Big(1);
  std::array<Big, 3> w = v;
  w[2] *= eta;
  std::array<Big, 3> out;
  for (int k = 0; k < 3; ++k) out[k] = iso.M[0][k] * w[0] + iso.M[1][k] * w[1] + iso.M[2][k] * w[2];
  out[2] *= eta;
  return out;
}

std::array<Big, 3> to_start_point(const OracleScene& s, const Isometry& iso, const std::array<Big, 3>& x) {
  return to_start_vector(s, iso, {x[0] - iso.b[0], x[1] - iso.b[1], x[2] - iso.b[2]});
}

// ---- the problem and the start state ----------------------------------------------------------
namespace {

template <class T>
Problem<T> make_problem(const OracleScene& s) {
  Problem<T> p{};
  p.kind = s.kind;
  p.model = s.model;
  p.R = T(s.R);
  p.K = s.kind == Kind::plane ? T(0) : (s.kind == Kind::sphere ? T(1) : T(-1)) / (p.R * p.R);
  p.m = T(s.mass);
  for (int i = 0; i < 4; ++i) p.J[i] = T(s.J[i]);
  const T det = p.J[0] * p.J[3] - p.J[1] * p.J[2];
  p.Jinv[0] = p.J[3] / det, p.Jinv[1] = -p.J[1] / det, p.Jinv[2] = -p.J[2] / det, p.Jinv[3] = p.J[0] / det;
  p.J_iso = (p.J[0] + p.J[3]) / 2;
  p.radial = s.radial;
  p.g = T(s.g);
  const Isometry iso = start_isometry(s);
  const std::array<Big, 3> O =
      to_start_point(s, iso, {Big(0), Big(0), s.kind == Kind::plane ? Big(0) : Big(s.R)});
  for (int i = 0; i < 3; ++i) p.O[i] = num::convert<T>(O[i]);
  p.def = s.def;
  p.A = T(s.A), p.B = T(s.B), p.C = T(s.C), p.ghat = T(s.ghat), p.gtilde = T(s.gtilde);
  p.literal = s.literal;
  return p;
}

// 2×2 helpers (row-major), in T
template <class T>
using M2 = std::array<T, 4>;
template <class T>
M2<T> mul(const M2<T>& a, const M2<T>& b) {
  return {a[0] * b[0] + a[1] * b[2], a[0] * b[1] + a[1] * b[3], a[2] * b[0] + a[3] * b[2],
          a[2] * b[1] + a[3] * b[3]};
}
template <class T>
M2<T> rot(const T& a) {
  return {num::cos(a), -num::sin(a), num::sin(a), num::cos(a)};
}
template <class T>
M2<T> trans(const M2<T>& a) {
  return {a[0], a[2], a[1], a[3]};
}
template <class T>
T trace(const M2<T>& a) {
  return a[0] + a[3];
}

// The scene's initial values (physics.md §1–§3, §13; spin, speed, heading as the scene format
// defines them) as a state vector in the start frame, where E₁ = x̂, E₂ = ŷ at X₀.
template <class T>
std::vector<T> start_state(const OracleScene& s, Problem<T>& p) {
  const T r(s.r), R(s.R);
  T S, C;
  if (s.kind == Kind::plane)
    S = r, C = T(1);
  else if (s.kind == Kind::sphere)
    S = R * num::sin(r / R), C = num::cos(r / R);
  else
    S = R * num::sinh(r / R), C = num::cosh(r / R);
  const V3<T> X0 = s.kind == Kind::plane ? V3<T>{T(0), T(0), T(0)} : V3<T>{T(0), T(0), R};
  const V3<T> E1{T(1), T(0), T(0)}, E2{T(0), T(1), T(0)};
  // velocity: V = ṙE₁ + Sφ̇E₂, or v(cos h E₁ + sin h E₂)
  T vr = T(s.r_dot), vphi = S * T(s.phi_dot), phi_dot = T(s.phi_dot);
  if (s.speed && s.heading) {
    vr = T(*s.speed) * num::cos(T(*s.heading));
    vphi = T(*s.speed) * num::sin(T(*s.heading));
    phi_dot = S == 0 ? T(0) : vphi / S;
  }
  const V3<T> V = vr * E1 + vphi * E2;
  const M2<T> eps{T(0), T(-1), T(1), T(0)};
  const M2<T> Ua = rot(T(s.alpha)), Ub = rot(T(s.beta));
  const M2<T> D{T(s.lambda), T(0), T(0), T(s.mu)}, Dd{T(s.lambda_dot), T(0), T(0), T(s.mu_dot)};
  const M2<T> L = mul(mul(Ua, D), trans(Ub));
  std::vector<T> y(p.size());
  auto put = [&](int i, const V3<T>& v) { y[i] = v[0], y[i + 1] = v[1], y[i + 2] = v[2]; };
  put(0, X0);
  put(3, V);
  if (s.model == Model::rigid) {
    const T l = T(s.lambda);
    // s = 2Jλ₀²(α̇ − β̇ + Cφ̇) with J = tr J/2 (§8.8, §13)
    const T w = s.spin ? T(*s.spin) / (2 * p.J_iso * l * l) : T(s.alpha_dot) - T(s.beta_dot) + C * phi_dot;
    p.omega_rigid = w;
    p.spin_rigid = 2 * p.J_iso * l * l * w;
    put(6, L[0] * E1 + L[2] * E2);
    return y;
  }
  // M = χεL + U(α)diag(λ̇, μ̇)U(β)ᵀ − β̇Lε, χ = α̇ + Cφ̇; with a given spin, s = tr((εL)ᵀMJ) solved for χ
  const M2<T> eL = mul(eps, L), Le = mul(L, eps);
  M2<T> N = mul(mul(Ua, Dd), trans(Ub));
  for (int i = 0; i < 4; ++i) N[i] -= T(s.beta_dot) * Le[i];
  const M2<T> Jm{p.J[0], p.J[1], p.J[2], p.J[3]};
  T chi = T(s.alpha_dot) + C * phi_dot;
  if (s.spin) {
    const T a = trace(mul(mul(trans(eL), eL), Jm)), b = trace(mul(mul(trans(eL), N), Jm));
    chi = (T(*s.spin) - b) / a;
  }
  M2<T> M;
  for (int i = 0; i < 4; ++i) M[i] = chi * eL[i] + N[i];
  put(6, L[0] * E1 + L[2] * E2);
  put(9, L[1] * E1 + L[3] * E2);
  put(12, M[0] * E1 + M[2] * E2);
  put(15, M[1] * E1 + M[3] * E2);
  p.det_c = L[0] * L[3] - L[1] * L[2];
  return y;
}

template <class T>
Body3 body_of(const Problem<T>& p, const std::vector<T>& y) {
  Body3 b;
  auto get = [&](int i) {
    return std::array<Big, 3>{num::big(y[i]), num::big(y[i + 1]), num::big(y[i + 2])};
  };
  b.X = get(0), b.V = get(3), b.e1 = get(6);
  if (p.model == Model::rigid) {
    const V3<T> X{y[0], y[1], y[2]}, e1{y[6], y[7], y[8]};
    const V3<T> e2 = p.jrot(X, e1), W1 = p.omega_rigid * e2, W2 = p.omega_rigid * p.jrot(X, e2);
    auto big3 = [](const V3<T>& v) {
      return std::array<Big, 3>{num::big(v[0]), num::big(v[1]), num::big(v[2])};
    };
    b.e2 = big3(e2), b.W1 = big3(W1), b.W2 = big3(W2);
  } else {
    b.e2 = get(9), b.W1 = get(12), b.W2 = get(15);
  }
  return b;
}

template <class T>
T energy_of_state(const Problem<T>& p, const std::vector<T>& y) {
  const V3<T> X{y[0], y[1], y[2]}, V{y[3], y[4], y[5]};
  V3<T> e[2] = {{y[6], y[7], y[8]}, {}}, W[2];
  if (p.model != Model::rigid) {
    e[1] = {y[9], y[10], y[11]};
    W[0] = {y[12], y[13], y[14]}, W[1] = {y[15], y[16], y[17]};
  }
  return p.energy(X, V, e, W);
}

// Gragg–Bulirsch–Stoer: the modified midpoint rule with n = 2, 4, …, 2k substeps, extrapolated to
// h → 0 in h² (Aitken–Neville); the difference of the last two diagonal entries is the error
// estimate of the order-(2k−2) one, and the order-2k one is kept.
template <class T>
OracleRun integrate(const OracleScene& s, double t_end, double tolerance, long max_steps) {
  constexpr int kStages = 8;
  Problem<T> p = make_problem<T>(s);
  std::vector<T> y = start_state(s, p);
  const int n = p.size();
  OracleRun run;
  run.start = body_of(p, y);
  const T H0 = energy_of_state(p, y);
  run.energy = num::to_double(H0);
  run.energy_exact = num::big(H0);
  {
    Problem<T> q = p;  // the yardstick: kinetic + |potential|
    const V3<T> X{y[0], y[1], y[2]};
    T pot = q.radial_potential(X, nullptr);
    if (p.model != Model::rigid)
      pot += q.deformation(X, {y[6], y[7], y[8]}, {y[9], y[10], y[11]}, nullptr, nullptr);
    run.energy_scale = num::to_double(num::abs(H0 - pot) + num::abs(pot));
  }
  std::vector<T> f0(n), z0(n), z1(n), fz(n);
  std::vector<std::vector<T>> prev(kStages, std::vector<T>(n)), cur = prev;
  const T tol(tolerance), end(t_end);
  T t(0), h = T(t_end) / 64;
  if (h > T(0.05)) h = T(0.05);
  auto eval = [&](const std::vector<T>& in, std::vector<T>& out) {
    p.field(in.data(), out.data());
    ++run.evaluations;
  };
  while (t < end) {
    if (run.steps >= max_steps) {
      run.error = "too many steps";
      return run;
    }
    bool last = false;
    if (t + h >= end) h = end - t, last = true;
    eval(y, f0);
    for (int j = 0; j < kStages; ++j) {
      const int steps = 2 * (j + 1);
      const T hs = h / steps;
      for (int i = 0; i < n; ++i) z0[i] = y[i], z1[i] = y[i] + hs * f0[i];
      for (int m = 1; m < steps; ++m) {
        eval(z1, fz);
        for (int i = 0; i < n; ++i) {
          const T next = z0[i] + 2 * hs * fz[i];
          z0[i] = z1[i], z1[i] = next;
        }
      }
      eval(z1, fz);
      for (int i = 0; i < n; ++i) cur[0][i] = (z1[i] + z0[i] + hs * fz[i]) / 2;
      for (int l = 1; l <= j; ++l) {  // Neville in h²: n_j / n_{j−l} = (j+1)/(j−l+1)
        const T ratio = T(j + 1) / T(j - l + 1);
        const T factor = T(1) / (ratio * ratio - 1);
        for (int i = 0; i < n; ++i) cur[l][i] = cur[l - 1][i] + (cur[l - 1][i] - prev[l - 1][i]) * factor;
      }
      std::swap(prev, cur);
    }
    // prev holds the last row: [k−1] is kept, its distance to [k−2] is the error estimate
    T err(0);
    for (int i = 0; i < n; ++i) {
      const T e = num::abs(prev[kStages - 1][i] - prev[kStages - 2][i]) / (1 + num::abs(y[i]));
      if (!(e <= err)) err = e;  // NaN propagates
    }
    if (!num::finite(err)) {
      run.error = "non-finite state";
      return run;
    }
    T factor =
        err == 0 ? T(4) : T(0.9) * num::sqrt(num::sqrt(num::sqrt(num::sqrt(tol / err))));  // ~ order 16
    if (factor > 4) factor = 4;
    if (factor < T(0.1)) factor = T(0.1);
    if (err <= tol) {
      y = prev[kStages - 1];
      t = last ? end : t + h;
      ++run.steps;
    } else {
      last = false;
    }
    h *= factor;
    if (h < T(1e-14) * (1 + T(t_end))) {
      run.error = "step size underflow";
      return run;
    }
  }
  run.end = body_of(p, y);
  run.end_energy = num::to_double(energy_of_state(p, y));
  run.ok = true;
  return run;
}

}  // namespace

OracleRun run_oracle(const OracleScene& scene, double t_end, double tolerance, Precision precision,
                     long max_steps) {
  if (precision == Precision::big) return integrate<Big>(scene, t_end, tolerance, max_steps);
  return integrate<Quad>(scene, t_end, tolerance, max_steps);
}

Big energy_of(const OracleScene& scene, const Body3& body) {
  Problem<Big> p = make_problem<Big>(scene);
  std::vector<Big> y(18);
  const std::array<Big, 3>* parts[6] = {&body.X, &body.V, &body.e1, &body.e2, &body.W1, &body.W2};
  for (int k = 0; k < 6; ++k)
    for (int i = 0; i < 3; ++i) y[3 * k + i] = (*parts[k])[i];
  if (scene.model == Model::rigid) {
    // the spin of the body as given (s = J_iso Σ ω(e_A, W_A))
    Problem<Big> q = p;
    q.model = Model::affine;
    const V3<Big> e[2] = {body.e1, body.e2}, W[2] = {body.W1, body.W2};
    Big s = 0;
    for (int a = 0; a < 2; ++a) s += p.J_iso * q.omega(body.X, e[a], W[a]);
    p.spin_rigid = s;
    return p.energy(body.X, body.V, e, W);
  }
  return energy_of_state(p, y);
}

namespace {

// ⟨u_i, u_j⟩ (i ≤ j) and ω(u_i, u_j) (i < j) of u = (V, e₁, e₂, W₁, W₂): what is left of the body
// once its place and heading are forgotten.
std::vector<Big> gram(const Problem<Big>& p, const Body3& b) {
  const V3<Big> u[5] = {b.V, b.e1, b.e2, b.W1, b.W2};
  std::vector<Big> g;
  for (int i = 0; i < 5; ++i)
    for (int j = i; j < 5; ++j) {
      g.push_back(p.dot(u[i], u[j]));
      if (j > i) g.push_back(p.omega(b.X, u[i], u[j]));
    }
  return g;
}

// Geodesic distance from the scene's pole of a point in the scene's coordinates.
Big radius_of(const OracleScene& s, const std::array<Big, 3>& X) {
  const Big rho = num::sqrt(X[0] * X[0] + X[1] * X[1]);
  if (s.kind == Kind::plane) return rho;
  if (s.kind == Kind::pseudosphere) return Big(s.R) * num::asinh(rho / Big(s.R));
  return Big(s.R) * boost::multiprecision::atan2(rho, X[2]);
}

std::array<Big, 3> to_global(const OracleScene& s, const Isometry& iso, const std::array<Big, 3>& x) {
  std::array<Big, 3> g;
  for (int i = 0; i < 3; ++i) g[i] = iso.M[i][0] * x[0] + iso.M[i][1] * x[1] + iso.M[i][2] * x[2] + iso.b[i];
  (void)s;
  return g;
}

}  // namespace

Difference compare(const OracleScene& scene, const OracleRun& run, const Body3& e, const Body3& local) {
  Problem<Big> p = make_problem<Big>(scene);
  const Body3& o = run.end;
  Difference d;
  const V3<Big> dX = o.X - e.X;
  const Big chord = num::sqrt(num::abs(p.dot(dX, dX)));
  if (scene.kind == Kind::plane)
    d.position = num::to_double(chord);
  else if (scene.kind == Kind::sphere)
    d.position = num::to_double(2 * p.R * num::asin(std::min(Big(1), chord / (2 * p.R))));
  else
    d.position = num::to_double(2 * p.R * num::asinh(chord / (2 * p.R)));
  const Isometry iso = start_isometry(scene);
  const Big r_o = radius_of(scene, to_global(scene, iso, o.X)),
            r_e = radius_of(scene, to_global(scene, iso, e.X));
  d.radius = num::to_double(num::abs(r_o - r_e));
  auto norm = [&](const V3<Big>& w) { return num::sqrt(num::abs(p.dot(w, w))); };
  auto tangential = [&](const V3<Big>& w) { return norm(p.P(o.X, w)); };
  d.velocity = num::to_double(tangential(o.V - e.V));
  const Big escale = std::max({norm(o.e1), norm(o.e2), Big(1e-300)});
  d.frame = num::to_double(std::max(tangential(o.e1 - e.e1), tangential(o.e2 - e.e2)) / escale);
  const std::vector<Big> go = gram(p, o), ge = gram(p, local);
  Big gscale = 1, gdiff = 0;
  for (std::size_t i = 0; i < go.size(); ++i) gscale = std::max(gscale, num::abs(go[i]));
  for (std::size_t i = 0; i < go.size(); ++i) gdiff = std::max(gdiff, num::abs(go[i] - ge[i]));
  d.invariants = num::to_double(gdiff / gscale);
  // H of the engine's body: kinetic and deformation parts from its own chart, V_r at its place
  Problem<Big> q = p;
  q.radial = false;
  Big He;
  if (scene.model == Model::rigid) {  // the rigid spin is read off the same vectors
    OracleScene plain = scene;
    plain.radial = false;
    He = energy_of(plain, local) + p.radial_potential(e.X, nullptr);
  } else {
    const V3<Big> ee[2] = {local.e1, local.e2}, W[2] = {local.W1, local.W2};
    He = q.energy(local.X, local.V, ee, W) + p.radial_potential(e.X, nullptr);
  }
  d.energy = num::to_double(num::abs(He - run.energy_exact) / Big(std::max(run.energy_scale, 1e-300)));
  if (scene.kind == Kind::pseudosphere) {
    const double c = std::cosh(std::max(num::to_double(r_o), scene.r) / scene.R);
    d.position_floor = 1000 * 2.2e-16 * scene.R * c;
    d.vector_floor = 100 * 2.2e-16 * c * c;
  }
  return d;
}

}  // namespace spinfold::oracle
