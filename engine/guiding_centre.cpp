#include "engine/guiding_centre.h"

#include <cmath>
#include <variant>

#include "engine/readout.h"
#include "engine/revolution.h"
#include "engine/surface.h"

namespace spinfold {

std::optional<GuidingDrift> guiding_drift(const Simulation& run) {
  const Scene& scene = run.scene;
  if (!offers(scene.surface.kind, Offer::profile_chart) || scene.friction ||
      !std::holds_alternative<std::monostate>(scene.potential.height))
    return std::nullopt;
  const RevolutionSurface rs = revolution_surface(scene.surface);
  const RevolutionEntry& entry = revolution_entry(rs.kind);
  const Readout r = readout(run);
  const double u = r.coordinates.r, phi = r.coordinates.phi.value_or(0.0);
  const ProfilePoint p = entry.profile(rs, u);
  const double feature = entry.picture(rs).feature, m = scene.body.mass, s = r.spin;
  const double v = std::sqrt(std::max(0.0, 2.0 * r.energy_orbital / m));
  if (p.rho <= 1e-9 * feature || s * p.K == 0.0) return std::nullopt;
  const double h = 1e-5 * feature;  // K_u by central difference: K is smooth in u
  const double K_u = (entry.profile(rs, u + h).K - entry.profile(rs, u - h).K) / (2.0 * h);
  GuidingDrift d;
  d.larmor_radius = m * v / std::abs(s * p.K);
  if (K_u == 0.0 || !(d.larmor_radius < 0.25 * feature)) return std::nullopt;
  const double f = profile_metric(p).f;
  d.phi_rate = -m * v * v * K_u / (2.0 * s * p.K * p.K * f * p.rho);
  d.direction = std::copysign(1.0, d.phi_rate) * Vec3(-std::sin(phi), std::cos(phi), 0.0);
  return d;
}

}  // namespace spinfold
