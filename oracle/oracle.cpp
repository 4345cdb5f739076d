#include "oracle/oracle.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>
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
// exp (the bump's height) through the 50-digit type: exact to quad's precision, slow, used once per
// field evaluation
inline Quad exp(Quad x) {
  return from_big(boost::multiprecision::exp(to_big(x)));
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
inline Big exp(const Big& x) {
  return boost::multiprecision::exp(x);
}
inline Big atan2(const Big& y, const Big& x) {
  return boost::multiprecision::atan2(y, x);
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
using M3 = std::array<V3<T>, 3>;  // rows

template <class T>
T dot3(const V3<T>& a, const V3<T>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
template <class T>
V3<T> mat_vec(const M3<T>& M, const V3<T>& v) {
  return {dot3(M[0], v), dot3(M[1], v), dot3(M[2], v)};
}

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
  T inertia_rigid;  // rigid: I = 2 J_iso λ₀² (physics-surfaces.md §2)
  T lambda0_sq;     // rigid: λ₀²
  T det_c;          // incompressible: det L
  // where the curvature varies: the surface's parameters, the height potential, friction
  T tube, centre, equatorial, polar, bump_h, bump_w, neck;
  HeightKind height;
  T height_k;  // g (gravity) or k (spring)
  T gamma_t, gamma_i;

  bool implicit() const { return implicit_kind(kind); }
  T eta() const { return kind == Kind::pseudosphere ? T(-1) : T(1); }
  T dot(const V3<T>& a, const V3<T>& b) const { return a[0] * b[0] + a[1] * b[1] + eta() * a[2] * b[2]; }
  // k = 1/⟨X,X⟩ (0 on the plane): the stabilised form of §7
  T kfac(const V3<T>& X) const { return kind == Kind::plane ? T(0) : T(1) / dot(X, X); }

  // ∇F and Hess F of the implicit surfaces (physics-surfaces.md §1's table, written out here).
  V3<T> grad_of(const V3<T>& X) const {
    const T x = X[0], y = X[1], z = X[2];
    switch (kind) {
      case Kind::torus: {
        const T k = 4 * (dot3(X, X) + centre * centre - tube * tube), c8 = 8 * centre * centre;
        return {k * x - c8 * x, k * y - c8 * y, k * z};
      }
      case Kind::spheroid:
        return {2 * x / (equatorial * equatorial), 2 * y / (equatorial * equatorial),
                2 * z / (polar * polar)};
      case Kind::bump: {
        const T G = bump_G(X), w2 = bump_w * bump_w;
        return {x * G / w2, y * G / w2, T(1)};
      }
      case Kind::catenoid: return {2 * x, 2 * y, -neck * num::sinh(2 * z / neck)};
      default: return {T(0), T(0), T(1)};
    }
  }
  M3<T> hess_of(const V3<T>& X) const {
    const T x = X[0], y = X[1], z = X[2], zero(0);
    switch (kind) {
      case Kind::torus: {
        const T k = 4 * (dot3(X, X) + centre * centre - tube * tube), c8 = 8 * centre * centre;
        return {V3<T>{k + 8 * x * x - c8, 8 * x * y, 8 * x * z},
                V3<T>{8 * x * y, k + 8 * y * y - c8, 8 * y * z}, V3<T>{8 * x * z, 8 * y * z, k + 8 * z * z}};
      }
      case Kind::spheroid: {
        const T a2 = 2 / (equatorial * equatorial);
        return {V3<T>{a2, zero, zero}, V3<T>{zero, a2, zero}, V3<T>{zero, zero, 2 / (polar * polar)}};
      }
      case Kind::bump: {
        const T G = bump_G(X), w2 = bump_w * bump_w, w4 = w2 * w2;
        return {V3<T>{G / w2 - x * x * G / w4, -x * y * G / w4, zero},
                V3<T>{-x * y * G / w4, G / w2 - y * y * G / w4, zero}, V3<T>{zero, zero, zero}};
      }
      case Kind::catenoid:
        return {V3<T>{T(2), zero, zero}, V3<T>{zero, T(2), zero},
                V3<T>{zero, zero, -2 * num::cosh(2 * z / neck)}};
      default: return {V3<T>{zero, zero, zero}, V3<T>{zero, zero, zero}, V3<T>{zero, zero, zero}};
    }
  }
  // The last point's ∇F, Hess F and n: a field evaluation asks for them at one X many times (the
  // bump's exp and the catenoid's sinh, cosh go through the 50-digit type).
  struct Geometry {
    V3<T> X, g, n;
    M3<T> H;
    bool valid = false;
  };
  mutable Geometry geometry;
  const Geometry& at(const V3<T>& X) const {
    if (!geometry.valid || geometry.X != X) {
      geometry.X = X;
      geometry.g = grad_of(X);
      geometry.H = hess_of(X);
      geometry.n = (T(1) / num::sqrt(dot3(geometry.g, geometry.g))) * geometry.g;
      geometry.valid = true;
    }
    return geometry;
  }
  V3<T> grad(const V3<T>& X) const { return at(X).g; }
  M3<T> hess(const V3<T>& X) const { return at(X).H; }
  T bump_G(const V3<T>& X) const {
    return bump_h * num::exp(-(X[0] * X[0] + X[1] * X[1]) / (2 * bump_w * bump_w));
  }

  V3<T> normal(const V3<T>& X) const {
    if (implicit()) return at(X).n;
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
  V3<T> P(const V3<T>& X, const V3<T>& w) const {
    if (implicit()) {
      const V3<T> n = normal(X);
      return w - dot3(n, w) * n;
    }
    return w - (kfac(X) * dot(w, X)) * X;
  }
  // The normal part of d(a)/dt for a tangent field a along a path with velocity V (the second
  // fundamental form): k⟨a, V⟩X at constant curvature, (aᵀ Hess F V/|∇F|²) ∇F on an implicit surface.
  V3<T> bend(const V3<T>& X, const V3<T>& a, const V3<T>& V) const {
    if (!implicit()) return (kfac(X) * dot(a, V)) * X;
    const V3<T> gr = grad(X);
    return (dot3(a, mat_vec(hess(X), V)) / dot3(gr, gr)) * gr;
  }
  // Gaussian curvature: constant, or K = gᵀ adj(Hess F) g / |g|⁴ (the bordered Hessian, §1).
  T curvature(const V3<T>& X) const {
    if (!implicit()) return K;
    const V3<T> gr = grad(X);
    const M3<T> H = hess(X);
    const M3<T> adj{V3<T>{H[1][1] * H[2][2] - H[1][2] * H[2][1], H[0][2] * H[2][1] - H[0][1] * H[2][2],
                          H[0][1] * H[1][2] - H[0][2] * H[1][1]},
                    V3<T>{H[1][2] * H[2][0] - H[1][0] * H[2][2], H[0][0] * H[2][2] - H[0][2] * H[2][0],
                          H[0][2] * H[1][0] - H[0][0] * H[1][2]},
                    V3<T>{H[1][0] * H[2][1] - H[1][1] * H[2][0], H[0][1] * H[2][0] - H[0][0] * H[2][1],
                          H[0][0] * H[1][1] - H[0][1] * H[1][0]}};
    const T g2 = dot3(gr, gr);
    return dot3(gr, mat_vec(adj, gr)) / (g2 * g2);
  }
  // §7's shape-operator bracket Π Σ J^{AB}(Dnᵀ W_A ⟨e_B, Dn V⟩ − Dnᵀ e_A ⟨W_B, Dn V⟩), Dn = ΠH/ν,
  // Dnᵀ = HΠ/ν: the spin–curvature force without K or s.
  V3<T> bracket(const V3<T>& X, const V3<T>* e, const V3<T>* W, const V3<T>& V) const {
    const V3<T> gr = grad(X);
    const M3<T> H = hess(X);
    const T nu = num::sqrt(dot3(gr, gr));
    auto Dn = [&](const V3<T>& v) { return (T(1) / nu) * P(X, mat_vec(H, v)); };
    auto DnT = [&](const V3<T>& v) { return (T(1) / nu) * mat_vec(H, P(X, v)); };
    const V3<T> DnV = Dn(V);
    V3<T> sum{T(0), T(0), T(0)};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        sum = sum + J[a * 2 + b] * (dot3(e[b], DnV) * DnT(W[a]) - dot3(W[b], DnV) * DnT(e[a]));
    return P(X, sum);
  }

  // V_h(z) (gravity m g z, spring k z²/2) and its derivative in z.
  T height_potential(const V3<T>& X, T* dVdz) const {
    const T z = X[2];
    if (height == HeightKind::gravity) {
      if (dVdz) *dVdz = m * height_k;
      return m * height_k * z;
    }
    if (height == HeightKind::spring) {
      if (dVdz) *dVdz = height_k * z;
      return height_k * z * z / 2;
    }
    if (dVdz) *dVdz = T(0);
    return T(0);
  }

  // V_r and its gradient (a vector) at X.
  T radial_potential(const V3<T>& X, V3<T>* grad_out) const {
    if (!radial) {
      if (grad_out) *grad_out = {T(0), T(0), T(0)};
      return T(0);
    }
    if (kind == Kind::plane) {
      const V3<T> d = X - O;
      const T rho2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (grad_out) *grad_out = (T(-2) * g / (rho2 * rho2)) * d;
      return g / rho2;
    }
    const Dual<T> u{K * dot(X, O), T(1)};  // u = C(r)
    const Dual<T> one = cst(T(1));
    const Dual<T> V =
        kind == Kind::sphere ? cst(g) / ((one - u) * (one + u)) : cst(g / (R * R)) / ((u - one) * (u + one));
    if (grad_out) *grad_out = (V.d * K) * O;
    return V.v;
  }
  // −∇(V_r + V_h), before the projection.
  V3<T> position_force(const V3<T>& X) const {
    V3<T> gr;
    radial_potential(X, &gr);
    T dVdz;
    height_potential(X, &dVdz);
    gr[2] += dVdz;
    return T(-1) * gr;
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
    T s = 0;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) s += J[b * 2 + a] * omega(X, e[a], W[b]);
    return s;
  }
  // rigid: [X, V, e₁, s, D]; affine: [X, V, e₁, e₂, W₁, W₂, D]; D = ∫2R dt, the energy friction took.
  int size() const { return model == Model::rigid ? 11 : 19; }
  // The rigid body's e₂ = n × e₁ and W_A = (s/I) n × e_A.
  void rigid_frame(const V3<T>& X, const V3<T>& e1, const T& s, V3<T>* e, V3<T>* W) const {
    e[0] = e1, e[1] = jrot(X, e1);
    const T w = s / inertia_rigid;
    W[0] = w * e[1], W[1] = w * jrot(X, e[1]);
  }

  void field(const T* y, T* f) const {
    V3<T> X{y[0], y[1], y[2]}, V{y[3], y[4], y[5]};
    const V3<T> F = P(X, position_force(X) - gamma_t * V);
    auto put = [&](int i, const V3<T>& v) { f[i] = v[0], f[i + 1] = v[1], f[i + 2] = v[2]; };
    put(0, V);
    if (model == Model::rigid) {
      const T s = y[9];
      V3<T> e[2], W[2];
      rigid_frame(X, {y[6], y[7], y[8]}, s, e, W);
      // the orbit: the bracket where the curvature varies (the engine writes K s n × V there)
      const V3<T> spin_force = implicit() ? bracket(X, e, W, V) : (K * s) * jrot(X, V);
      put(3, (T(1) / m) * (spin_force + F) - bend(X, V, V));
      put(6, W[0] - bend(X, e[0], V));
      f[9] = T(-2) * gamma_i * lambda0_sq * s / inertia_rigid;
      f[10] = gamma_t * dot(V, V) + gamma_i * (dot(W[0], W[0]) + dot(W[1], W[1]));
      return;
    }
    const V3<T> e[2] = {{y[6], y[7], y[8]}, {y[9], y[10], y[11]}};
    const V3<T> W[2] = {{y[12], y[13], y[14]}, {y[15], y[16], y[17]}};
    const T s = spin(X, e, W);
    // the orbit: K s n × V, K from the bordered Hessian where the curvature varies (the engine
    // writes §7's bracket there)
    put(3, (T(1) / m) * ((curvature(X) * s) * jrot(X, V) + F) - bend(X, V, V));
    T Va, Vb;
    deformation(X, e[0], e[1], &Va, &Vb);
    const V3<T> je1 = jrot(X, e[0]), je2 = jrot(X, e[1]);
    const V3<T> G[2] = {P(X, Va * (e[0] + je2) + Vb * (e[0] - je2) + gamma_i * W[0]),
                        P(X, Va * (e[1] - je1) + Vb * (e[1] + je1) + gamma_i * W[1])};
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
      put(6 + 3 * a, W[a] - bend(X, e[a], V));
      put(12 + 3 * a, acc[a] - bend(X, W[a], V));
    }
    f[18] = gamma_t * dot(V, V) + gamma_i * (dot(W[0], W[0]) + dot(W[1], W[1]));
  }

  // H (rigid: s is the spin carried by the state; its I from |e₁|²).
  T energy(const V3<T>& X, const V3<T>& V, const V3<T>* e, const V3<T>* W, const T& s_rigid) const {
    T H = m * dot(V, V) / 2 + radial_potential(X, nullptr) + height_potential(X, nullptr);
    if (model == Model::rigid) return H + s_rigid * s_rigid / (4 * J_iso * dot(e[0], e[0]));
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
    const std::pair<const char*, Kind> kinds[] = {
        {"sphere", Kind::sphere},    {"pseudosphere", Kind::pseudosphere}, {"plane", Kind::plane},
        {"torus", Kind::torus},      {"spheroid", Kind::spheroid},         {"bump", Kind::bump},
        {"catenoid", Kind::catenoid}};
    const auto it =
        std::find_if(std::begin(kinds), std::end(kinds), [&](const auto& k) { return kind == k.first; });
    if (it == std::end(kinds)) throw std::runtime_error("surface.kind: unknown '" + kind + "'");
    s.kind = it->second;
    s.R = number(surface, "radius", 1.0, "surface");
    s.tube_radius = number(surface, "tube_radius", s.tube_radius, "surface");
    s.center_radius = number(surface, "center_radius", s.center_radius, "surface");
    s.equatorial_radius = number(surface, "equatorial_radius", s.equatorial_radius, "surface");
    s.polar_radius = number(surface, "polar_radius", s.polar_radius, "surface");
    s.bump_height = number(surface, "height", s.bump_height, "surface");
    s.bump_width = number(surface, "width", s.bump_width, "surface");
    s.neck_radius = number(surface, "neck_radius", s.neck_radius, "surface");
  }
  const json& friction = block(j, "friction");
  s.friction_t = number(friction, "translational", 0.0, "friction");
  s.friction_i = number(friction, "internal", 0.0, "friction");
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
  if (const auto it = potential.find("height"); it != potential.end() && it->is_object()) {
    const std::string kind = it->value("kind", std::string());
    if (kind == "gravity") {
      s.height = HeightKind::gravity;
      s.height_coefficient = number(*it, "g", 0, "potential.height");
    } else if (kind == "spring") {
      s.height = HeightKind::spring;
      s.height_coefficient = number(*it, "k", 0, "potential.height");
    } else {
      throw std::runtime_error("potential.height.kind: unknown '" + kind + "'");
    }
  }
  const json& q = block(j, "initial");
  const std::string p = "initial";
  s.r = number(q, "r", 1.0, p), s.phi = number(q, "phi", 0.0, p);
  s.u = number(q, "u", 0.0, p), s.u_dot = number(q, "u_dot", 0.0, p);
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
  if (implicit_kind(s.kind)) {  // the scene's own frame
    iso.M = {{{Big(1), Big(0), Big(0)}, {Big(0), Big(1), Big(0)}, {Big(0), Big(0), Big(1)}}};
    return iso;
  }
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
  p.K = s.kind == Kind::plane || implicit_kind(s.kind)
            ? T(0)
            : (s.kind == Kind::sphere ? T(1) : T(-1)) / (p.R * p.R);
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
  p.lambda0_sq = T(s.lambda) * T(s.lambda);
  p.inertia_rigid = 2 * p.J_iso * p.lambda0_sq;
  p.tube = T(s.tube_radius), p.centre = T(s.center_radius);
  p.equatorial = T(s.equatorial_radius), p.polar = T(s.polar_radius);
  p.bump_h = T(s.bump_height), p.bump_w = T(s.bump_width), p.neck = T(s.neck_radius);
  p.height = s.height;
  p.height_k = T(s.height_coefficient);
  p.gamma_t = T(s.friction_t), p.gamma_i = T(s.friction_i);
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

// Where the curvature varies: the point (u, φ) of the profile (physics-surfaces.md §1's table, written
// out here) and |X_u| = f. The frame is then taken from the normal: E₂ = (−sin φ, cos φ, 0),
// E₁ = E₂ × n (n = E₁ × E₂ = ∇F/|∇F|), and C = ρ_u/f = n_z.
template <class T>
struct ProfileAt {
  T rho, z, f;
};
template <class T>
ProfileAt<T> profile_at(const OracleScene& s, const T& u) {
  switch (s.kind) {
    case Kind::torus: {
      const T a(s.tube_radius), c(s.center_radius);
      return {c + a * num::cos(u), -a * num::sin(u), a};
    }
    case Kind::spheroid: {
      const T a(s.equatorial_radius), b(s.polar_radius), ca = a * num::cos(u), sb = b * num::sin(u);
      return {a * num::sin(u), b * num::cos(u), num::sqrt(ca * ca + sb * sb)};
    }
    case Kind::bump: {
      const T h(s.bump_height), w(s.bump_width);
      const T z = h * num::exp(-u * u / (2 * w * w)), z_u = -u * z / (w * w);
      return {u, z, num::sqrt(1 + z_u * z_u)};
    }
    default: {  // catenoid
      const T c(s.neck_radius);
      return {c * num::cosh(u / c), -u, num::cosh(u / c)};
    }
  }
}

// The scene's initial values (physics.md §1–§3, §13; spin, speed, heading as the scene format
// defines them) as a state vector in the start frame, where E₁ = x̂, E₂ = ŷ at X₀ (constant
// curvature), or in the scene's frame (where the curvature varies).
template <class T>
std::vector<T> start_state(const OracleScene& s, Problem<T>& p) {
  const T r(s.r), R(s.R);
  T S, C, f(1), q_dot(s.r_dot);
  V3<T> X0, E1{T(1), T(0), T(0)}, E2{T(0), T(1), T(0)};
  if (implicit_kind(s.kind)) {
    const T u(s.u), phi(s.phi);
    const ProfileAt<T> at = profile_at(s, u);
    X0 = {at.rho * num::cos(phi), at.rho * num::sin(phi), at.z};
    E2 = {-num::sin(phi), num::cos(phi), T(0)};
    const V3<T> n = p.normal(X0);
    E1 = cross(E2, n);
    S = at.rho, C = n[2], f = at.f, q_dot = T(s.u_dot);
  } else {
    if (s.kind == Kind::plane)
      S = r, C = T(1);
    else if (s.kind == Kind::sphere)
      S = R * num::sin(r / R), C = num::cos(r / R);
    else
      S = R * num::sinh(r / R), C = num::cosh(r / R);
    X0 = s.kind == Kind::plane ? V3<T>{T(0), T(0), T(0)} : V3<T>{T(0), T(0), R};
  }
  // velocity: V = f q̇ E₁ + Sφ̇ E₂, or v(cos h E₁ + sin h E₂)
  T vr = f * q_dot, vphi = S * T(s.phi_dot), phi_dot = T(s.phi_dot);
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
  std::vector<T> y(p.size(), T(0));
  auto put = [&](int i, const V3<T>& v) { y[i] = v[0], y[i + 1] = v[1], y[i + 2] = v[2]; };
  put(0, X0);
  put(3, V);
  if (s.model == Model::rigid) {
    // s = I(α̇ − β̇ + Cφ̇), I = 2Jλ₀² with J = tr J/2 (§8.8, §13)
    const T w = s.spin ? T(*s.spin) / p.inertia_rigid : T(s.alpha_dot) - T(s.beta_dot) + C * phi_dot;
    put(6, L[0] * E1 + L[2] * E2);
    y[9] = p.inertia_rigid * w;
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

// The body's six vectors and, for the rigid body, its spin.
template <class T>
struct Vectors {
  V3<T> X, V, e[2], W[2];
  T s{0};
};
template <class T>
Vectors<T> vectors_of(const Problem<T>& p, const std::vector<T>& y) {
  Vectors<T> v;
  v.X = {y[0], y[1], y[2]}, v.V = {y[3], y[4], y[5]};
  if (p.model == Model::rigid) {
    v.s = y[9];
    p.rigid_frame(v.X, {y[6], y[7], y[8]}, v.s, v.e, v.W);
  } else {
    v.e[0] = {y[6], y[7], y[8]}, v.e[1] = {y[9], y[10], y[11]};
    v.W[0] = {y[12], y[13], y[14]}, v.W[1] = {y[15], y[16], y[17]};
  }
  return v;
}

template <class T>
Body3 body_of(const Problem<T>& p, const std::vector<T>& y) {
  const Vectors<T> v = vectors_of(p, y);
  auto big3 = [](const V3<T>& w) {
    return std::array<Big, 3>{num::big(w[0]), num::big(w[1]), num::big(w[2])};
  };
  Body3 b;
  b.X = big3(v.X), b.V = big3(v.V), b.e1 = big3(v.e[0]), b.e2 = big3(v.e[1]);
  b.W1 = big3(v.W[0]), b.W2 = big3(v.W[1]);
  return b;
}

template <class T>
T energy_of_state(const Problem<T>& p, const std::vector<T>& y) {
  const Vectors<T> v = vectors_of(p, y);
  return p.energy(v.X, v.V, v.e, v.W, v.s);
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
    T pot = q.radial_potential(X, nullptr) + q.height_potential(X, nullptr);
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
  const T H1 = energy_of_state(p, y);
  run.end_energy = num::to_double(H1);
  run.end_energy_exact = num::big(H1);
  run.dissipated = num::to_double(y[n - 1]);
  run.balance = num::to_double(num::abs(H1 + y[n - 1] - H0)) / std::max(run.energy_scale, 1e-300);
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
  const Problem<Big> p = make_problem<Big>(scene);
  const V3<Big> e[2] = {body.e1, body.e2}, W[2] = {body.W1, body.W2};
  // the rigid body's spin as the vectors carry it (s = J_iso Σ ω(e_A, W_A))
  Big s = 0;
  for (int a = 0; a < 2; ++a) s += p.J_iso * p.omega(body.X, e[a], W[a]);
  return p.energy(body.X, body.V, e, W, s);
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
  if (s.kind == Kind::plane || implicit_kind(s.kind)) return rho;  // (varying: from the axis)
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
  if (scene.kind == Kind::plane || implicit_kind(scene.kind))  // (the chord: the differences are small)
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
  // H of the engine's body: kinetic, deformation and height parts from its own chart (where the
  // curvature varies, the scene's frame), V_r at its place; the rigid spin read off the same vectors
  Problem<Big> q = p;
  q.radial = false;
  const V3<Big> ee[2] = {local.e1, local.e2}, W[2] = {local.W1, local.W2};
  Big s = 0;
  for (int a = 0; a < 2; ++a) s += p.J_iso * p.omega(local.X, ee[a], W[a]);
  const Big He = q.energy(local.X, local.V, ee, W, s) + p.radial_potential(e.X, nullptr);
  // against H(T) of the oracle (H(0) without friction, to its drift of ~1e-25)
  d.energy = num::to_double(num::abs(He - run.end_energy_exact) / Big(std::max(run.energy_scale, 1e-300)));
  if (scene.kind == Kind::pseudosphere) {
    const double c = std::cosh(std::max(num::to_double(r_o), scene.r) / scene.R);
    d.position_floor = 1000 * 2.2e-16 * scene.R * c;
    d.vector_floor = 100 * 2.2e-16 * c * c;
  }
  return d;
}

}  // namespace spinfold::oracle
