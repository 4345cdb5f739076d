// A Gaussian bump on the plane: z = h exp(−ρ²/(2w²)), height h of either sign, width w > 0
// (physics-surfaces.md §1). u is the distance ρ from the axis, u ≥ 0; the top (u = 0) is an axis point.
// K > 0 for u < w, K < 0 beyond, K → 0 like e^{−u²/w²}.
#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/revolution.h"

namespace spinfold {
namespace {

// ρ = u, z = h E, E = e^{−u²/(2w²)}; z_u = −(h u/w²) E, z_uu = (h/w²)(u²/w² − 1) E;
// K = (h²/w⁴) E² (1 − u²/w²)/f⁴ with f² = 1 + z_u².
ProfilePoint bump_profile(const RevolutionSurface& s, double u) {
  const double h = s.height, w2 = s.width * s.width;
  const double E = std::exp(-u * u / (2.0 * w2));
  ProfilePoint p;
  p.rho = u;
  p.rho_u = 1.0;
  p.rho_uu = 0.0;
  // Where E underflows (u > 38.6 w) the bump is the plane in double: every term has the factor E,
  // but h/w⁴ can overflow first (a narrow bump far out gave 0 · ∞ = NaN for K).
  if (E == 0.0) return p;
  p.z = h * E;
  p.z_u = -(h * u / w2) * E;
  p.z_uu = (h / w2) * (u * u / w2 - 1.0) * E;
  const double f2 = 1.0 + p.z_u * p.z_u;
  p.K = (h * h / (w2 * w2)) * E * E * (1.0 - u * u / w2) / (f2 * f2);
  p.zu_over_rho = -(h / w2) * E;
  return p;
}

// F = z − G, G = h exp(−(x² + y²)/(2w²)).
ImplicitPoint bump_implicit(const RevolutionSurface& s, const Vec3& X) {
  const double w2 = s.width * s.width;
  const double G = s.height * std::exp(-(X.x() * X.x() + X.y() * X.y()) / (2.0 * w2));
  ImplicitPoint p;
  p.F = X.z() - G;
  p.gradient = Vec3(X.x() * G / w2, X.y() * G / w2, 1.0);
  p.hessian.setZero();
  if (G == 0.0) {  // the plane in double (bump_profile says why); zeros of the same signs
    p.gradient = Vec3(X.x() * G, X.y() * G, 1.0);
    return p;
  }
  p.hessian(0, 0) = G / w2 - X.x() * X.x() * G / (w2 * w2);
  p.hessian(1, 1) = G / w2 - X.y() * X.y() * G / (w2 * w2);
  p.hessian(0, 1) = p.hessian(1, 0) = -X.x() * X.y() * G / (w2 * w2);
  return p;
}

double bump_u(const RevolutionSurface&, const Vec3& X) {
  return std::hypot(X.x(), X.y());
}

ProfileDomain bump_domain(const RevolutionSurface&) {
  return {0.0, std::numeric_limits<double>::infinity(), false, true, false};
}

// The plane out to ρ = 4w, where the bump has fallen to e⁻⁸ of its height.
ProfilePicture bump_picture(const RevolutionSurface& s) {
  return {0.0, 4.0 * s.width, std::max(4.0 * s.width, std::abs(s.height)), s.width, 0.5 * s.width};
}

}  // namespace

const RevolutionEntry bump_entry{
    SurfaceKind::bump,
    "bump",
    "a Gaussian bump z = h exp(-r^2/(2w^2)) on the plane; K > 0 on top, < 0 round it",
    bump_profile,
    bump_implicit,
    bump_u,
    bump_domain,
    bump_picture,
    " (the distance from the axis)"};

}  // namespace spinfold
