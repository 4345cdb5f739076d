#include "engine/surface.h"

#include <cmath>
#include <stdexcept>

namespace spinfold {

namespace {

// A constant-curvature formula asked of a surface whose curvature varies: a caller's mistake.
[[noreturn]] void not_constant(const Surface&) {
  throw std::logic_error("a constant-curvature formula on a surface whose curvature varies");
}

}  // namespace

double curvature_sign(const Surface& surface) {
  switch (surface.kind) {
    case SurfaceKind::sphere: return 1.0;
    case SurfaceKind::pseudosphere: return -1.0;
    case SurfaceKind::plane: return 0.0;
    default: not_constant(surface);
  }
}

void resolve_curvature(Surface& surface) {
  if (!surface.curvature_given) return;
  const double K = *surface.curvature_given;
  if (!std::isfinite(K)) return;  // refused by validate_scene, naming surface.curvature
  if (std::abs(K) < kFlatCurvature) {
    surface.kind = SurfaceKind::plane;
    surface.radius = 1.0;
    return;
  }
  surface.kind = K > 0.0 ? SurfaceKind::sphere : SurfaceKind::pseudosphere;
  surface.radius = 1.0 / std::sqrt(std::abs(K));
}

double curvature(const Surface& surface) {
  return curvature_sign(surface) / (surface.radius * surface.radius);
}

double polar_S(const Surface& surface, double r) {
  const double R = surface.radius;
  switch (surface.kind) {
    case SurfaceKind::sphere: return R * std::sin(r / R);
    case SurfaceKind::pseudosphere: return R * std::sinh(r / R);
    case SurfaceKind::plane: return r;
    default: not_constant(surface);
  }
}

double polar_C(const Surface& surface, double r) {
  const double R = surface.radius;
  switch (surface.kind) {
    case SurfaceKind::sphere: return std::cos(r / R);
    case SurfaceKind::pseudosphere: return std::cosh(r / R);
    case SurfaceKind::plane: return 1.0;
    default: not_constant(surface);
  }
}

double dot(const Surface& surface, const Vec3& a, const Vec3& b) {
  const double planar = a.x() * b.x() + a.y() * b.y();
  return surface.kind == SurfaceKind::pseudosphere ? planar - a.z() * b.z() : planar + a.z() * b.z();
}

Vec3 unit_normal(const Surface& surface, const Vec3& X) {
  if (surface.kind == SurfaceKind::plane) return Vec3::UnitZ();
  return X / surface.radius;
}

Vec3 raise(const Surface& surface, const Vec3& w) {
  if (surface.kind == SurfaceKind::pseudosphere) return {w.x(), w.y(), -w.z()};
  return w;
}

Vec3 rotate_quarter(const Surface& surface, const Vec3& X, const Vec3& v) {
  return raise(surface, unit_normal(surface, X).cross(v));
}

Vec3 tangential(const Surface& surface, const Vec3& X, const Vec3& w) {
  if (surface.kind == SurfaceKind::plane) return {w.x(), w.y(), 0.0};
  return w - (dot(surface, w, X) / dot(surface, X, X)) * X;
}

ChartPoint chart_point(const Surface& surface, double r, double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  const double S = polar_S(surface, r), C = polar_C(surface, r);
  ChartPoint p;
  p.E2 = {-s, c, 0.0};
  switch (surface.kind) {
    case SurfaceKind::sphere:
      p.X = {S * c, S * s, surface.radius * C};
      p.E1 = {C * c, C * s, -S / surface.radius};
      break;
    case SurfaceKind::pseudosphere:
      p.X = {S * c, S * s, surface.radius * C};
      p.E1 = {C * c, C * s, S / surface.radius};
      break;
    case SurfaceKind::plane:
      p.X = {r * c, r * s, 0.0};
      p.E1 = {c, s, 0.0};
      break;
    default: not_constant(surface);
  }
  return p;
}

PolarCoordinates polar_coordinates(const Surface& surface, const Vec3& X) {
  const double rho = std::hypot(X.x(), X.y());
  const double phi = std::atan2(X.y(), X.x());
  const double R = surface.radius;
  switch (surface.kind) {
    case SurfaceKind::sphere: return {R * std::atan2(rho, X.z()), phi, rho};
    case SurfaceKind::pseudosphere: return {R * std::asinh(rho / R), phi, rho};
    case SurfaceKind::plane: return {rho, phi, rho};
    default: not_constant(surface);
  }
}

}  // namespace spinfold
