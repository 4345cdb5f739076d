// The spheroid: equatorial radius a, polar radius b (oblate a > b, prolate a < b, a = b the sphere;
// physics-surfaces.md §1). u is the polar angle θ from the north pole, u ∈ [0, π]; both poles are axis
// points (§8).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/revolution.h"

namespace spinfold {
namespace {

// ρ = a sin u, z = b cos u; f = √(a² cos²u + b² sin²u); K = b²/f⁴ (b²/a⁴ at the poles).
ProfilePoint spheroid_profile(const RevolutionSurface& s, double u) {
  const double a = s.equatorial_radius, b = s.polar_radius;
  const double cu = std::cos(u), su = std::sin(u);
  ProfilePoint p;
  p.rho = a * su;
  p.rho_u = a * cu;
  p.rho_uu = -a * su;
  p.z = b * cu;
  p.z_u = -b * su;
  p.z_uu = -b * cu;
  const double f2 = a * a * cu * cu + b * b * su * su;
  p.K = b * b / (f2 * f2);
  p.zu_over_rho = -b / a;
  return p;
}

// F = (x² + y²)/a² + z²/b² − 1.
ImplicitPoint spheroid_implicit(const RevolutionSurface& s, const Vec3& X) {
  const double ia2 = 1.0 / (s.equatorial_radius * s.equatorial_radius);
  const double ib2 = 1.0 / (s.polar_radius * s.polar_radius);
  ImplicitPoint p;
  p.F = (X.x() * X.x() + X.y() * X.y()) * ia2 + X.z() * X.z() * ib2 - 1.0;
  p.gradient = Vec3(2.0 * X.x() * ia2, 2.0 * X.y() * ia2, 2.0 * X.z() * ib2);
  p.hessian = Vec3(2.0 * ia2, 2.0 * ia2, 2.0 * ib2).asDiagonal();
  return p;
}

double spheroid_u(const RevolutionSurface& s, const Vec3& X) {
  return std::atan2(std::hypot(X.x(), X.y()) / s.equatorial_radius, X.z() / s.polar_radius);
}

ProfileDomain spheroid_domain(const RevolutionSurface&) {
  return {0.0, std::numbers::pi, false, true, true};
}

ProfilePicture spheroid_picture(const RevolutionSurface& s) {
  return {0.0, std::numbers::pi, std::max(s.equatorial_radius, s.polar_radius),
          std::min(s.equatorial_radius, s.polar_radius), std::numbers::pi / 12};
}

}  // namespace

const RevolutionEntry spheroid_entry{SurfaceKind::spheroid,
                                     "spheroid",
                                     "equatorial radius a, polar radius b: oblate a > b, prolate a < b",
                                     spheroid_profile,
                                     spheroid_implicit,
                                     spheroid_u,
                                     spheroid_domain,
                                     spheroid_picture,
                                     " (the polar angle from the north pole)"};

}  // namespace spinfold
