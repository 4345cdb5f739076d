// The equations the oracle integrates, in its start frame (oracle/oracle.h): physics.md §7's
// embedding equations on S², H² and the plane, physics-surfaces.md §7 on an implicit surface, with
// the potentials, friction and the energy. Header-only: the problem is a template over the scalar.
#pragma once

#include <array>
#include <vector>

#include "oracle/formula.h"
#include "oracle/oracle.h"
#include "oracle/scalars.h"

namespace spinfold::oracle {

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

  // a formula surface (Kind::formula): its reader's F (or f, F = z − f for a graph)
  const OracleFormula* formula = nullptr;
  bool graph = false;

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
  // A formula's ∇F and Hess F in 50 digits (hyper-dual numbers, oracle/formula.h), in T.
  void formula_at(const V3<T>& X, V3<T>& gradient, M3<T>& H) const {
    const FormulaValue f = formula->at({num::big(X[0]), num::big(X[1]), num::big(X[2])});
    const T sign = graph ? T(-1) : T(1);  // a graph's F = z − f: ∇F = ẑ − ∇f, Hess F = −Hess f
    for (int i = 0; i < 3; ++i) {
      gradient[i] = sign * num::convert<T>(f.gradient[i]);
      for (int k = 0; k < 3; ++k) H[i][k] = sign * num::convert<T>(f.hessian[i][k]);
    }
    if (graph) gradient[2] = T(1);
  }
  const Geometry& at(const V3<T>& X) const {
    if (!geometry.valid || geometry.X != X) {
      geometry.X = X;
      if (kind == Kind::formula) {
        formula_at(X, geometry.g, geometry.H);
      } else {
        geometry.g = grad_of(X);
        geometry.H = hess_of(X);
      }
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

}  // namespace spinfold::oracle
