#include "engine/chart.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "engine/dynamics.h"
#include "engine/embedded_run.h"
#include "engine/inertia.h"

namespace spinfold {

Mat2 rotation2(double psi) {
  Mat2 U;
  U << std::cos(psi), -std::sin(psi), std::sin(psi), std::cos(psi);
  return U;
}

Mat3 inverse_linear(const Surface& surface, const Mat3& A) {
  if (!offers(surface, Offer::negative_curvature)) return A.transpose();
  const Eigen::DiagonalMatrix<double, 3> eta(1.0, 1.0, -1.0);
  return eta * A.transpose() * eta;
}

BodyKinematics chart_kinematics(const Scene& scene, const Coords& y) {
  const Surface& surface = scene.surface;
  const double m = scene.body.mass, r = y[coord::r];
  const double S = polar_S(surface, r), C = polar_C(surface, r);
  const ChartPoint p = chart_point(surface, r, y[coord::phi]);
  const InternalState in = internal_state(scene, y);
  const double s = spin_of(scene, y);
  const double S_phi_dot = (y[coord::p_phi] - C * s) / (m * S);  // S φ̇ = Π/(mS)
  return {p.X, (y[coord::p_r] / m) * p.E1 + S_phi_dot * p.E2, p.E1, in.L, in.M, s};
}

Coords chart_coords(const Scene& scene, const BodyKinematics& body) {
  const Surface& surface = scene.surface;
  const double m = scene.body.mass;
  const PolarCoordinates pc = polar_coordinates(surface, body.X);
  const ChartPoint p = chart_point(surface, pc.r, pc.phi);
  // F₁ = cos ψ E₁ + sin ψ E₂ ⇒ components in (E₁, E₂) are U(ψ) times those in (F₁, F₂).
  const double psi = std::atan2(dot(surface, body.F1, p.E2), dot(surface, body.F1, p.E1));
  const Mat2 U = rotation2(psi);
  const Mat2 L = U * body.L, M = U * body.M;
  const double S = polar_S(surface, pc.r), C = polar_C(surface, pc.r);

  Coords y;
  if (scene.body.model == BodyModel::rigid) {
    y.resize(coord::rigid_size);
    y[coord::theta] = std::atan2(L(1, 0), L(0, 0));
    y[coord::spin] = body.spin;
  } else {
    y.resize(coord::affine_size);
    const Mat2 P = momentum_from_rate(inertia_of(scene.body), M);  // P = MJ (physics.md §13)
    y.segment<4>(coord::L) << L(0, 0), L(0, 1), L(1, 0), L(1, 1);
    y.segment<4>(coord::P) << P(0, 0), P(0, 1), P(1, 0), P(1, 1);
  }
  y[coord::r] = pc.r;
  y[coord::phi] = pc.phi;
  y[coord::p_r] = m * dot(surface, body.V, p.E1);
  y[coord::p_phi] = m * S * dot(surface, body.V, p.E2) + C * spin_of(scene, y);
  return y;
}

BodyKinematics initial_kinematics(const Scene& scene) {
  const Surface& surface = scene.surface;
  const InitialState& q = scene.initial;
  const ChartPoint p = chart_point(surface, q.r, q.phi);
  const double S = polar_S(surface, q.r), C = polar_C(surface, q.r);
  const Mat2 Ua = rotation2(q.alpha), Ub = rotation2(q.beta), eps = epsilon();
  const Mat2 L = Ua * Eigen::Vector2d(q.lambda, q.mu).asDiagonal() * Ub.transpose();
  // L̇ = α̇εL − β̇Lε + U(α) diag(λ̇, μ̇) U(β)ᵀ; M = L̇ + Cφ̇εL (physics.md §3).
  const Mat2 L_dot = q.alpha_dot * eps * L - q.beta_dot * L * eps +
                     Ua * Eigen::Vector2d(q.lambda_dot, q.mu_dot).asDiagonal() * Ub.transpose();
  const Mat2 M = L_dot + C * q.phi_dot * eps * L;
  const double spin = spin_from_rate(inertia_of(scene.body), L, M);  // s = tr((εL)ᵀMJ)
  return {p.X, q.r_dot * p.E1 + S * q.phi_dot * p.E2, p.E1, L, M, spin};
}

namespace {

// The length that the chart bands are measured in: R, but at most kMaxChartScale on a nearly flat
// sphere or H² (a small curvature dialled towards 0), whose polar charts would otherwise put the pole
// ~R away and leave the body's motion to the last digits of coordinates of size R. The plane's
// radius is its scale.
constexpr double kMaxChartScale = 100.0;  // [length]
double chart_scale(const Surface& surface) {
  return offers(surface, Offer::zero_curvature) ? surface.radius : std::min(surface.radius, kMaxChartScale);
}

// Bounds of |S(r)|/ℓ (away from the pole, and on S² from its antipode) and of r/ℓ, ℓ the chart scale.
struct Band {
  double low, high;
};

bool in_band(const Surface& surface, double r, Band band) {
  const double R = surface.radius, l = chart_scale(surface), x = r / R;
  if (l != R) {  // a nearly flat S² or H²: as on the plane, and clear of S²'s antipode
    const bool clear = !offers(surface, Offer::positive_curvature) ||
                       (x > 0.0 && x < std::numbers::pi && R * std::sin(x) >= band.low * l);
    return clear && r >= band.low * l && r <= band.high * l;
  }
  if (offers(surface, Offer::positive_curvature))
    return x > 0.0 && x < std::numbers::pi && std::sin(x) >= band.low;
  return x >= band.low && x <= band.high;
}

}  // namespace

bool chart_well_conditioned(const Surface& surface, double r) {
  return in_band(surface, r, {0.3, 4.0});
}

bool chart_comfortable(const Surface& surface, double r) {
  return in_band(surface, r, {0.5, 3.0});
}

namespace {

// Distance of the body from a new chart's pole: the middle of the well-conditioned band.
double recentre_distance(const Surface& surface) {
  const double l = chart_scale(surface);
  return offers(surface, Offer::positive_curvature) && l == surface.radius ? 0.5 * std::numbers::pi * l : l;
}

}  // namespace

void recentre(const Scene& scene, const BodyKinematics& body, Chart& chart, Coords& y) {
  const Surface& surface = scene.surface;
  const double K = curvature(surface);
  const Vec3& X = body.X;
  // The new pole lies at distance d₀ from the body along −u, u ⟂ velocity, on the convex side of
  // the spin–curvature bending (κ_g ∝ Ks, physics.md §8.5) so the body stays far from it.
  const double speed = std::sqrt(std::max(0.0, dot(surface, body.V, body.V)));
  Vec3 u = body.F1;
  if (speed > 0.0) u = rotate_quarter(surface, X, body.V) * ((K * body.spin >= 0.0 ? 1.0 : -1.0) / speed);

  const double d0 = recentre_distance(surface);
  const double Sd = polar_S(surface, d0), Cd = polar_C(surface, d0);
  Vec3 pole, a1, b_rel = Vec3::Zero();
  if (offers(surface, Offer::zero_curvature)) {
    pole = X - d0 * u;
    a1 = u;
    b_rel = pole;
  } else {
    pole = Cd * X - Sd * u;    // exp_X(−d₀u)
    a1 = K * Sd * X + Cd * u;  // unit tangent at the pole, pointing at the body
  }
  Mat3 A_rel;
  A_rel.col(0) = a1;
  A_rel.col(1) = rotate_quarter(surface, pole, a1);
  A_rel.col(2) = unit_normal(surface, pole);
  const Mat3 A_inv = inverse_linear(surface, A_rel);

  const BodyKinematics moved{A_inv * (X - b_rel), A_inv * body.V, A_inv * body.F1, body.L, body.M, body.spin};
  y = chart_coords(scene, moved);
  chart.b = chart.A * b_rel + chart.b;
  chart.A = chart.A * A_rel;
  chart.global = false;
}

void recentre(const Scene& scene, State& state) {
  recentre(scene, chart_kinematics(scene, state.y), state.chart, state.y);
}

bool maintain_chart(const Scene& scene, State& state) {
  const bool leave = !chart_well_conditioned(scene.surface, state.y[coord::r]);
  if (state.chart.global && !leave) return false;
  const BodyKinematics body = chart_kinematics(scene, state.y);
  const Chart& chart = state.chart;
  const BodyKinematics global{
      chart.A * body.X + chart.b, chart.A * body.V, chart.A * body.F1, body.L, body.M, body.spin};
  if (!state.chart.global && chart_comfortable(scene.surface, polar_coordinates(scene.surface, global.X).r)) {
    state.chart = Chart{};
    state.y = chart_coords(scene, global);
    return true;
  }
  if (!leave) return false;
  recentre(scene, body, state.chart, state.y);
  return true;
}

double embedded_state_error(const Scene& scene, const State& a, const State& b) {
  const EmbeddedBody x = global_embedding(scene, a), y = global_embedding(scene, b);
  double e = 0.0;
  for (const auto& [u, v] : {std::pair{x.X, y.X},
                             {x.V, y.V},
                             {x.e[0], y.e[0]},
                             {x.e[1], y.e[1]},
                             {x.W[0], y.W[0]},
                             {x.W[1], y.W[1]}}) {
    const Vec3 d = u - v;
    // maxCoeff and std::max both pass over a NaN: a state gone NaN would read as no error at all.
    if (!d.allFinite()) return std::numeric_limits<double>::infinity();
    e = std::max(e, d.cwiseAbs().maxCoeff() / std::max(1.0, v.norm()));
  }
  return std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
}

EmbeddedBody global_embedding(const Scene& scene, const State& state) {
  if (chart_free(scene.surface)) return embedded_body(EmbeddedScene(scene), state.y);
  const BodyKinematics body = chart_kinematics(scene, state.y);
  const Mat3& A = state.chart.A;
  const Vec3 F2 = rotate_quarter(scene.surface, body.X, body.F1);
  EmbeddedBody out;
  out.X = A * body.X + state.chart.b;
  out.V = A * body.V;
  for (int a = 0; a < 2; ++a) {
    out.e[a] = A * (body.F1 * body.L(0, a) + F2 * body.L(1, a));
    out.W[a] = A * (body.F1 * body.M(0, a) + F2 * body.M(1, a));
  }
  return out;
}

State place_body(const Scene& scene, const PlacedBody& p) {
  State state;
  const Surface& surface = scene.surface;
  if (offers(surface, Offer::negative_curvature) && p.r > recentre_distance(surface) &&
      !chart_well_conditioned(surface, p.r)) {
    // Far out on H² the global embedding is ~R e^{r/R}/2 and ⟨X, X⟩ = −R² drowns in its round-off
    // (from r ≈ 8R on), so a chart is not built from X: first a chart whose pole lies on the
    // body's radial geodesic at distance d₀ before it (an isometry along that geodesic: E₁, E₂
    // and so L, M keep their meaning), then the usual re-centring from there.
    const double d0 = recentre_distance(surface);
    const ChartPoint pole = chart_point(surface, p.r - d0, p.phi);
    const ChartPoint here = chart_point(surface, d0, 0.0);
    state.chart.A.col(0) = pole.E1;
    state.chart.A.col(1) = pole.E2;
    state.chart.A.col(2) = unit_normal(surface, pole.X);
    state.chart.global = false;
    const BodyKinematics radial{here.X, p.v_r * here.E1 + p.v_phi * here.E2, here.E1, p.L, p.M, p.spin};
    recentre(scene, radial, state.chart, state.y);
    return state;
  }
  const ChartPoint here = chart_point(surface, p.r, p.phi);
  const BodyKinematics body{here.X, p.v_r * here.E1 + p.v_phi * here.E2, here.E1, p.L, p.M, p.spin};
  if (!chart_well_conditioned(surface, p.r))
    recentre(scene, body, state.chart, state.y);
  else
    state.y = chart_coords(scene, body);
  return state;
}

State initial_state(const Scene& scene) {
  const InitialState& q = scene.initial;
  if (chart_free(scene.surface)) {  // the chart-free state (engine/embedded_run.h)
    State state;
    state.y = embedded_start(EmbeddedScene(scene), q);
    return state;
  }
  if (!chart_well_conditioned(scene.surface, q.r)) {
    const BodyKinematics body = initial_kinematics(scene);
    const double v_phi = polar_S(scene.surface, q.r) * q.phi_dot;
    return place_body(scene, {q.r, q.phi, q.r_dot, v_phi, body.L, body.M, body.spin});
  }
  State state;
  const BodyKinematics body = initial_kinematics(scene);
  // The scene's own chart: canonical values straight from the initial ones (physics.md §3).
  const double m = scene.body.mass;
  const double S = polar_S(scene.surface, q.r), C = polar_C(scene.surface, q.r);
  Coords& y = state.y;
  if (scene.body.model == BodyModel::rigid) {
    y.resize(coord::rigid_size);
    y[coord::theta] = q.alpha - q.beta;
    y[coord::spin] = body.spin;
  } else {
    y.resize(coord::affine_size);
    const Mat2 P = momentum_from_rate(inertia_of(scene.body), body.M);
    y.segment<4>(coord::L) << body.L(0, 0), body.L(0, 1), body.L(1, 0), body.L(1, 1);
    y.segment<4>(coord::P) << P(0, 0), P(0, 1), P(1, 0), P(1, 1);
  }
  y[coord::r] = q.r;
  y[coord::phi] = q.phi;
  y[coord::p_r] = m * q.r_dot;
  y[coord::p_phi] = m * S * S * q.phi_dot + C * spin_of(scene, y);
  return state;
}

}  // namespace spinfold
