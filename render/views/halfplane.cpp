// The Poincaré upper half-plane (H²): angles true, geodesics semicircles on the boundary or
// vertical lines; the window follows the body at its height.
#include <algorithm>
#include <cmath>

#include "render/views/camera.h"
#include "render/views/drawing.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

// The window: from just below y = 0 to twice the centre's height (a window that scales with the
// height is the same picture at any height); the centre is view.target's (x, y), else (0, 1).
Window2d halfplane_window(const ViewOptions& view) {
  const glm::dvec2 centre = target_or(view, glm::dvec2(0.0, 1.0));
  return window_around(view, centre, 1.08 * centre.y);
}

class HalfPlaneView final : public ViewModel {
 public:
  glm::dvec3 world_position(const Surface& surface, const Vec3& X) const override {
    return glm::dvec3(half_plane_point(surface, X), 0.0);
  }

  // y > 0 and its boundary y = 0, and H²'s polar grid out to r = 6 (the half-plane magnifies by
  // e^r towards one side: its circles need more points).
  StaticGeometry build_static(const Surface& surface) const override {
    const SurfaceKind kind = surface.kind;
    StaticGeometry g;
    constexpr float far = 1e4f;
    for (const glm::vec2 c : {glm::vec2(-far, 0), glm::vec2(far, 0), glm::vec2(far, far), glm::vec2(-far, 0),
                              glm::vec2(far, far), glm::vec2(-far, far)})
      g.surface.push_back({glm::vec3(c, 0.0f), {0, 0, 1}});
    add_segment(g.grid, {-far, 0, 0}, {far, 0, 0}, kGridColor);
    add_geodesic_polar_grid(g.grid, Surface{kind, 1.0}, *this, 6.0, 512, 256);
    return g;
  }

  glm::mat4 camera(const ViewOptions& view) const override { return window_camera(halfplane_window(view)); }

  // Centred across the bodies and their recent trails, at a height that keeps the highest of
  // them and the widest spread in the window (which spans y ∈ (−0.08, 2.16)·centre height), and
  // never below the main body's (which is then drawn as large as at the centre, or smaller).
  void aim(ViewOptions& view, const Snapshot& snapshot, const HudLayout& /*hud*/) const override {
    const std::vector<Sight> points = sights(*this, snapshot, view, true);
    const double main = points.front().at.y;
    double lo = points.front().at.x, hi = lo, top = main;
    for (const Sight& p : points)
      lo = std::min(lo, p.at.x), hi = std::max(hi, p.at.x), top = std::max(top, p.at.y);
    const double aspect = static_cast<double>(view.width) / view.height;
    const double height = std::max({main, top / 1.9, (hi - lo) / (2.0 * 0.9 * 1.08 * std::max(1.0, aspect))});
    view.target = std::array<double, 3>{0.5 * (lo + hi), height, 0.0};
  }
  std::string grid_caption(const Snapshot& /*snapshot*/, const ViewOptions& /*view*/) const override {
    return "Grid: geodesic circles about the pole, labelled with their radius r; radial geodesics every 30 "
           "degrees.";
  }
  FigureScale figure_scale() const override { return FigureScale::circle_labels; }
};

}  // namespace

glm::dvec2 half_plane_point(const Surface& surface, const Vec3& X) {
  const double R = surface.radius;
  const double k = (X.z() + X.x()) / (R * R + X.y() * X.y());
  return {-X.y() * k, R * k};
}

const ViewModel& halfplane_view() {
  static const HalfPlaneView view;
  return view;
}

}  // namespace spinfold::render
