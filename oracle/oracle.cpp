// The oracle's run (oracle/oracle.h): the start state in the start frame, the Gragg–Bulirsch–Stoer
// integration, the energy and the comparison with an engine state. The equations are
// oracle/equations.h, the scalars oracle/scalars.h, the scene's reading oracle/scene_reading.cpp.
#include "oracle/oracle.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>
#include <vector>

#include "oracle/equations.h"
#include "oracle/formula.h"
#include "oracle/scalars.h"

namespace spinfold::oracle {

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
  p.formula = s.formula.get();
  p.graph = s.graph;
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

// A formula surface's start (physics-anysurface.md §6), the oracle's own way: a graph's (x, y, f(x, y));
// otherwise Newton along ∇F from initial.X, in T, to the last digits (at most 60 steps).
template <class T>
V3<T> formula_foot(const OracleScene& s) {
  const auto F_at = [&](const V3<T>& X, V3<T>& g) {
    const FormulaValue v = s.formula->at({num::big(X[0]), num::big(X[1]), num::big(X[2])});
    for (int i = 0; i < 3; ++i) g[i] = num::convert<T>(v.gradient[i]);
    return num::convert<T>(v.F);
  };
  V3<T> X{T(s.X[0]), T(s.X[1]), T(s.X[2])};
  V3<T> g;
  if (s.graph) {
    X[2] = F_at(X, g);
    return X;
  }
  for (int k = 0; k < 60; ++k) {
    const T F = F_at(X, g), g2 = dot3(g, g);
    const V3<T> step = (F / g2) * g;
    X = X - step;
    if (num::abs(F) <= T(1e-30) * num::sqrt(g2)) break;
  }
  return X;
}

// The scene's initial values (physics.md §1–§3, §13; spin, speed, heading as the scene format
// defines them) as a state vector in the start frame, where E₁ = x̂, E₂ = ŷ at X₀ (constant
// curvature), or in the scene's frame (where the curvature varies).
template <class T>
std::vector<T> start_state(const OracleScene& s, Problem<T>& p) {
  const T r(s.r), R(s.R);
  T S, C, f(1), q_dot(s.r_dot);
  V3<T> X0, E1{T(1), T(0), T(0)}, E2{T(0), T(1), T(0)};
  if (s.kind == Kind::formula) {
    // §5's convention: E₁ the x-axis's tangential part normalised (the y-axis's where that is
    // shorter than 0.1), E₂ = n × E₁; no chart (S = 1, C = 0: the rates are relative to transport).
    X0 = formula_foot<T>(s);
    const V3<T> n = p.normal(X0);
    V3<T> t = V3<T>{T(1), T(0), T(0)} - n[0] * n;
    if (num::sqrt(dot3(t, t)) < T(0.1)) t = V3<T>{T(0), T(1), T(0)} - n[1] * n;
    E1 = (T(1) / num::sqrt(dot3(t, t))) * t;
    E2 = cross(n, E1);
    S = T(1), C = T(0), q_dot = T(0);
  } else if (implicit_kind(s.kind)) {
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
