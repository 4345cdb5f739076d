#include "engine/exact_solution.h"

#include <cmath>
#include <numbers>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/integrator.h"

namespace spinfold {

const IntegratorInfo exact_info{
    "exact", 0, true, false, true, "closed form of the separable scenes (no radial potential; abc or none)"};

namespace {

using Vec2 = Eigen::Vector2d;
constexpr double kPi = std::numbers::pi;

// s(t) = |w(t)|² and ṡ(t): s̈ = 2E/J − (8C/J)s (harmonic, hyperbolic or quadratic in t).
std::pair<double, double> squared_radius_at(const PlaneMotion& m, double t) {
  const double J = m.J, C = m.C;
  if (C == 0.0) {
    const double a = m.energy / J;
    return {m.s0 + m.s_dot0 * t + a * t * t, m.s_dot0 + 2.0 * a * t};
  }
  const double c = m.energy / (4.0 * C), a = m.s0 - c;
  if (C > 0.0) {
    const double w = std::sqrt(8.0 * C / J), cs = std::cos(w * t), sn = std::sin(w * t);
    return {c + a * cs + (m.s_dot0 / w) * sn, -a * w * sn + m.s_dot0 * cs};
  }
  const double w = std::sqrt(-8.0 * C / J), ch = std::cosh(w * t), sh = std::sinh(w * t);
  return {c + a * ch + (m.s_dot0 / w) * sh, a * w * sh + m.s_dot0 * ch};
}

// ∫₀ᵗ dt′/s(t′), continuous in t (physics.md §8.4). The smallest value of s comes from the product
// of the turning points s₊s₋ = (ℓ²/J + 2A)/(8C), never from a difference that would cancel.
double inverse_squared_radius_integral(const PlaneMotion& m, double t) {
  const double J = m.J, C = m.C;
  const double q = m.ell * m.ell / J + 2.0 * m.A;  // > 0
  if (C > 0.0) {
    const double w = std::sqrt(8.0 * C / J), c = m.energy / (4.0 * C);
    const double a = m.s0 - c, b = m.s_dot0 / w;
    const double rho = std::hypot(a, b), theta0 = std::atan2(b, a);
    const double root = std::sqrt(q / (8.0 * C));  // √(c² − ρ²)
    const double s_max = c + rho, s_min = root * root / s_max;
    const auto F = [&](double th) {
      return (2.0 / root) *
             (std::atan2(std::sqrt(s_min) * std::sin(0.5 * th), std::sqrt(s_max) * std::cos(0.5 * th)) +
              2.0 * kPi * std::round(th / (4.0 * kPi)));
    };
    return (F(w * t - theta0) - F(-theta0)) / w;
  }
  if (C < 0.0) {
    // s = c + ρ cosh(Ωt + τ) with c² − ρ² = q/(8C) < 0: the arctan branch of §8.4 (ii).
    const double w = std::sqrt(-8.0 * C / J), c = m.energy / (4.0 * C);
    const double a = m.s0 - c, b = m.s_dot0 / w;
    const double rho = std::sqrt((a - b) * (a + b)), tau = std::atanh(b / a);
    const double root = std::sqrt(-q / (8.0 * C));  // √(ρ² − c²)
    const double ratio = root / (rho + c);          // √((ρ − c)/(ρ + c))
    const auto H = [&](double th) { return (2.0 / root) * std::atan(ratio * std::tanh(0.5 * th)); };
    return (H(w * t + tau) - H(tau)) / w;
  }
  // s = s₀ + ṡ₀t + (E/J)t², discriminant 4ac − b² = q/J (§8.4 (iii)).
  const double a = m.energy / J, root = std::sqrt(q / J);
  return (2.0 / root) * (std::atan((2.0 * a * t + m.s_dot0) / root) - std::atan(m.s_dot0 / root));
}

// exp(tA), A w = η((ηM) × w)/(mR²): the orbit's isometry flow (physics.md §8.6), A³ = −cA.
Mat3 orbital_isometry(const Surface& surface, const Vec3& M, double m, double t) {
  const double R = surface.radius;
  const Vec3 etaM = raise(surface, M);
  Mat3 A;
  for (int i = 0; i < 3; ++i) A.col(i) = raise(surface, etaM.cross(Vec3::Unit(i))) / (m * R * R);
  const double c = -0.5 * (A * A).trace();
  const Mat3 A2 = A * A;
  if (c > 0.0) {
    const double k = std::sqrt(c);
    return Mat3::Identity() + (std::sin(k * t) / k) * A + (2.0 * std::pow(std::sin(0.5 * k * t), 2) / c) * A2;
  }
  if (c < 0.0) {
    const double k = std::sqrt(-c);
    return Mat3::Identity() + (std::sinh(k * t) / k) * A +
           (2.0 * std::pow(std::sinh(0.5 * k * t), 2) / -c) * A2;
  }
  return Mat3::Identity() + t * A + (0.5 * t * t) * A2;
}

// L from its anticonformal (u, v) and conformal (p, q) parts (physics.md §2).
Mat2 assemble(const Vec2& uv, const Vec2& pq) {
  Mat2 L;
  L << pq.x() + uv.x(), uv.y() - pq.y(), uv.y() + pq.y(), pq.x() - uv.x();
  return L;
}

}  // namespace

PlaneMotion plane_motion(double J, double A, double C, const Vec2& w0, const Vec2& w_dot0) {
  PlaneMotion m;
  m.J = J;
  m.A = A;
  m.C = C;
  m.w0 = w0;
  m.w_dot0 = w_dot0;
  m.s0 = w0.squaredNorm();
  m.s_dot0 = 2.0 * w0.dot(w_dot0);
  m.psi0 = std::atan2(w0.y(), w0.x());
  m.ell = 2.0 * J * (w0.x() * w_dot0.y() - w0.y() * w_dot0.x());
  m.energy = J * w_dot0.squaredNorm() + 2.0 * C * m.s0 + (A != 0.0 ? A / (2.0 * m.s0) : 0.0);
  return m;
}

std::pair<Vec2, Vec2> plane_motion_at(const PlaneMotion& m, double t) {
  if (m.A == 0.0) {
    // ẅ = −(2C/J) w: a linear oscillator in each component, regular through w = 0.
    const double k = 2.0 * m.C / m.J;
    if (k > 0.0) {
      const double w = std::sqrt(k), cs = std::cos(w * t), sn = std::sin(w * t);
      return {m.w0 * cs + m.w_dot0 * (sn / w), -m.w0 * (w * sn) + m.w_dot0 * cs};
    }
    if (k < 0.0) {
      const double w = std::sqrt(-k), ch = std::cosh(w * t), sh = std::sinh(w * t);
      return {m.w0 * ch + m.w_dot0 * (sh / w), m.w0 * (w * sh) + m.w_dot0 * ch};
    }
    return {m.w0 + m.w_dot0 * t, m.w_dot0};
  }
  const auto [s, s_dot] = squared_radius_at(m, t);
  const double psi =
      m.psi0 + (m.ell != 0.0 ? (m.ell / (2.0 * m.J)) * inverse_squared_radius_integral(m, t) : 0.0);
  const double radius = std::sqrt(s);
  const Vec2 radial(std::cos(psi), std::sin(psi)), angular(-radial.y(), radial.x());
  return {radius * radial, (s_dot / (2.0 * radius)) * radial + (m.ell / (2.0 * m.J * radius)) * angular};
}

std::optional<std::string> exact_unsupported_reason(const Scene& scene) {
  if (scene.potential.radial)
    return "the orbit under the radial potential has no closed form implemented (physics.md §8.2): "
           "use an integrator";
  if (std::holds_alternative<PolarPotential>(scene.potential.deformation))
    return "the polar deformation potential has no closed form in time (physics.md §8.7): use an integrator";
  return std::nullopt;
}

ExactSolution make_exact_solution(const Scene& scene) {
  ExactSolution sol;
  sol.scene = scene;
  sol.initial = initial_kinematics(scene);
  if (const auto* abc = std::get_if<AbcPotential>(&scene.potential.deformation)) sol.internal = *abc;
  return sol;
}

BodyKinematics integrable_flow(const Scene& scene, const AbcPotential& internal, const BodyKinematics& start,
                               double t) {
  const Surface& surface = scene.surface;
  const double m = scene.body.mass, R = surface.radius;
  BodyKinematics body;
  body.spin = start.spin;
  if (surface.kind == SurfaceKind::plane) {
    body.X = start.X + t * start.V;
    body.V = start.V;
    body.F1 = start.F1;
  } else {
    const Vec3 momentum =
        m * start.X.cross(start.V) + curvature(surface) * R * start.spin * raise(surface, start.X);
    const Mat3 G = orbital_isometry(surface, momentum, m, t);
    body.X = G * start.X;
    body.V = G * start.V;
    body.F1 = G * start.F1;
  }
  // Rotation of the body frame against the moved frame (flow of −σs²/(2mR²)).
  const double theta_s = -curvature_sign(surface) * start.spin * t / (m * R * R);
  if (scene.body.model == BodyModel::rigid) {
    const double l0 = scene.initial.lambda;
    const double omega = start.spin / (2.0 * scene.body.inertia * l0 * l0);
    body.L = rotation2(theta_s + omega * t) * start.L;
    body.M = omega * epsilon() * body.L;
    return body;
  }
  const Mat2& L = start.L;
  const Mat2& M = start.M;
  const double J = scene.body.inertia;
  const PlaneMotion anticonformal =
      plane_motion(J, internal.A, internal.C, Vec2(0.5 * (L(0, 0) - L(1, 1)), 0.5 * (L(0, 1) + L(1, 0))),
                   Vec2(0.5 * (M(0, 0) - M(1, 1)), 0.5 * (M(0, 1) + M(1, 0))));
  const PlaneMotion conformal =
      plane_motion(J, internal.B, internal.C, Vec2(0.5 * (L(0, 0) + L(1, 1)), 0.5 * (L(1, 0) - L(0, 1))),
                   Vec2(0.5 * (M(0, 0) + M(1, 1)), 0.5 * (M(1, 0) - M(0, 1))));
  const auto [uv, uv_dot] = plane_motion_at(anticonformal, t);
  const auto [pq, pq_dot] = plane_motion_at(conformal, t);
  const Mat2 U = rotation2(theta_s);
  body.L = U * assemble(uv, pq);
  body.M = U * assemble(uv_dot, pq_dot);
  return body;
}

State exact_state(const ExactSolution& sol, double t) {
  const Scene& scene = sol.scene;
  const BodyKinematics body = integrable_flow(scene, sol.internal, sol.initial, t);
  State state;
  state.t = t;
  if (chart_well_conditioned(scene.surface, polar_coordinates(scene.surface, body.X).r)) {
    state.y = chart_coords(scene, body);
  } else {
    recentre(scene, body, state.chart, state.y);
  }
  return state;
}

}  // namespace spinfold
