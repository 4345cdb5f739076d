// The Poincaré disk (H²) or the stereographic plane (S²): one flat map, angles true.
#include <cmath>

#include "render/views/camera.h"
#include "render/views/drawing.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

class DiskView final : public ViewModel {
 public:
  // Poincaré disk (H²) or stereographic projection from the south pole (S²): (X₁, X₂)/(R + X₃).
  // Far out on H² both grow like e^{r/R} and the ratio stays below 1 without overflow.
  glm::dvec3 world_position(const Surface& surface, const Vec3& X) const override {
    const double d = surface.radius + X.z();
    return glm::dvec3(X.x() / d, X.y() / d, 0.0);
  }

  // The disk |w| < 1 of H² with its polar grid and rim, or the sphere's map out to |w| = 3 with
  // parallels down to 150° and meridians every 30°.
  StaticGeometry build_static(const Surface& surface) const override {
    const SurfaceKind kind = surface.kind;
    StaticGeometry g;
    const Surface unit{kind, 1.0};
    if (offers(kind, Offer::negative_curvature))
      add_geodesic_polar_grid(g.grid, unit, *this, 6.0, kRimSlices / 2, 64);
    const double radius = offers(kind, Offer::negative_curvature) ? 1.0 : 3.0;
    const int slices = kRimSlices;
    for (int j = 0; j < slices; ++j) {
      const double p0 = 2 * kPi * j / slices, p1 = 2 * kPi * (j + 1) / slices;
      const LitVertex c{{0, 0, 0}, {0, 0, 1}};
      g.surface.push_back(c);
      g.surface.push_back({glm::vec3(radius * std::cos(p0), radius * std::sin(p0), 0), {0, 0, 1}});
      g.surface.push_back({glm::vec3(radius * std::cos(p1), radius * std::sin(p1), 0), {0, 0, 1}});
    }
    if (offers(kind, Offer::positive_curvature)) {
      for (int k = 1; k < 10; ++k)  // parallels down to 150°
        add_grid_curve(
            g.grid, unit, *this, [&](double s) { return chart_point(unit, kPi * k / 12, 2 * kPi * s).X; },
            128);
      for (int k = 0; k < 12; ++k)
        add_grid_curve(
            g.grid, unit, *this,
            [&](double s) { return chart_point(unit, kPi * 0.8 * s, 2 * kPi * k / 12).X; }, 64);
    } else {
      for (int j = 0; j < slices; ++j) {  // the rim
        const double p0 = 2 * kPi * j / slices, p1 = 2 * kPi * (j + 1) / slices;
        add_segment(g.grid, {std::cos(p0), std::sin(p0), 0}, {std::cos(p1), std::sin(p1), 0}, kGridColor);
      }
    }
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
  std::string grid_caption(const Snapshot& snapshot, const ViewOptions& /*view*/) const override {
    return offers(snapshot.surface, Offer::positive_curvature)
               ? "Grid: geodesic circles about the pole (parallels "
                 "every 15 degrees); meridians every 30 degrees."
               : "Grid: geodesic circles about the pole, labelled "
                 "with their radius r; radial geodesics every 30 "
                 "degrees.";
  }
  FigureScale figure_scale() const override { return FigureScale::circle_labels; }
};

}  // namespace

const ViewModel& disk_view() {
  static const DiskView view;
  return view;
}

}  // namespace spinfold::render
