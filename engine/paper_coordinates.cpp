#include "engine/paper_coordinates.h"

#include <cmath>
#include <numbers>

#include "engine/chart.h"
#include "engine/inertia.h"
#include "engine/invariants.h"

namespace spinfold {

namespace {

// Polar pair of one plane of L's decomposition (physics.md §2): the radius hypot(c, s) (the paper's
// magnitude over √2: (λ − μ)/2 or (λ + μ)/2), the angle, their rates. The radii, not the magnitudes,
// are summed into λ and μ: a round trip through √2 made λ = 1.1 read 1.1000000000000003.
struct PolarPart {
  double radius, angle, radius_dot, angle_dot;
  bool angle_defined;
};

PolarPart polar_part(double c, double s, double c_dot, double s_dot, double scale) {
  const double h = std::hypot(c, s);
  PolarPart p{};
  p.radius = h;
  p.angle_defined = h > 1e-12 * scale;
  if (p.angle_defined) {
    p.angle = std::atan2(s, c);
    p.radius_dot = (c * c_dot + s * s_dot) / h;
    p.angle_dot = (c * s_dot - s * c_dot) / (h * h);
  } else {
    // At radius 0 the one-sided rate of the (non-negative) radius is |rate|.
    p.radius_dot = std::hypot(c_dot, s_dot);
  }
  return p;
}

double wrap(double angle) {
  return std::remainder(angle, 2.0 * std::numbers::pi);
}

}  // namespace

FrameStretches frame_stretches(const Mat2& L) {
  // The radii of the two polar pairs (polar_part), summed; μ = det L / λ: as accurate as the
  // difference of the radii, and the given μ back where L was made from it (the difference read
  // μ = 0.6 as 0.6000000000000001).
  const double x = std::hypot(0.5 * (L(0, 0) - L(1, 1)), 0.5 * (L(0, 1) + L(1, 0)));
  const double y = std::hypot(0.5 * (L(0, 0) + L(1, 1)), 0.5 * (L(1, 0) - L(0, 1)));
  const double lambda = y + x;
  return {lambda, lambda > 0.0 ? L.determinant() / lambda : 0.0};
}

void set_internal_coordinates(PaperCoordinates& out, const Mat2& L, const Mat2& L_dot, const Mat2& M,
                              const Inertia& inertia, BodyModel model, bool frame_defined) {
  const double J = inertia.J;
  const double scale = std::sqrt(L.squaredNorm());
  const PolarPart x = polar_part(0.5 * (L(0, 0) - L(1, 1)), 0.5 * (L(0, 1) + L(1, 0)),
                                 0.5 * (L_dot(0, 0) - L_dot(1, 1)), 0.5 * (L_dot(0, 1) + L_dot(1, 0)), scale);
  const PolarPart y = polar_part(0.5 * (L(0, 0) + L(1, 1)), 0.5 * (L(1, 0) - L(0, 1)),
                                 0.5 * (L_dot(0, 0) + L_dot(1, 1)), 0.5 * (L_dot(1, 0) - L_dot(0, 1)), scale);
  const FrameStretches stretches = frame_stretches(L);
  out.lambda = stretches.lambda;
  out.mu = stretches.mu;
  out.lambda_dot = y.radius_dot + x.radius_dot;
  out.mu_dot = y.radius_dot - x.radius_dot;
  out.p_lambda = J * out.lambda_dot;
  out.p_mu = J * out.mu_dot;
  if (!inertia.isotropic && model == BodyModel::affine) {
    if (x.angle_defined && y.angle_defined) {
      // p_λ = tr((∂L/∂λ)ᵀP) = (U(α)ᵀ P U(β))₁₁, p_μ = (…)₂₂ with P = MJ (physics.md §13); the same in
      // any frame (a frame rotation turns L and P alike and shifts only α).
      const Mat2 P = momentum_from_rate(inertia, M);
      const Mat2 D =
          rotation2(0.5 * (x.angle + y.angle)).transpose() * P * rotation2(0.5 * (x.angle - y.angle));
      out.p_lambda = D(0, 0);
      out.p_mu = D(1, 1);
    } else {
      for (const char* f : {"p_lambda", "p_mu"})
        out.undefined.push_back(
            {f,
             "with anisotropic inertia p_lambda and p_mu need alpha and beta, undefined at lambda = +-mu"});
    }
  }
  if (!frame_defined) return;
  out.L = L;
  // γ = α + β lives in the anticonformal plane (x), δ = α − β in the conformal plane (y).
  if (y.angle_defined) {
    out.theta = y.angle;
    out.theta_dot = y.angle_dot;
  } else {
    for (const char* f : {"theta", "theta_dot"})
      out.undefined.push_back({f, "lambda = -mu (y = 0): only alpha + beta is defined"});
  }
  if (x.angle_defined && y.angle_defined) {
    out.alpha = wrap(0.5 * (x.angle + y.angle));
    out.beta = wrap(0.5 * (x.angle - y.angle));
    out.alpha_dot = 0.5 * (x.angle_dot + y.angle_dot);
    out.beta_dot = 0.5 * (x.angle_dot - y.angle_dot);
  } else {
    const std::string why = x.angle_defined
                                ? "lambda = -mu (y = 0): alpha and beta are not separately defined"
                                : "lambda = mu (isotropic frame): only theta = alpha - beta is defined";
    for (const char* f : {"alpha", "beta", "alpha_dot", "beta_dot"}) out.undefined.push_back({f, why});
  }
}

PaperCoordinates paper_coordinates(const Scene& scene, const State& state) {
  const GlobalBody g = global_body(scene, state);
  const Inertia inertia = inertia_of(scene.body);
  const double m = scene.body.mass;
  PaperCoordinates out;
  out.r = g.r;
  out.X = g.X;
  out.det_L = g.L.determinant();
  out.p_alpha = g.spin;
  out.p_beta = vorticity(scene, state);
  out.p_phi = angular_momentum(scene, state);
  if (!state.chart.global && !offers(scene.surface, Offer::zero_curvature)) {
    const ChartMomentum cm = chart_momentum(scene, state);
    if (!well_conditioned(cm.rounding.z(), std::abs(cm.global.z()) + cm.local.cwiseAbs().sum())) {
      out.undefined.push_back(
          {"p_phi",
           "far out on the pseudosphere p_phi = m S^2 phi_dot + C s is the difference of numbers of size "
           "e^(r/R) and keeps fewer than 8 digits in double (physics.md §6)"});
    }
  }

  const Mat2& L = g.L;
  // L̇ = M − Cφ̇εL in the paper's frame; at a pole only frame-independent parts are used.
  Mat2 L_dot = g.M;
  if (!g.at_pole) {
    Mat2 eps_L;
    eps_L << -L(1, 0), -L(1, 1), L(0, 0), L(0, 1);
    L_dot -= g.C * g.phi_dot * eps_L;
  }
  set_internal_coordinates(out, L, L_dot, g.M, inertia, scene.body.model, !g.at_pole);
  if (g.at_pole) {
    const std::string why = "the body is at a pole of the scene's chart, where phi and E1 are undefined";
    for (const char* f : {"phi", "phi_dot", "r_dot", "p_r"}) out.undefined.push_back({f, why});
    for (const char* f : {"alpha", "beta", "theta", "alpha_dot", "beta_dot", "theta_dot", "L"})
      out.undefined.push_back({f, why});
    return out;
  }
  out.phi = g.phi;
  out.phi_dot = g.phi_dot;
  out.r_dot = g.r_dot;
  out.p_r = m * g.r_dot;
  return out;
}

}  // namespace spinfold
