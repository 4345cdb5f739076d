// The flat plane, in a window that follows the body; its grid stays put in the world.
#include <cmath>

#include "render/views/camera.h"
#include "render/views/drawing.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

// The window: kPlaneHalfHeight about view.target's (x, y), else the origin.
Window2d plane_window(const ViewOptions& view) {
  return window_around(view, target_or(view, glm::dvec2(0.0)), kPlaneHalfHeight);
}

// The grid across the frame: lines at whole multiples of kPlaneGridSpacing, so that the grid
// stays put in the world while the frame follows the body.
std::vector<Vertex> plane_grid(const ViewOptions& view) {
  const Window2d w = plane_window(view);
  const double x0 = w.centre.x - w.hx, x1 = w.centre.x + w.hx, y0 = w.centre.y - w.hy, y1 = w.centre.y + w.hy;
  std::vector<Vertex> lines;
  // Counted, at most 2000 lines each way (a window far out, where ++k no longer moves k, or a huge
  // one, drew for ever; issue 48's hunt).
  for (double k = std::floor(x0 / kPlaneGridSpacing), n = 0;
       k <= std::ceil(x1 / kPlaneGridSpacing) && n < 2000; ++k, ++n)
    add_segment(lines, {k * kPlaneGridSpacing, y0 - 1.0, 0}, {k * kPlaneGridSpacing, y1 + 1.0, 0},
                kGridColor);
  for (double k = std::floor(y0 / kPlaneGridSpacing), n = 0;
       k <= std::ceil(y1 / kPlaneGridSpacing) && n < 2000; ++k, ++n)
    add_segment(lines, {x0 - 1.0, k * kPlaneGridSpacing, 0}, {x1 + 1.0, k * kPlaneGridSpacing, 0},
                kGridColor);
  return lines;
}

class PlaneView final : public ViewModel {
 public:
  // X/R.
  glm::dvec3 world_position(const Surface& surface, const Vec3& X) const override {
    const double R = surface.radius;
    return glm::dvec3(X.x() / R, X.y() / R, 0.0);
  }
  // No static geometry: the plane is the whole frame (cleared to its colour) and its grid follows
  // the camera.
  void add_background(FrameScene& scene, const Surface& /*surface*/, const ViewOptions& view) const override {
    if (scene.draw_surface) scene.clear_color = scene.surface_color;
    if (scene.draw_grid) scene.grid_lines = plane_grid(view);
  }
  glm::mat4 camera(const ViewOptions& view) const override { return window_camera(plane_window(view)); }
  void aim(ViewOptions& view, const Snapshot& snapshot, const HudLayout& /*hud*/) const override {
    aim_at_bodies_centre(*this, view, snapshot);
  }
  std::string grid_caption(const Snapshot& snapshot, const ViewOptions& /*view*/) const override {
    return "Grid: lines every " + caption_number("%g", kPlaneGridSpacing) +
           " R (R = " + caption_number("%g", snapshot.surface.radius) + ").";
  }
  FigureScale figure_scale() const override { return FigureScale::scale_bar; }
};

}  // namespace

const ViewModel& plane_view() {
  static const PlaneView view;
  return view;
}

}  // namespace spinfold::render
