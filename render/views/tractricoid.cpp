// Beltrami's pseudosphere in ℝ³: the horocyclic strip y' ≥ 1 of the half-plane wrapped round its
// axis (world_position in scene_builder.h), ending at its rim u = 0.
#include <algorithm>
#include <cmath>

#include "render/views/camera.h"
#include "render/views/drawing.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

// Overlays sit this far [radii] above the surface so that the depth test keeps them.
constexpr double kLift = 0.004;
// The surface drawn: ρ = R sech u, z = R(u − tanh u) for 0 ≤ u ≤ kTractricoidExtent.
constexpr double kTractricoidExtent = 5.0;

// The outward unit normal at a world point (ρ cos θ, ρ sin θ, z), ρ = sech u:
// (tanh u cos θ, tanh u sin θ, sech u).
glm::dvec3 tractricoid_normal(const glm::dvec3& w) {
  const double rho = std::min(1.0, glm::length(glm::dvec2(w)));
  const double t = std::sqrt(std::max(0.0, 1.0 - rho * rho));  // tanh u
  const glm::dvec2 radial = rho > 0.0 ? glm::dvec2(w) / rho : glm::dvec2(1.0, 0.0);
  return {t * radial.x, t * radial.y, rho};
}

class TractricoidView final : public ViewModel {
 public:
  // The covering map of the strip y' = kTractricoidDilation·y ≥ 1: θ = x', ρ = R/y',
  // z = R(arcosh y' − √(1 − 1/y'²)); points below the strip land in the rim's plane.
  glm::dvec3 world_position(const Surface& surface, const Vec3& X) const override {
    const glm::dvec2 h = kTractricoidDilation * half_plane_point(surface, X);
    const double rho = 1.0 / h.y;
    const double z = h.y >= 1.0 ? std::acosh(h.y) - std::sqrt(1.0 - rho * rho) : 0.0;
    return {rho * std::cos(h.x), rho * std::sin(h.x), z};
  }
  bool on_view(const Surface& surface, const Vec3& X) const override {
    return kTractricoidDilation * half_plane_point(surface, X).y >= 1.0;
  }
  std::string_view off_view_note(const Surface& /*surface*/, const Vec3& /*X*/) const override {
    return "body 1 is beyond the rim: off the part of H2 this surface shows";
  }
  glm::dvec3 normal(const Surface& /*surface*/, const glm::dvec3& w) const override {
    return tractricoid_normal(w);
  }
  double lift() const override { return kLift; }

  // The surface of revolution, with its meridians (geodesics) every 30° and its parallels
  // (horocycles) every 0.5 in u; the seam and the rim (u = 0, where the surface ends) marked.
  StaticGeometry build_static(const Surface& surface) const override {
    StaticGeometry g;
    const int rings = 80, slices = 72;
    const auto at = [](double u, double theta) {
      const double rho = 1.0 / std::cosh(u);
      return glm::dvec3(rho * std::cos(theta), rho * std::sin(theta), u - std::tanh(u));
    };
    const auto vertex = [&](double u, double theta) {
      const glm::dvec3 w = at(u, theta);
      return LitVertex{to_float(w), to_float(tractricoid_normal(w))};
    };
    const auto u_of = [](int i) {
      return kTractricoidExtent * std::pow(static_cast<double>(i) / rings, 1.5);
    };
    for (int i = 0; i < rings; ++i)
      for (int j = 0; j < slices; ++j) {
        const double t0 = 2 * kPi * j / slices, t1 = 2 * kPi * (j + 1) / slices;
        add_quad(g, vertex(u_of(i), t0), vertex(u_of(i + 1), t0), vertex(u_of(i + 1), t1),
                 vertex(u_of(i), t1));
      }
    const auto curve = [&](auto point_at, int segments, const glm::vec4& color) {
      for (int i = 0; i < segments; ++i)
        add_segment(g.grid, lifted(*this, surface, point_at(static_cast<double>(i) / segments)),
                    lifted(*this, surface, point_at(static_cast<double>(i + 1) / segments)), color);
    };
    for (int k = 0; k < 12; ++k) {
      const double theta = 2 * kPi * k / 12;
      curve([&](double s) { return at(kTractricoidExtent * s * s, theta); }, 64,
            k == 6 ? kSeamColor : kGridColor);
    }
    for (double u = 0.0; u <= 3.0 + 1e-9; u += 0.5)
      curve([&](double s) { return at(u, 2 * kPi * s); }, 128, u == 0.0 ? kSeamColor : kGridColor);
    return g;
  }

  // By default orbiting a point on the axis above the rim.
  glm::mat4 camera(const ViewOptions& view) const override { return orbit_camera(view, orbit_home()); }
  glm::dvec3 orbit_home() const override { return glm::dvec3(0, 0, 0.8); }
  // From the bodies' own side (the far side faces away), the rim's neighbourhood at least.
  void aim(ViewOptions& view, const Snapshot& snapshot, const HudLayout& hud) const override {
    aim_orbit(*this, view, snapshot, hud, 0.9, 0.35, 0.0);
  }
  std::string grid_caption(const Snapshot& /*snapshot*/, const ViewOptions& /*view*/) const override {
    return "Grid: meridians (geodesics) every 30 degrees, parallels (horocycles).";
  }
};

}  // namespace

const ViewModel& tractricoid_view() {
  static const TractricoidView view;
  return view;
}

}  // namespace spinfold::render
