// The torus: tube radius a, centre radius c > a (physics-surfaces.md §1). u is the tube angle, u = 0
// the outer equator (K > 0), u = ±π/2 the bottom and top circles (K = 0), u = π the inner equator
// (K = −1/(a(c − a)), the most negative). No axis points: |∇F| = 8acρ ≥ 8ac(c − a) > 0.
#include <cmath>
#include <numbers>

#include "engine/number_text.h"
#include "engine/revolution.h"

namespace spinfold {
namespace {

// ρ = c + a cos u, z = −a sin u; f = a; K = cos u / (a(c + a cos u)).
ProfilePoint torus_profile(const RevolutionSurface& s, double u) {
  const double a = s.tube_radius, c = s.center_radius;
  const double cu = std::cos(u), su = std::sin(u);
  ProfilePoint p;
  p.rho = c + a * cu;
  p.rho_u = -a * su;
  p.rho_uu = -a * cu;
  p.z = -a * su;
  p.z_u = -a * cu;
  p.z_uu = a * su;
  p.K = cu / (a * p.rho);
  p.zu_over_rho = p.z_u / p.rho;
  return p;
}

// F = (q + c² − a²)² − 4c²(x² + y²), q = |X|²: a quartic, smooth everywhere (no √(x² + y²)).
ImplicitPoint torus_implicit(const RevolutionSurface& s, const Vec3& X) {
  const double a = s.tube_radius, c = s.center_radius;
  const double q = X.squaredNorm(), w = q + c * c - a * a, k = 4.0 * w;
  const double planar = X.x() * X.x() + X.y() * X.y();
  ImplicitPoint p;
  p.F = w * w - 4.0 * c * c * planar;
  p.gradient = k * X - 8.0 * c * c * Vec3(X.x(), X.y(), 0.0);
  p.hessian = k * Mat3::Identity() + 8.0 * X * X.transpose();
  p.hessian(0, 0) -= 8.0 * c * c;
  p.hessian(1, 1) -= 8.0 * c * c;
  return p;
}

double torus_u(const RevolutionSurface& s, const Vec3& X) {
  return std::atan2(-X.z(), std::hypot(X.x(), X.y()) - s.center_radius);
}

ProfileDomain torus_domain(const RevolutionSurface&) {
  return {-std::numbers::pi, std::numbers::pi, true, false, false};
}

ProfilePicture torus_picture(const RevolutionSurface& s) {
  return {-std::numbers::pi, std::numbers::pi, s.center_radius + s.tube_radius, s.tube_radius,
          std::numbers::pi / 6};
}

// c > a: else the tube would cross the axis.
std::optional<ParameterProblem> torus_radii(const RevolutionSurface& s) {
  if (!std::isfinite(s.tube_radius) || !std::isfinite(s.center_radius) || s.center_radius > s.tube_radius)
    return std::nullopt;
  return ParameterProblem{"center_radius", s.center_radius,
                          "must be > tube_radius (" + shortest(s.tube_radius) +
                              "): the tube would cross the axis and the torus intersect itself"};
}

}  // namespace

const RevolutionEntry torus_entry{
    SurfaceKind::torus,
    "torus",
    "tube radius a round a centre circle of radius c > a; K > 0 outside, < 0 inside",
    torus_profile,
    torus_implicit,
    torus_u,
    torus_domain,
    torus_picture,
    {},
    torus_radii};

}  // namespace spinfold
