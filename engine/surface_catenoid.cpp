// The catenoid: neck radius c (physics-surfaces.md §1). u = −z ∈ ℝ; K = −1/(c² cosh⁴(u/c)) < 0
// everywhere, most negative on the neck; no axis points.
#include <cmath>
#include <limits>

#include "engine/revolution.h"

namespace spinfold {
namespace {

// ρ = c cosh(u/c), z = −u; f = cosh(u/c), C = tanh(u/c).
ProfilePoint catenoid_profile(const RevolutionSurface& s, double u) {
  const double c = s.neck_radius;
  const double ch = std::cosh(u / c), sh = std::sinh(u / c);
  ProfilePoint p;
  p.rho = c * ch;
  p.rho_u = sh;
  p.rho_uu = ch / c;
  p.z = -u;
  p.z_u = -1.0;
  p.z_uu = 0.0;
  p.K = -1.0 / (c * c * ch * ch * ch * ch);
  p.zu_over_rho = -1.0 / p.rho;
  return p;
}

// F = x² + y² − c² cosh²(z/c).
ImplicitPoint catenoid_implicit(const RevolutionSurface& s, const Vec3& X) {
  const double c = s.neck_radius, ch = std::cosh(X.z() / c);
  ImplicitPoint p;
  p.F = X.x() * X.x() + X.y() * X.y() - c * c * ch * ch;
  p.gradient = Vec3(2.0 * X.x(), 2.0 * X.y(), -c * std::sinh(2.0 * X.z() / c));
  p.hessian = Vec3(2.0, 2.0, -2.0 * std::cosh(2.0 * X.z() / c)).asDiagonal();
  return p;
}

double catenoid_u(const RevolutionSurface&, const Vec3& X) {
  return -X.z();
}

ProfileDomain catenoid_domain(const RevolutionSurface&) {
  const double inf = std::numeric_limits<double>::infinity();
  return {-inf, inf, false, false, false};
}

// |z| ≤ 2c, where ρ = c cosh 2 ≈ 3.8c.
ProfilePicture catenoid_picture(const RevolutionSurface& s) {
  return {-2.0 * s.neck_radius, 2.0 * s.neck_radius, 3.0 * s.neck_radius, s.neck_radius, 0.5 * s.neck_radius};
}

}  // namespace

const RevolutionEntry catenoid_entry{
    SurfaceKind::catenoid, "catenoid",        "neck radius c; K < 0 everywhere, most negative on the neck",
    catenoid_profile,      catenoid_implicit, catenoid_u,
    catenoid_domain,       catenoid_picture};

}  // namespace spinfold
