#include "engine/revolution.h"

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace spinfold {

RevolutionSurface revolution_surface(const Surface& surface) {
  if (!offers(surface, Offer::profile_chart)) throw std::logic_error("revolution_surface: no profile chart");
  RevolutionSurface r;
  r.kind = surface.kind;
  r.tube_radius = surface.tube_radius;
  r.center_radius = surface.center_radius;
  r.equatorial_radius = surface.equatorial_radius;
  r.polar_radius = surface.polar_radius;
  r.height = surface.height;
  r.width = surface.width;
  r.neck_radius = surface.neck_radius;
  return r;
}

std::span<const std::reference_wrapper<const RevolutionEntry>> revolution_catalog() {
  static const std::vector<std::reference_wrapper<const RevolutionEntry>> table = [] {
    std::vector<std::reference_wrapper<const RevolutionEntry>> rows;
    for (const SurfaceRow& row : kSurfaceCatalog)
      if (row.profile) rows.emplace_back(*row.profile);
    return rows;
  }();
  return table;
}

const RevolutionEntry& revolution_entry(SurfaceKind kind) {
  if (!offers(kind, Offer::profile_chart)) throw std::logic_error("revolution_entry: no profile chart");
  return *kSurfaceCatalog[static_cast<unsigned>(kind)].profile;
}

const RevolutionEntry* find_revolution(std::string_view name) {
  for (const RevolutionEntry& entry : revolution_catalog())
    if (entry.name == name) return &entry;
  return nullptr;
}

ProfileMetric profile_metric(const ProfilePoint& p) {
  ProfileMetric m;
  m.f = std::hypot(p.rho_u, p.z_u);
  m.f_u = (p.rho_u * p.rho_uu + p.z_u * p.z_uu) / m.f;
  m.C = p.rho_u / m.f;
  m.C_u = (p.rho_uu * m.f - p.rho_u * m.f_u) / (m.f * m.f);
  return m;
}

RevolutionFrame revolution_frame(const RevolutionSurface& surface, double u, double phi) {
  const ProfilePoint p = revolution_entry(surface.kind).profile(surface, u);
  const double f = std::hypot(p.rho_u, p.z_u);
  const double c = std::cos(phi), s = std::sin(phi);
  RevolutionFrame frame;
  frame.X = Vec3(p.rho * c, p.rho * s, p.z);
  frame.E1 = Vec3(p.rho_u * c, p.rho_u * s, p.z_u) / f;
  frame.E2 = Vec3(-s, c, 0.0);
  frame.n = Vec3(-p.z_u * c, -p.z_u * s, p.rho_u) / f;
  return frame;
}

ProfilePlace profile_place(const RevolutionSurface& surface, double u) {
  const RevolutionEntry& entry = revolution_entry(surface.kind);
  const ProfilePoint p = entry.profile(surface, u);
  const ProfileMetric m = profile_metric(p);
  const ProfileDomain d = entry.domain(surface);
  const bool axis = p.rho == 0.0 || (d.axis_at_min && u == d.u_min) || (d.axis_at_max && u == d.u_max);
  return {axis ? 0.0 : p.rho, m.C, m.f, axis};
}

double bordered_hessian_curvature(const ImplicitPoint& p) {
  Eigen::Matrix4d bordered = Eigen::Matrix4d::Zero();
  bordered.topLeftCorner<3, 3>() = p.hessian;
  bordered.topRightCorner<3, 1>() = p.gradient;
  bordered.bottomLeftCorner<1, 3>() = p.gradient.transpose();
  const double g2 = p.gradient.squaredNorm();
  return -bordered.determinant() / (g2 * g2);
}

}  // namespace spinfold
