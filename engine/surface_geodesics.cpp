#include "engine/surface_geodesics.h"

#include <cmath>

namespace spinfold {

Vec3 project_onto_surface(const ImplicitSurface& surface, const Vec3& X) {
  Vec3 p = X;
  for (int i = 0; i < 16; ++i) {
    const ImplicitPoint at = surface.at(p);
    const double g2 = at.gradient.squaredNorm();
    if (!(g2 > 0.0)) break;  // on the axis of a surface whose F is flat there: leave the point
    const Vec3 step = (at.F / g2) * at.gradient;
    p -= step;
    if (step.norm() <= 1e-15 * (p.norm() + 1.0)) break;
  }
  return p;
}

Vec3 tangent_part(const ImplicitSurface& surface, const Vec3& X, const Vec3& v) {
  const Vec3 g = surface.at(X).gradient;
  const double g2 = g.squaredNorm();
  return g2 > 0.0 ? Vec3(v - (v.dot(g) / g2) * g) : v;
}

namespace {

// Ẍ = −(VᵀHV/|∇F|²)∇F: the acceleration that keeps a free point on the surface.
Vec3 geodesic_acceleration(const ImplicitSurface& surface, const Vec3& X, const Vec3& V) {
  const ImplicitPoint at = surface.at(X);
  const double g2 = at.gradient.squaredNorm();
  return g2 > 0.0 ? Vec3(-(V.dot(at.hessian * V) / g2) * at.gradient) : Vec3::Zero();
}

}  // namespace

Vec3 implicit_exponential_map(const ImplicitSurface& surface, const Vec3& X, const Vec3& v, int steps) {
  if (v.squaredNorm() == 0.0 || steps < 1) return X;
  const double h = 1.0 / steps;
  Vec3 x = X, V = v;
  for (int i = 0; i < steps; ++i) {
    const Vec3 k1x = V, k1v = geodesic_acceleration(surface, x, V);
    const Vec3 k2x = V + 0.5 * h * k1v, k2v = geodesic_acceleration(surface, x + 0.5 * h * k1x, k2x);
    const Vec3 k3x = V + 0.5 * h * k2v, k3v = geodesic_acceleration(surface, x + 0.5 * h * k2x, k3x);
    const Vec3 k4x = V + h * k3v, k4v = geodesic_acceleration(surface, x + h * k3x, k4x);
    x += (h / 6.0) * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    V += (h / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    x = project_onto_surface(surface, x);
    V = tangent_part(surface, x, V);
  }
  return x;
}

}  // namespace spinfold
