#include "engine/initial_rates.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "engine/inertia.h"
#include "engine/number_text.h"
#include "engine/revolution.h"
#include "engine/surface.h"

namespace spinfold {

namespace {

bool finite(double v) {
  return std::isfinite(v);
}

// The chart's poles, where S(r) = 0 and φ, E₂ are undefined: r = 0, and r = πR on the sphere
// (where R sin(r/R) rounds to ~1e-16 R, not 0).
bool at_pole(const Surface& surface, double r) {
  return r == 0.0 || (offers(surface, Offer::positive_curvature) && r == std::numbers::pi * surface.radius);
}

// The start's place as the rates see it: V = f q̇ E₁ + S φ̇ E₂ with q = r (f = 1, S = S(r), C = C(r))
// or, where the curvature varies, q = u (f, S = ρ(u), C = ρ_u/f; physics-surfaces.md §1).
struct StartPlace {
  bool pole;  // S = 0: E₂'s rate φ̇ undefined
  double S, C, f;
  double q, q_dot;         // r or u, and its rate
  const char* q_dot_name;  // "r_dot" or "u_dot"
};
StartPlace start_place(const Scene& scene) {
  const InitialState& q = scene.initial;
  // A formula surface has no chart: the velocity is speed and heading themselves, and the frame's
  // rates are relative to parallel transport (C = 0, physics-anysurface.md §5).
  if (offers(scene.surface, Offer::formula)) return {false, 1.0, 0.0, 1.0, 0.0, 0.0, "speed"};
  if (chart_free(scene.surface)) {
    if (!finite(q.u)) return {false, 0.0, 0.0, 1.0, q.u, q.u_dot, "u_dot"};
    const ProfilePlace p = profile_place(revolution_surface(scene.surface), q.u);
    return {p.axis, p.rho, p.C, p.f, q.u, q.u_dot, "u_dot"};
  }
  if (!finite(q.r)) return {false, 0.0, 0.0, 1.0, q.r, q.r_dot, "r_dot"};
  return {at_pole(scene.surface, q.r),
          polar_S(scene.surface, q.r),
          polar_C(scene.surface, q.r),
          1.0,
          q.r,
          q.r_dot,
          "r_dot"};
}

// sin h is zero up to its rounding at a multiple of π (sin(π) = 1.2e-16 in double).
bool along_E1(double heading) {
  const double eps = std::numeric_limits<double>::epsilon();
  return std::abs(std::sin(heading)) <= 4.0 * eps * std::max(1.0, std::abs(heading));
}

// With anisotropic J the spin s = tr((εL)ᵀMJ) (physics.md §13) is linear in χ = α̇ + Cφ̇:
// s = a χ + b with a = tr(LᵀLJ) and b = tr((εL)ᵀ(U(α)diag(λ̇, μ̇)U(β)ᵀ − β̇Lε)J), because
// M = χεL − β̇Lε + U(α)diag(λ̇, μ̇)U(β)ᵀ and (εL)ᵀεL = LᵀL.
struct SpinLine {
  double a, b;
};
SpinLine spin_line(const InitialState& q, const Mat2& J) {
  const auto rot = [](double t) {
    Mat2 U;
    U << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
    return U;
  };
  Mat2 eps;
  eps << 0.0, -1.0, 1.0, 0.0;
  const Mat2 Ua = rot(q.alpha), Ub = rot(q.beta);
  const Mat2 L = Ua * Eigen::Vector2d(q.lambda, q.mu).asDiagonal() * Ub.transpose();
  const Mat2 rest =
      Ua * Eigen::Vector2d(q.lambda_dot, q.mu_dot).asDiagonal() * Ub.transpose() - q.beta_dot * L * eps;
  return {(L.transpose() * L).cwiseProduct(J).sum(), (eps * L).cwiseProduct(rest * J).sum()};
}

}  // namespace

std::vector<FieldError> resolve_initial_rates(Scene& scene) {
  std::vector<FieldError> errors;
  const InitialState& q = scene.initial;
  const StartPlace place = start_place(scene);
  double q_dot = place.q_dot, phi_dot = q.phi_dot, alpha_dot = q.alpha_dot;

  // Speed and heading: V = v(cos h E₁ + sin h E₂) = f q̇ E₁ + Sφ̇ E₂ (physics.md §1, §3).
  if (q.speed.has_value() != q.heading.has_value()) {
    if (q.speed)
      errors.push_back({"initial.heading", "null",
                        std::string("is missing: speed comes with heading (the angle of the velocity from ") +
                            (chart_free(scene.surface) ? "E1 = X_u/f" : "E1 = d/dr") + " towards E2, rad)"});
    else
      errors.push_back({"initial.speed", "null", "is missing: heading comes with speed (|velocity| >= 0)"});
  } else if (q.speed && finite(*q.speed) && finite(*q.heading) && finite(place.q)) {
    const double v = *q.speed, h = *q.heading;
    const bool pole = place.pole;
    if (pole && v != 0.0 && !along_E1(h)) {
      errors.push_back(
          {"initial.heading", shortest(h),
           chart_free(scene.surface)
               ? "cannot be converted at an axis point (rho(u) = 0, where E2 = X_phi/rho is "
                 "undefined): with speed > 0 give heading 0 or pi, or u_dot and phi_dot, or start "
                 "away from the axis"
               : "cannot be converted at a pole (S(r) = 0, where E2 = (1/S) d/dphi is undefined): "
                 "with speed > 0 give heading 0 or pi, or r_dot and phi_dot, or start away from "
                 "the pole"});
    } else {
      q_dot = v * std::cos(h) / place.f;
      phi_dot = pole ? 0.0 : v * std::sin(h) / place.S;
      if (!finite(q_dot) || !finite(phi_dot))
        errors.push_back({"initial.speed", shortest(v),
                          "gives a rate " + std::string(place.q_dot_name) +
                              " or phi_dot that is not a finite number: use a smaller speed"});
    }
  }

  // Spin: s = J[(λ² + μ²)(α̇ + Cφ̇) − 2λμβ̇] solved for α̇ (physics.md §3), with the φ̇ above.
  const Inertia inertia = inertia_of(scene.body);
  if (q.spin && finite(*q.spin) && finite(inertia.J) && inertia.J > 0.0 && finite(q.lambda) && finite(q.mu) &&
      finite(q.beta_dot) && finite(phi_dot) && finite(place.q)) {
    const double J = inertia.J, l = q.lambda, m = q.mu;
    const double C = place.C;
    if (inertia.isotropic || scene.body.model == BodyModel::rigid) {
      alpha_dot = (*q.spin / J + 2.0 * l * m * q.beta_dot) / (l * l + m * m) - C * phi_dot;
    } else {
      const SpinLine line = spin_line(q, inertia.matrix);
      alpha_dot = (*q.spin - line.b) / line.a - C * phi_dot;
    }
    if (!finite(alpha_dot))
      errors.push_back(
          {"initial.spin", shortest(*q.spin),
           "gives a rate alpha_dot that is not a finite number: use a spin of smaller magnitude"});
  }

  if (!errors.empty()) return errors;
  scene.initial.alpha_dot = alpha_dot;
  if (offers(scene.surface, Offer::formula)) return errors;  // the start reads speed and heading
  (chart_free(scene.surface) ? scene.initial.u_dot : scene.initial.r_dot) = q_dot;
  scene.initial.phi_dot = phi_dot;
  return errors;
}

double spin_of(const Scene& scene) {
  const InitialState& q = scene.initial;
  const double chi = q.alpha_dot + start_place(scene).C * q.phi_dot;  // χ = α̇ + Cφ̇
  const Inertia inertia = inertia_of(scene.body);
  if (!inertia.isotropic && scene.body.model == BodyModel::affine) {
    const SpinLine line = spin_line(q, inertia.matrix);
    return line.a * chi + line.b;
  }
  return inertia.J * ((q.lambda * q.lambda + q.mu * q.mu) * chi - 2.0 * q.lambda * q.mu * q.beta_dot);
}

double speed_of(const Scene& scene) {
  const StartPlace p = start_place(scene);
  return std::hypot(p.f * p.q_dot, p.S * scene.initial.phi_dot);
}

double heading_of(const Scene& scene) {
  const StartPlace p = start_place(scene);
  return std::atan2(p.S * scene.initial.phi_dot, p.f * p.q_dot);
}

}  // namespace spinfold
