// Drawing through a view (view_model.h): segments and polylines mapped to the view's world and
// lifted off its surface, the bodies' ellipses and arrows, the layers' colours, and the pieces of
// static geometry that several views share (geodesic grids, quads).
#pragma once

#include <numbers>
#include <string>
#include <vector>

#include "engine/chart.h"
#include "render/scene_builder.h"
#include "render/views/view_model.h"

namespace spinfold::render {

inline constexpr double kPi = std::numbers::pi;

// Colours of the layers.
inline const glm::vec4 kGridColor{0.45f, 0.52f, 0.62f, 1.0f};
// The tractricoid's seam and rim, and H²'s ideal boundary in the conformal view.
inline const glm::vec4 kSeamColor{0.80f, 0.35f, 0.55f, 1.0f};
inline constexpr float kFillAlpha = 0.55f;
inline const glm::vec4 kArrowColors[2] = {{0.85f, 0.10f, 0.10f, 1.0f}, {0.10f, 0.60f, 0.15f, 1.0f}};
// The drift layer's arrow (kDrift): a dark violet, apart from the frame's red and green.
inline const glm::vec4 kDriftColor = {0.42f, 0.18f, 0.62f, 1.0f};

// A number in a caption or label, printf-formatted ("%g" → "0.5").
std::string caption_number(const char* pattern, double value);

inline glm::vec3 to_float(const glm::dvec3& w) {
  return glm::vec3(w);
}
inline glm::vec4 rgba(const std::array<float, 3>& c, float alpha = 1.0f) {
  return {c[0], c[1], c[2], alpha};
}
// The outline of an ellipse: the main body's dark orange, a companion's own colour darkened by a
// quarter.
glm::vec4 outline_color(const BodySnapshot& body);

// A world point lifted off the view's surface along its normal by view.lift() (unchanged when 0).
glm::dvec3 lifted(const ViewModel& view, const Surface& surface, const glm::dvec3& w);

void add_segment(std::vector<Vertex>& lines, const glm::dvec3& a, const glm::dvec3& b,
                 const glm::vec4& color);

// A polyline through embedded points, mapped and lifted; segments with an end off the view are
// left out, and with `clip` those with an end far from it.
void add_polyline(std::vector<Vertex>& lines, const Surface& surface, const ViewModel& view,
                  const std::vector<Vec3>& points, const glm::vec4& color, bool closed,
                  const Window2d* clip = nullptr);

// The same (open) with a colour per point, each segment shading from its first point's to its last's.
void add_polyline(std::vector<Vertex>& lines, const Surface& surface, const ViewModel& view,
                  const std::vector<Vec3>& points, const std::vector<glm::vec4>& colors,
                  const Window2d* clip = nullptr);

// The same polyline dashed: kDash on, kGap off, measured along the drawn (world) path, so that the
// dashes keep their length however densely the path is sampled.
void add_dashed_polyline(std::vector<Vertex>& lines, const Surface& surface, const ViewModel& view,
                         const std::vector<Vec3>& points, const glm::vec4& color,
                         const Window2d* clip = nullptr);

// exp_X(a e₁ + b e₂) of a body's frame, with the vector's intrinsic length from the Gram matrix.
Vec3 exp_frame(const Surface& surface, const BodySnapshot& body, double a, double b);

// A body's ellipse drawn on the view's surface: a translucent fill following the surface (rings)
// and its outline.
void add_body(FrameScene& scene, const Surface& surface, const ViewModel& view, double scale,
              const BodySnapshot& body);
// A body's frame arrows e₁ (red) and e₂ (green): geodesic shafts, barbs in the tangent plane.
void add_frame_arrows(FrameScene& scene, const Surface& surface, const ViewModel& view, double scale,
                      const BodySnapshot& body);
// The drift layer's arrow at a body whose guiding centre drifts (BodySnapshot::drift), kDriftColor.
void add_drift_arrow(FrameScene& scene, const Surface& surface, const ViewModel& view, double scale,
                     const BodySnapshot& body);

// Two triangles a b c, a c d.
void add_quad(StaticGeometry& g, const LitVertex& a, const LitVertex& b, const LitVertex& c,
              const LitVertex& d);

// A grid curve: the polyline through point_at(s) (embedded points of `unit`) at s = 0, 1/segments,
// …, 1, in the grid's colour.
template <class PointAt>
void add_grid_curve(std::vector<Vertex>& grid, const Surface& unit, const ViewModel& view, PointAt point_at,
                    int segments) {
  std::vector<Vec3> pts;
  for (int i = 0; i <= segments; ++i) pts.push_back(point_at(static_cast<double>(i) / segments));
  add_polyline(grid, unit, view, pts, kGridColor, false);
}

// H²'s geodesic polar grid about the pole: circles r = 0.5, 1, … up to `extent` [radii] with
// `around` segments each, and radial geodesics every 30° with `out` segments each.
void add_geodesic_polar_grid(std::vector<Vertex>& grid, const Surface& unit, const ViewModel& view,
                             double extent, int around, int out);

}  // namespace spinfold::render
