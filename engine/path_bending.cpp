#include "engine/path_bending.h"

#include <cmath>

#include "engine/embedded_dynamics.h"

namespace spinfold {

Vec3 surface_normal(const SurfaceModel& surface, const Vec3& X) {
  if (surface.implicit) return embedded_normal(*surface.implicit, X);
  return unit_normal(surface.surface, X);
}

double curvature_at(const SurfaceModel& surface, const Vec3& X) {
  if (surface.implicit) return bordered_hessian_curvature(surface.implicit->at(X));
  return surface.curvature;
}

namespace {

// |v| in the surface's metric (a chord of H² is spacelike).
double chord_length(const SurfaceModel& surface, const Vec3& v) {
  if (surface.implicit) return v.norm();
  return std::sqrt(std::abs(dot(surface.surface, v, v)));
}

}  // namespace

std::vector<double> geodesic_curvatures(const SurfaceModel& surface, std::span<const Vec3> path) {
  std::vector<double> kappa(path.size(), 0.0);
  if (path.size() < 3) return kappa;
  for (std::size_t i = 1; i + 1 < path.size(); ++i) {
    const Vec3 a = path[i] - path[i - 1], b = path[i + 1] - path[i];
    const double la = chord_length(surface, a), lb = chord_length(surface, b),
                 lab = chord_length(surface, a + b);
    if (!(la > 0.0 && lb > 0.0 && lab > 0.0)) continue;
    Eigen::Matrix3d m;
    m << surface_normal(surface, path[i]), a, b;
    const double k = 2.0 * m.determinant() / (la * lb * lab);
    if (std::isfinite(k)) kappa[i] = k;
  }
  kappa.front() = kappa[1];
  kappa.back() = kappa[path.size() - 2];
  return kappa;
}

}  // namespace spinfold
