// The chart (u, φ) of a surface of revolution whose curvature varies, unrolled flat: φ across from
// −π to π, u down the drawn range (the torus's tube angle from −π to π, the spheroid's polar angle
// from the north pole, the distance from the bump's axis, −z on the catenoid), the background
// coloured by K band by band (warm > 0, white 0, cool < 0) with the K = 0 parallels dark. Lengths
// and angles are not true (a parallel of radius ρ is drawn as long as any other): it is the picture
// of the coordinates a researcher plots, beside the surface in space (the revolution view).
#include <cmath>

#include "render/views/camera.h"
#include "render/views/drawing.h"
#include "render/views/profile_drawing.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

// Bands of the background and segments of its grid lines.
constexpr int kBands = 96, kSegments = 72;
// The chart fills [−1, 1]²; the window leaves a margin round it.
constexpr double kChartHalfHeight = 1.08;

// (φ/π, 1 − 2(u − u_min)/(u_max − u_min)): u_min at the top.
glm::dvec3 chart_position(const ProfilePicture& picture, double u, double phi) {
  return {phi / kPi, 1.0 - 2.0 * (u - picture.u_min) / (picture.u_max - picture.u_min), 0.0};
}

class ChartView final : public ViewModel {
 public:
  glm::dvec3 world_position(const Surface& surface, const Vec3& X) const override {
    const ProfileShape shape = profile_shape(surface);
    return chart_position(shape.picture, shape.entry->u_of(shape.surface, X), std::atan2(X.y(), X.x()));
  }
  bool on_view(const Surface& surface, const Vec3& X) const override { return on_drawn_piece(surface, X); }
  std::string_view off_view_note(const Surface& surface, const Vec3& X) const override {
    return off_drawn_piece_note(surface, X);
  }
  // A step of more than a quarter of the width: across the seam (or over an axis point, where φ jumps).
  bool torn(const glm::dvec3& a, const glm::dvec3& b) const override { return std::abs(a.x - b.x) > 0.5; }

  // The background bands (each vertex's tint the curvature colour of K at its u; the surface's own
  // colour without the curvature layer) and the grid: meridians every 30°, the picture's parallels,
  // the K = 0 parallels dark.
  StaticGeometry build_static(const Surface& surface) const override {
    const ProfileShape shape = profile_shape(surface);
    const ProfilePicture& p = shape.picture;
    const double full = largest_curvature(shape, kBands);
    StaticGeometry g;
    const auto vertex = [&](double u, double x) {
      const glm::dvec3 w = chart_position(p, u, x * kPi);
      return LitVertex{to_float(w), {0.0f, 0.0f, 1.0f}, curvature_color(shape.K(u), full)};
    };
    for (int i = 0; i < kBands; ++i) {
      const double u0 = p.u_min + (p.u_max - p.u_min) * i / kBands;
      const double u1 = p.u_min + (p.u_max - p.u_min) * (i + 1) / kBands;
      add_quad(g, vertex(u0, -1.0), vertex(u1, -1.0), vertex(u1, 1.0), vertex(u0, 1.0));
    }
    const auto line = [&](glm::dvec3 a, glm::dvec3 b, const glm::vec4& color) {
      for (int k = 0; k < kSegments; ++k)
        add_segment(g.grid, glm::mix(a, b, static_cast<double>(k) / kSegments),
                    glm::mix(a, b, static_cast<double>(k + 1) / kSegments), color);
    };
    for (int k = -6; k <= 6; ++k)
      line(chart_position(p, p.u_min, kPi * k / 6), chart_position(p, p.u_max, kPi * k / 6), kGridColor);
    for (const double u : grid_parallels(shape))
      line(chart_position(p, u, -kPi), chart_position(p, u, kPi), kGridColor);
    for (const double u : zero_curvature_parallels(shape))
      line(chart_position(p, u, -kPi), chart_position(p, u, kPi), kZeroCurvatureColor);
    return g;
  }

  // The background is the curvature, whatever the layers say: the chart's point.
  void add_background(FrameScene& scene, const Surface& /*surface*/,
                      const ViewOptions& /*view*/) const override {
    scene.tint_by_curvature = true;
  }
  glm::mat4 camera(const ViewOptions& view) const override {
    return window_camera(zoomed_window(view, glm::dvec2(0.0), kChartHalfHeight));
  }
  // The whole chart, slid or drawn back when a body is under the HUD or the legend.
  void aim(ViewOptions& view, const Snapshot& snapshot, const HudLayout& hud) const override {
    aim_2d_window(*this, view, snapshot, hud, kChartHalfHeight);
  }
  double body_scale_length(const Surface& surface) const override {
    return profile_shape(surface).picture.feature;
  }
  std::string grid_caption(const Snapshot& /*snapshot*/, const ViewOptions& /*view*/) const override {
    return "Chart: phi across (-pi to pi), u down; the background coloured by the Gaussian curvature K (warm "
           "> 0, "
           "cool < 0, white 0); meridians every 30 degrees, parallels, the K = 0 parallels darker.";
  }
};

}  // namespace

const ViewModel& chart_view() {
  static const ChartView view;
  return view;
}

}  // namespace spinfold::render
