#include "engine/exact_solution.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <tuple>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/inertia.h"
#include "engine/integrator.h"
#include "engine/invariants.h"
#include "engine/potentials.h"
#include "engine/scene_fields.h"

namespace spinfold {

const IntegratorInfo exact_info{"exact",
                                0,
                                true,
                                false,
                                true,
                                "closed form of the separable scenes (physics.md §8, §17): radial potential "
                                "g > 0 or none, abc or none (anisotropic inertia only without abc), rigid or "
                                "affine; checked against its start's invariants"};

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

// The three antiderivatives of physics.md §8.4, continuous in t. Each takes the product
// (c − ρ)(c + ρ) (or the discriminant) from the turning-point identities of §8.2/§8.3, never from a
// subtraction that would cancel near a pole or near x = 0.

// ∫₀ᵗ dt′/f, f = c + A cos ωt + B sin ωt > 0, product = c² − ρ² > 0.
double integral_inverse_trig(double c, double A, double B, double w, double product, double t) {
  const double rho = std::hypot(A, B), theta0 = std::atan2(B, A);
  const double root = std::sqrt(product), high = c + rho, low = product / high;
  const auto F = [&](double th) {
    return (2.0 / root) *
           (std::atan2(std::sqrt(low) * std::sin(0.5 * th), std::sqrt(high) * std::cos(0.5 * th)) +
            2.0 * kPi * std::round(th / (4.0 * kPi)));
  };
  return (F(w * t - theta0) - F(-theta0)) / w;
}

// ∫₀ᵗ dt′/f, f = c + A cosh Ωt + B sinh Ωt = c + ρ cosh(Ωt + τ) > 0 (A > |B|), product = c² − ρ².
double integral_inverse_hyperbolic(double c, double A, double B, double w, double product, double t) {
  const double rho = std::sqrt((A - B) * (A + B)), tau = std::atanh(B / A);
  std::function<double(double)> H;
  if (product > 0.0) {                                                 // c > ρ
    const double root = std::sqrt(product), ratio = root / (c + rho);  // √((c − ρ)/(c + ρ))
    H = [=](double th) { return (2.0 / root) * std::atanh(ratio * std::tanh(0.5 * th)); };
  } else if (product < 0.0) {                                           // |c| < ρ
    const double root = std::sqrt(-product), ratio = root / (rho + c);  // √((ρ − c)/(ρ + c))
    H = [=](double th) { return (2.0 / root) * std::atan(ratio * std::tanh(0.5 * th)); };
  } else {
    H = [=](double th) { return std::tanh(0.5 * th) / rho; };
  }
  return (H(w * t + tau) - H(tau)) / w;
}

// ∫₀ᵗ dt′/f, f = c + bt + at², a > 0, discriminant = 4ac − b² > 0.
double integral_inverse_quadratic(double c, double b, double a, double discriminant, double t) {
  (void)c;
  const double root = std::sqrt(discriminant);
  return (2.0 / root) * (std::atan((2.0 * a * t + b) / root) - std::atan(b / root));
}

// ∫₀ᵗ dt′/s(t′) for the squared radius of a plane motion; s₊s₋ = (ℓ²/J + 2A)/(8C).
double inverse_squared_radius_integral(const PlaneMotion& m, double t) {
  const double J = m.J, C = m.C;
  const double q = m.ell * m.ell / J + 2.0 * m.A;  // > 0
  if (C == 0.0) return integral_inverse_quadratic(m.s0, m.s_dot0, m.energy / J, q / J, t);
  const double c = m.energy / (4.0 * C), w = std::sqrt(std::abs(8.0 * C / J));
  if (C > 0.0) return integral_inverse_trig(c, m.s0 - c, m.s_dot0 / w, w, q / (8.0 * C), t);
  return integral_inverse_hyperbolic(c, m.s0 - c, m.s_dot0 / w, w, q / (8.0 * C), t);
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

// The internal motion at a fixed point without drive: §8.3 for isotropic J; for anisotropic J only
// the free motion, Ṗ = 0 ⇒ Ṁ = 0, L(t) = L + tM (physics.md §13; callers keep the abc potential
// out of `abc`: exact_unsupported_reason refuses it, the splitting kicks it).
std::pair<Mat2, Mat2> internal_flow(const Scene& scene, const AbcPotential& abc, const Mat2& L, const Mat2& M,
                                    double t) {
  // The incompressible body's internal motion is the splitting's RATTLE step (splitting.cpp), not part
  // of this flow: here the body only turns with the frame (physics.md §15).
  if (scene.body.model == BodyModel::incompressible) return {L, M};
  const Inertia inertia = inertia_of(scene.body);
  if (inertia.isotropic) return flat_internal_motion(inertia.J, abc, L, M, t);
  return {L + t * M, M};
}

struct OrbitPoint {
  double r, r_dot, phi, drive;  // drive D(t) = ∫₀ᵗ Cφ̇ dt′
};

// physics.md §8.2 (S², H²) and §8.9 (plane).
OrbitPoint radial_orbit_at(const Surface& surface, double m, const RadialOrbit& o, double t) {
  const double s = o.spin, p = o.p_phi, G = o.strength;
  if (offers(surface, Offer::zero_curvature)) {
    // r² = r₀² + 2r₀ṙ₀t + (2E/m)t², φ̇ = (p_φ − s)/(mr²), D = φ − φ₀.
    const double a = 2.0 * o.energy / m, b = 2.0 * o.r0 * o.r_dot0, c = o.r0 * o.r0;
    const double discriminant = 4.0 * ((p - s) * (p - s) / (m * m) + 2.0 * G / m);
    const double r2 = c + b * t + a * t * t, r = std::sqrt(r2);
    const double phi_offset = ((p - s) / m) * integral_inverse_quadratic(c, b, a, discriminant, t);
    return {r, (b + 2.0 * a * t) / (2.0 * r), o.phi0 + phi_offset, phi_offset};
  }
  const double K = curvature(surface), R = surface.radius, L = o.Lambda;
  const double u0 = polar_C(surface, o.r0), u_dot0 = -K * polar_S(surface, o.r0) * o.r_dot0;
  const double A = u0 - o.u_c;
  double u, u_dot, I_minus, I_plus;  // I∓ = ∫dt/(1 ∓ u)
  // (1 − u₊)(1 − u₋) and (1 + u₊)(1 + u₋), the cancellation-free products of §8.2.
  const double P_minus = K * K * ((p - s) * (p - s) + 2.0 * m * G) / (m * m * L);
  const double P_plus = K * K * ((p + s) * (p + s) + 2.0 * m * G) / (m * m * L);
  const bool sphere = offers(surface, Offer::positive_curvature);
  if (L > 0.0) {
    const double w = std::sqrt(L), B = u_dot0 / w;
    u = o.u_c + A * std::cos(w * t) + B * std::sin(w * t);
    u_dot = -A * w * std::sin(w * t) + u_dot0 * std::cos(w * t);
    // On S², 1 − u > 0; on H², u − 1 > 0 and ∫1/(1 − u) = −∫1/(u − 1).
    I_minus = sphere ? integral_inverse_trig(1.0 - o.u_c, -A, -B, w, P_minus, t)
                     : -integral_inverse_trig(o.u_c - 1.0, A, B, w, P_minus, t);
    I_plus = integral_inverse_trig(1.0 + o.u_c, A, B, w, P_plus, t);
  } else if (L < 0.0) {
    const double w = std::sqrt(-L), B = u_dot0 / w;
    u = o.u_c + A * std::cosh(w * t) + B * std::sinh(w * t);
    u_dot = A * w * std::sinh(w * t) + u_dot0 * std::cosh(w * t);
    I_minus = -integral_inverse_hyperbolic(o.u_c - 1.0, A, B, w, P_minus, t);
    I_plus = integral_inverse_hyperbolic(1.0 + o.u_c, A, B, w, P_plus, t);
  } else {
    const double a = K * K * p * s / (2.0 * m * m);
    u = u0 + u_dot0 * t + a * t * t;
    u_dot = u_dot0 + 2.0 * a * t;
    I_minus = -integral_inverse_quadratic(u0 - 1.0, u_dot0, a, 4.0 * a * (u0 - 1.0) - u_dot0 * u_dot0, t);
    I_plus = integral_inverse_quadratic(u0 + 1.0, u_dot0, a, 4.0 * a * (u0 + 1.0) - u_dot0 * u_dot0, t);
  }
  const double half_minus = 0.5 * (p - s), half_plus = 0.5 * (p + s);
  const double phi = o.phi0 + (K / m) * (half_minus * I_minus + half_plus * I_plus);
  const double drive = (K / m) * (s * t + half_minus * I_minus - half_plus * I_plus);
  // S = R√((1 − u)(1 + u)) on S², R√((u − 1)(u + 1)) on H²; ṙ = −u̇/(KS).
  const double S = R * std::sqrt(std::abs((1.0 - u) * (1.0 + u)));
  const double r = sphere ? R * std::atan2(S / R, u) : R * std::asinh(S / R);
  return {r, -u_dot / (K * S), phi, drive};
}

}  // namespace

std::pair<Mat2, Mat2> flat_internal_motion(double J, const AbcPotential& abc, const Mat2& L, const Mat2& M,
                                           double t) {
  const PlaneMotion anticonformal =
      plane_motion(J, abc.A, abc.C, Vec2(0.5 * (L(0, 0) - L(1, 1)), 0.5 * (L(0, 1) + L(1, 0))),
                   Vec2(0.5 * (M(0, 0) - M(1, 1)), 0.5 * (M(0, 1) + M(1, 0))));
  const PlaneMotion conformal =
      plane_motion(J, abc.B, abc.C, Vec2(0.5 * (L(0, 0) + L(1, 1)), 0.5 * (L(1, 0) - L(0, 1))),
                   Vec2(0.5 * (M(0, 0) + M(1, 1)), 0.5 * (M(1, 0) - M(0, 1))));
  const auto [uv, uv_dot] = plane_motion_at(anticonformal, t);
  const auto [pq, pq_dot] = plane_motion_at(conformal, t);
  return {assemble(uv, pq), assemble(uv_dot, pq_dot)};
}

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
  if (chart_free(scene.surface))
    return "the closed forms hold where the curvature is constant (physics.md §8); on the " +
           std::string(enum_name(scene.surface.kind)) +
           (offers(scene.surface, Offer::formula) ? " surface" : "") + " use an integrator";
  if (scene.friction && scene.friction->any())
    return "with friction the motion has no closed form here (physics-surfaces.md §13): use an integrator";
  if (!std::holds_alternative<std::monostate>(scene.potential.height))
    return "the height potential's orbit has no closed form here (physics-surfaces.md §5): use an integrator";
  if (std::holds_alternative<PolarPotential>(scene.potential.deformation))
    return "the polar deformation potential has no closed form in time (physics.md §8.7): use an integrator";
  if (scene.body.model == BodyModel::incompressible)
    return "the incompressible body (det L fixed) has no closed form here: use split4 or split6 (physics.md "
           "§15)";
  if (scene.body.model == BodyModel::affine && !isotropic_inertia(scene.body) &&
      has_deformation_potential(scene.potential))
    return "with anisotropic inertia the abc internal motion has no closed form here (x² and y² are harmonic "
           "only for isotropic J, physics.md §8.3, §13): use an integrator (split4 and split6 keep the orbit "
           "exact)";
  return std::nullopt;
}

namespace {

// The orbit's constants under the radial potential (physics.md §8.2) from its start in the scene's
// chart: r, φ, ṙ and the conserved p_φ, s, E_orb.
RadialOrbit radial_orbit(const Scene& scene, double r0, double phi0, double r_dot0, double p_phi, double spin,
                         double energy) {
  const double m = scene.body.mass, K = curvature(scene.surface);
  RadialOrbit o;
  o.r0 = r0;
  o.phi0 = phi0;
  o.r_dot0 = r_dot0;
  o.p_phi = p_phi;
  o.spin = spin;
  o.energy = energy;
  o.strength = radial_strength(scene.surface, *scene.potential.radial);
  o.Lambda = 2.0 * K * o.energy / m + K * K * o.spin * o.spin / (m * m);
  o.u_c = o.Lambda != 0.0 ? K * K * o.p_phi * o.spin / (m * m * o.Lambda) : 0.0;
  return o;
}

bool has_radial_barrier(const Scene& scene) {
  return scene.potential.radial && scene.potential.radial->gamma > 0.0;
}

}  // namespace

ExactSolution make_exact_solution(const Scene& scene) {
  ExactSolution sol;
  sol.scene = scene;
  sol.initial = initial_kinematics(scene);
  const State start = initial_state(scene);
  sol.chart0 = start.chart;
  sol.local0 = chart_kinematics(scene, start.y);
  sol.theta0 = scene.initial.alpha - scene.initial.beta;
  if (const auto* abc = std::get_if<AbcPotential>(&scene.potential.deformation)) sol.internal = *abc;
  if (has_radial_barrier(scene)) {
    // p_φ of the scene's chart, from the initial values: start.y is in a moved chart when the start
    // lies outside the well-conditioned band (near a pole, far out on H²), and its p_φ is another one.
    const InitialState& q = scene.initial;
    const double s = spin_of(scene, start.y), S = polar_S(scene.surface, q.r);
    const double p_phi = scene.body.mass * S * S * q.phi_dot + polar_C(scene.surface, q.r) * s;
    sol.radial = radial_orbit(scene, q.r, q.phi, q.r_dot, p_phi, s, orbital_energy(scene, start));
  }
  return sol;
}

ExactSolution make_exact_solution(const Scene& scene, const State& start) {
  ExactSolution sol;
  sol.scene = scene;
  sol.chart0 = start.chart;
  sol.local0 = chart_kinematics(scene, start.y);
  // The same body in the scene's coordinates: X ↦ AX + b, tangent vectors by A.
  sol.initial = sol.local0;
  sol.initial.X = start.chart.A * sol.local0.X + start.chart.b;
  sol.initial.V = start.chart.A * sol.local0.V;
  sol.initial.F1 = start.chart.A * sol.local0.F1;
  if (const auto* abc = std::get_if<AbcPotential>(&scene.potential.deformation)) sol.internal = *abc;
  if (has_radial_barrier(scene)) {
    // The radial closed form runs in the scene's chart, frame (E₁, E₂).
    const GlobalBody g = global_body(scene, start);
    sol.initial.L = g.L;
    sol.initial.M = g.M;
    sol.theta0 = std::atan2(g.L(1, 0), g.L(0, 0));
    sol.radial = radial_orbit(scene, g.r, g.phi, g.r_dot, angular_momentum(scene, start), g.spin,
                              orbital_energy(scene, start));
  }
  return sol;
}

namespace {

// The body-frame part of the integrable flow: the internal motion at a fixed point and the
// rotation θ_s = −σst/(mR²) against the moved frame (flow of −σs²/(2mR²)).
std::pair<Mat2, Mat2> frame_flow(const Scene& scene, const AbcPotential& internal,
                                 const BodyKinematics& start, double t) {
  const Surface& surface = scene.surface;
  const double theta_s =
      -curvature_sign(surface) * start.spin * t / (scene.body.mass * surface.radius * surface.radius);
  if (scene.body.model == BodyModel::rigid) {
    const double l0 = scene.initial.lambda;
    const double omega = start.spin / (2.0 * rigid_inertia(inertia_of(scene.body)) * l0 * l0);
    const Mat2 L = rotation2(theta_s + omega * t) * start.L;
    return {L, omega * epsilon() * L};
  }
  const auto [L, M] = internal_flow(scene, internal, start.L, start.M, t);
  const Mat2 U = rotation2(theta_s);
  return {U * L, U * M};
}

Vec3 momentum_of(const Scene& scene, const BodyKinematics& body) {
  const Surface& surface = scene.surface;
  return scene.body.mass * body.X.cross(body.V) +
         curvature(surface) * surface.radius * body.spin * raise(surface, body.X);
}

// The isometry the orbit has moved by after time t: X ↦ A X + b.
Chart orbit_motion(const Scene& scene, const BodyKinematics& start, double t) {
  Chart g;
  g.global = false;
  if (offers(scene.surface, Offer::zero_curvature))
    g.b = t * start.V;
  else
    g.A = orbital_isometry(scene.surface, momentum_of(scene, start), scene.body.mass, t);
  return g;
}

}  // namespace

BodyKinematics integrable_flow(const Scene& scene, const AbcPotential& internal, const BodyKinematics& start,
                               double t) {
  const Chart g = orbit_motion(scene, start, t);
  BodyKinematics body;
  body.spin = start.spin;
  body.X = g.A * start.X + g.b;
  body.V = g.A * start.V;
  body.F1 = g.A * start.F1;
  std::tie(body.L, body.M) = frame_flow(scene, internal, start, t);
  return body;
}

namespace {

// The closed form under a radial potential, in the scene's chart: the orbit of §8.2 and the
// internal motion of §8.3 turned by −D(t).
Coords radial_exact_coords(const ExactSolution& sol, double t) {
  const Scene& scene = sol.scene;
  const RadialOrbit& o = *sol.radial;
  const Inertia inertia = inertia_of(scene.body);
  const double m = scene.body.mass, J = rigid_inertia(inertia);
  const OrbitPoint orbit = radial_orbit_at(scene.surface, m, o, t);
  Coords y;
  if (scene.body.model == BodyModel::rigid) {
    const double l0 = scene.initial.lambda;
    y.resize(coord::rigid_size);
    y[coord::theta] = sol.theta0 + o.spin * t / (2.0 * J * l0 * l0) - orbit.drive;
    y[coord::spin] = o.spin;
  } else {
    const auto [L_int, M_int] = internal_flow(scene, sol.internal, sol.initial.L, sol.initial.M, t);
    const Mat2 U = rotation2(-orbit.drive);
    const Mat2 L = U * L_int;
    // Isotropic: J(UM) as an Eigen product with the scalar folded in, the bits of the scalar code.
    const Mat2 P = inertia.isotropic ? Mat2(J * (U * M_int)) : momentum_from_rate(inertia, U * M_int);
    y.resize(coord::affine_size);
    y.segment<4>(coord::L) << L(0, 0), L(0, 1), L(1, 0), L(1, 1);
    y.segment<4>(coord::P) << P(0, 0), P(0, 1), P(1, 0), P(1, 1);
  }
  y[coord::r] = orbit.r;
  y[coord::phi] = orbit.phi;
  y[coord::p_r] = m * orbit.r_dot;
  y[coord::p_phi] = o.p_phi;
  return y;
}

}  // namespace

State exact_state(const ExactSolution& sol, double t) {
  const Scene& scene = sol.scene;
  State state;
  state.t = t;
  if (sol.radial) {
    state.y = radial_exact_coords(sol, t);
    const double r = state.y[coord::r], R = scene.surface.radius;
    if (offers(scene.surface, Offer::negative_curvature) && r > 2.0 * R) {
      // Far out on H²: a chart whose pole lies on the body's own radial geodesic at distance R
      // behind it (rotation by φ after a boost along x by r − R). The frame (E₁, E₂) is the same
      // in both charts, so L, P and p_r carry over and only p_φ changes: no e^{r/R} cancels.
      const double beta = r / R - 1.0, phi = state.y[coord::phi];
      Mat3 boost, turn;
      boost << std::cosh(beta), 0, std::sinh(beta), 0, 1, 0, std::sinh(beta), 0, std::cosh(beta);
      turn << std::cos(phi), -std::sin(phi), 0, std::sin(phi), std::cos(phi), 0, 0, 0, 1;
      const double m = scene.body.mass, s = sol.radial->spin;
      const double S_phi_dot =
          (state.y[coord::p_phi] - polar_C(scene.surface, r) * s) / (m * polar_S(scene.surface, r));
      state.chart = Chart{turn * boost, Vec3::Zero(), false};
      state.y[coord::r] = R;
      state.y[coord::phi] = 0.0;
      state.y[coord::p_phi] = m * polar_S(scene.surface, R) * S_phi_dot + polar_C(scene.surface, R) * s;
    } else if (!chart_well_conditioned(scene.surface, r)) {
      recentre(scene, state);  // near a pole: moderate numbers, the general re-centring is exact
    }
    return state;
  }
  // Without V_r: the initial local body, its frame turned and deformed, in the moved chart. The
  // orbit's isometry is taken in the start's chart (chart0 ∘ G_local(t) = G(t) ∘ chart0): the body's
  // coordinates there are moderate, while far out on H² the global ones grow like e^{r/R} and the
  // momentum map m X × V computed from them cancels to nothing (physics.md §8.6, chart rules).
  const Chart g = orbit_motion(scene, sol.local0, t);
  state.chart.A = sol.chart0.A * g.A;
  state.chart.b = sol.chart0.A * g.b + sol.chart0.b;
  state.chart.global = t == 0.0 && sol.chart0.global;
  BodyKinematics local = sol.local0;
  std::tie(local.L, local.M) = frame_flow(scene, sol.internal, sol.local0, t);
  state.y = chart_coords(scene, local);
  return state;
}

namespace {

// f(τ) = c + bτ + aτ², or the same with a, b, c of a function of another shape: its sign changes.
struct Quadratic {
  double a, b, c;
};

// Simple real roots of aτ² + bτ + c (a double root is a touch, not a crossing), without cancellation.
std::vector<double> quadratic_roots(const Quadratic& f) {
  if (f.a == 0.0) {
    if (f.b == 0.0) return {};
    return {-f.c / f.b};
  }
  const double discriminant = f.b * f.b - 4.0 * f.a * f.c;
  if (!(discriminant > 0.0)) return {};
  const double q = -0.5 * (f.b + std::copysign(std::sqrt(discriminant), f.b));
  std::vector<double> roots;
  if (q != 0.0)
    roots = {q / f.a, f.c / q};
  else
    roots = {0.0};
  std::sort(roots.begin(), roots.end());
  return roots;
}

// |w(τ)|² of a plane motion as c + a·cos Ωτ + b·sin Ωτ (C > 0), c + a·cosh Ωτ + b·sinh Ωτ (C < 0)
// or c + bτ + aτ² (C = 0): s̈ = 2E/J − (8C/J)s, the same Ω for both planes (physics.md §8.3).
Quadratic squared_radius_coefficients(const PlaneMotion& m) {
  if (m.C == 0.0) return {m.energy / m.J, m.s_dot0, m.s0};
  const double c = m.energy / (4.0 * m.C), w = std::sqrt(std::abs(8.0 * m.C / m.J));
  return {m.s0 - c, m.s_dot0 / w, c};  // a, b, c of c + a·cos + b·sin (or cosh, sinh)
}

}  // namespace

std::vector<double> degenerate_times(const ExactSolution& sol, double t0, double t1, std::size_t max_count) {
  const Scene& scene = sol.scene;
  std::vector<double> times;
  if (scene.body.model != BodyModel::affine || !(t1 > t0)) return times;
  const auto keep = [&](double t) {
    if (t > t0 && t <= t1) times.push_back(t);
  };
  // The internal motion starts from the frame of the solution's start (the rotations by θ_s and
  // −D(τ) leave det L alone).
  const Mat2& L = sol.radial ? sol.initial.L : sol.local0.L;
  const Mat2& M = sol.radial ? sol.initial.M : sol.local0.M;
  const Inertia inertia = inertia_of(scene.body);
  if (!inertia.isotropic) {  // free body: det(L + τM) = det L + τ tr(cof(L)ᵀM) + τ² det M
    const double linear = L(0, 0) * M(1, 1) + L(1, 1) * M(0, 0) - L(0, 1) * M(1, 0) - L(1, 0) * M(0, 1);
    for (double t : quadratic_roots({M.determinant(), linear, L.determinant()})) keep(t);
    return times;
  }
  const AbcPotential& abc = sol.internal;
  const PlaneMotion uv =
      plane_motion(inertia.J, abc.A, abc.C, Vec2(0.5 * (L(0, 0) - L(1, 1)), 0.5 * (L(0, 1) + L(1, 0))),
                   Vec2(0.5 * (M(0, 0) - M(1, 1)), 0.5 * (M(0, 1) + M(1, 0))));
  const PlaneMotion pq =
      plane_motion(inertia.J, abc.B, abc.C, Vec2(0.5 * (L(0, 0) + L(1, 1)), 0.5 * (L(1, 0) - L(0, 1))),
                   Vec2(0.5 * (M(0, 0) + M(1, 1)), 0.5 * (M(1, 0) - M(0, 1))));
  const Quadratic f_uv = squared_radius_coefficients(uv), f_pq = squared_radius_coefficients(pq);
  const Quadratic f{f_pq.a - f_uv.a, f_pq.b - f_uv.b, f_pq.c - f_uv.c};  // det L = |pq|² − |uv|²
  if (abc.C == 0.0) {
    for (double t : quadratic_roots(f)) keep(t);
    return times;
  }
  const double w = std::sqrt(std::abs(8.0 * abc.C / inertia.J));
  if (abc.C < 0.0) {
    // c + a cosh + b sinh = 0 with z = e^{Ωτ}: (a + b)z² + 2cz + (a − b) = 0, z > 0.
    for (double z : quadratic_roots({f.a + f.b, 2.0 * f.c, f.a - f.b}))
      if (z > 0.0) keep(std::log(z) / w);
    std::sort(times.begin(), times.end());
    return times;
  }
  // c + ρ cos(Ωτ − θ₀) = 0: Ωτ = θ₀ ± β + 2πk, β = arccos(−c/ρ) (no crossing when ρ ≤ |c|).
  const double rho = std::hypot(f.a, f.b), theta0 = std::atan2(f.b, f.a);
  if (!(rho > std::abs(f.c))) return times;
  const double beta = std::acos(-f.c / rho), period = 2.0 * kPi;
  // Each family's roots counted from its first, at most max_count of them (the oldest of both
  // families are among the first max_count of each), and never past where k + 1 rounds to k.
  for (const double offset : {theta0 - beta, theta0 + beta}) {
    const double k_first = std::floor((w * t0 - offset) / period);
    std::size_t kept = 0;
    for (double k = k_first; kept < max_count && k + 1.0 != k; k += 1.0) {
      const double t = (offset + period * k) / w;
      if (t > t1) break;
      const std::size_t before = times.size();
      keep(t);
      kept += times.size() - before;
    }
  }
  std::sort(times.begin(), times.end());
  if (times.size() > max_count) times.resize(max_count);
  return times;
}

}  // namespace spinfold
