// The Beltrami–Klein disk (H²): geodesics are straight chords; angles and shapes are not true.
#include <cmath>

#include "render/views/camera.h"
#include "render/views/drawing.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

class KleinView final : public ViewModel {
 public:
  // (X₁, X₂)/X₃: the central projection of the hyperboloid onto the plane X₃ = R (in radii).
  glm::dvec3 world_position(const Surface& /*surface*/, const Vec3& X) const override {
    return glm::dvec3(X.x() / X.z(), X.y() / X.z(), 0.0);
  }

  // The unit disk and its rim, and H²'s polar grid out to r = 6.
  StaticGeometry build_static(const Surface& surface) const override {
    const SurfaceKind kind = surface.kind;
    StaticGeometry g;
    const int slices = kRimSlices;
    for (int j = 0; j < slices; ++j) {
      const double p0 = 2 * kPi * j / slices, p1 = 2 * kPi * (j + 1) / slices;
      g.surface.push_back({{0, 0, 0}, {0, 0, 1}});
      g.surface.push_back({glm::vec3(std::cos(p0), std::sin(p0), 0), {0, 0, 1}});
      g.surface.push_back({glm::vec3(std::cos(p1), std::sin(p1), 0), {0, 0, 1}});
      add_segment(g.grid, {std::cos(p0), std::sin(p0), 0}, {std::cos(p1), std::sin(p1), 0}, kGridColor);
    }
    add_geodesic_polar_grid(g.grid, Surface{kind, 1.0}, *this, 6.0, kRimSlices / 2, 64);
    return g;
  }

  // The unit disk and a margin, or a close-up of the bodies near its rim, or slid clear of the
  // boxes (aim_2d_window).
  glm::mat4 camera(const ViewOptions& view) const override {
    return window_camera(zoomed_window(view, glm::dvec2(0.0), kDiskWindowHalf));
  }
  void aim(ViewOptions& view, const Snapshot& snapshot, const HudLayout& hud) const override {
    aim_2d_window(*this, view, snapshot, hud, kDiskWindowHalf);
  }
  std::string grid_caption(const Snapshot& /*snapshot*/, const ViewOptions& /*view*/) const override {
    return "Grid: geodesic circles about the pole, labelled with their radius r; radial geodesics every 30 "
           "degrees.";
  }
  FigureScale figure_scale() const override { return FigureScale::circle_labels; }
};

}  // namespace

const ViewModel& klein_view() {
  static const KleinView view;
  return view;
}

}  // namespace spinfold::render
