#include "render/views/drawing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace spinfold::render {

namespace {

// The geodesic companion's trail: dashes and gaps of these lengths [world units, radii].
constexpr double kDash = 0.045, kGap = 0.03;
constexpr int kMaxDashes = 4096;  // ~300 world units of one segment: several hundred frames across

// The body-frame vector a e₁ + b e₂ and its intrinsic length from the Gram matrix.
struct FrameVector {
  Vec3 v;
  double length;
};
FrameVector frame_vector(const BodySnapshot& s, double a, double b) {
  const double q = s.gram(0, 0) * a * a + 2.0 * s.gram(0, 1) * a * b + s.gram(1, 1) * b * b;
  return {a * s.e[0] + b * s.e[1], std::sqrt(std::max(0.0, q))};
}

}  // namespace

glm::vec4 outline_color(const BodySnapshot& body) {
  if (body.color == kMainBodyColor) return {0.70f, 0.30f, 0.02f, 1.0f};
  return {0.75f * body.color[0], 0.75f * body.color[1], 0.75f * body.color[2], 1.0f};
}

glm::dvec3 lifted(const ViewModel& view, const Surface& surface, const glm::dvec3& w) {
  const double lift = view.lift();
  return lift != 0.0 ? w + lift * view.normal(surface, w) : w;
}

void add_segment(std::vector<Vertex>& lines, const glm::dvec3& a, const glm::dvec3& b,
                 const glm::vec4& color) {
  lines.push_back({to_float(a), color});
  lines.push_back({to_float(b), color});
}

void add_polyline(std::vector<Vertex>& lines, const Surface& surface, const ViewModel& view,
                  const std::vector<Vec3>& points, const glm::vec4& color, bool closed,
                  const Window2d* clip) {
  for (std::size_t i = 0; i + 1 < points.size() + (closed ? 1 : 0); ++i) {
    const Vec3& a = points[i];
    const Vec3& b = points[(i + 1) % points.size()];
    if (!view.draws(surface, a) || !view.draws(surface, b)) continue;
    const glm::dvec3 wa = lifted(view, surface, view.world_position(surface, a)),
                     wb = lifted(view, surface, view.world_position(surface, b));
    if (clip && !(clip->near(glm::dvec2(wa)) && clip->near(glm::dvec2(wb)))) continue;
    if (view.torn(wa, wb)) continue;
    add_segment(lines, wa, wb, color);
  }
}

void add_polyline(std::vector<Vertex>& lines, const Surface& surface, const ViewModel& view,
                  const std::vector<Vec3>& points, const std::vector<glm::vec4>& colors,
                  const Window2d* clip) {
  for (std::size_t i = 0; i + 1 < points.size() && i + 1 < colors.size(); ++i) {
    const Vec3& a = points[i];
    const Vec3& b = points[i + 1];
    if (!view.draws(surface, a) || !view.draws(surface, b)) continue;
    const glm::dvec3 wa = lifted(view, surface, view.world_position(surface, a)),
                     wb = lifted(view, surface, view.world_position(surface, b));
    if (clip && !(clip->near(glm::dvec2(wa)) && clip->near(glm::dvec2(wb)))) continue;
    if (view.torn(wa, wb)) continue;
    lines.push_back({to_float(wa), colors[i]});
    lines.push_back({to_float(wb), colors[i + 1]});
  }
}

void add_dashed_polyline(std::vector<Vertex>& lines, const Surface& surface, const ViewModel& view,
                         const std::vector<Vec3>& points, const glm::vec4& color, const Window2d* clip) {
  double phase = 0.0;  // distance into the current dash + gap period
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    if (!view.draws(surface, points[i]) || !view.draws(surface, points[i + 1])) continue;
    const glm::dvec3 a = lifted(view, surface, view.world_position(surface, points[i]));
    const glm::dvec3 b = lifted(view, surface, view.world_position(surface, points[i + 1]));
    if (clip && !(clip->near(glm::dvec2(a)) && clip->near(glm::dvec2(b)))) continue;
    if (view.torn(a, b)) continue;
    const double length = glm::length(b - a);
    if (!std::isfinite(length)) continue;
    // At most kMaxDashes dash periods of a segment, from its start: a longer one (a geodesic
    // companion run off to r = 250 R on the hyperboloid, ~1e108 world units) reaches far outside any
    // frame, and dashing it whole never ended (issue 48's hunt: a frame took ~1 GB/s).
    double done = 0.0;
    for (int pieces = 0; done < length && pieces < 2 * kMaxDashes; ++pieces) {
      const bool on = phase < kDash;
      const double step = std::min(length - done, (on ? kDash : kDash + kGap) - phase);
      if (on)
        add_segment(lines, a + (b - a) * (done / length), a + (b - a) * ((done + step) / length), color);
      done += step;
      phase += step;
      if (phase >= kDash + kGap) phase = 0.0;
    }
  }
}

Vec3 exp_frame(const Surface& surface, const BodySnapshot& body, double a, double b) {
  const FrameVector f = frame_vector(body, a, b);
  return exponential_map(surface, body.X, f.v, f.length);
}

void add_body(FrameScene& scene, const Surface& surface, const ViewModel& view, double scale,
              const BodySnapshot& body) {
  const glm::vec4 fill = rgba(body.color, kFillAlpha);
  const std::vector<Vec3> outline = ellipse_points(surface, body, scale, 64);
  // The fill follows the surface: rings at 1/8, 2/8, … of the way out (a flat fan would sink
  // below the sphere's surface and vanish under the depth test).
  constexpr int kRings = 8;
  const auto ring_point = [&](int ring, std::size_t i) {
    const double theta = 2 * kPi * static_cast<double>(i % outline.size()) / outline.size();
    const double f = scale * ring / kRings;
    return to_float(lifted(
        view, surface,
        view.world_position(surface, exp_frame(surface, body, f * std::cos(theta), f * std::sin(theta)))));
  };
  for (int ring = 0; ring < kRings; ++ring)
    for (std::size_t i = 0; i < outline.size(); ++i) {
      const glm::vec3 a = ring_point(ring, i), b = ring_point(ring + 1, i), c = ring_point(ring + 1, i + 1),
                      d = ring_point(ring, i + 1);
      if (view.torn(glm::dvec3(a), glm::dvec3(c)) || view.torn(glm::dvec3(b), glm::dvec3(d)))
        continue;  // an ellipse across the chart's seam: its quads there
      scene.fills.insert(scene.fills.end(), {{a, fill}, {b, fill}, {c, fill}});
      if (ring > 0) scene.fills.insert(scene.fills.end(), {{a, fill}, {c, fill}, {d, fill}});
    }
  add_polyline(scene.lines, surface, view, outline, outline_color(body), true);
}

void add_frame_arrows(FrameScene& scene, const Surface& surface, const ViewModel& view, double scale,
                      const BodySnapshot& body) {
  for (int a = 0; a < 2; ++a) {
    std::vector<Vec3> shaft;
    for (int i = 0; i <= 16; ++i) {
      const double f = scale * 1.3 * i / 16;
      shaft.push_back(exp_frame(surface, body, a == 0 ? f : 0.0, a == 0 ? 0.0 : f));
    }
    add_polyline(scene.lines, surface, view, shaft, kArrowColors[a], false);
    // Arrowhead in world space: two barbs back from the tip, in the surface's tangent plane.
    const glm::dvec3 tip = lifted(view, surface, view.world_position(surface, shaft.back()));
    const glm::dvec3 before = lifted(view, surface, view.world_position(surface, shaft[12]));
    const glm::dvec3 back = before - tip;
    if (glm::length(back) > 0.0) {
      const glm::dvec3 normal = view.normal(surface, tip);
      const glm::dvec3 side = 0.45 * glm::length(back) * glm::normalize(glm::cross(normal, back));
      add_segment(scene.lines, tip, before + side, kArrowColors[a]);
      add_segment(scene.lines, tip, before - side, kArrowColors[a]);
    }
  }
}

// The drift arrow: from the body's centre along its drift, 2.2× the body's drawn size, on the
// surface (the exponential map), its head in the tangent plane.
void add_drift_arrow(FrameScene& scene, const Surface& surface, const ViewModel& view, double scale,
                     const BodySnapshot& body) {
  if (!body.drift) return;
  std::vector<Vec3> shaft;
  for (int i = 0; i <= 16; ++i) {
    const double f = scale * 2.2 * i / 16;
    shaft.push_back(exponential_map(surface, body.X, *body.drift * f, f));
  }
  add_polyline(scene.lines, surface, view, shaft, kDriftColor, false);
  const glm::dvec3 tip = lifted(view, surface, view.world_position(surface, shaft.back()));
  const glm::dvec3 before = lifted(view, surface, view.world_position(surface, shaft[12]));
  const glm::dvec3 back = before - tip;
  if (glm::length(back) > 0.0) {
    const glm::dvec3 side =
        0.5 * glm::length(back) * glm::normalize(glm::cross(view.normal(surface, tip), back));
    add_segment(scene.lines, tip, before + side, kDriftColor);
    add_segment(scene.lines, tip, before - side, kDriftColor);
  }
}

void add_quad(StaticGeometry& g, const LitVertex& a, const LitVertex& b, const LitVertex& c,
              const LitVertex& d) {
  g.surface.insert(g.surface.end(), {a, b, c, a, c, d});
}

void add_geodesic_polar_grid(std::vector<Vertex>& grid, const Surface& unit, const ViewModel& view,
                             double extent, int around, int out) {
  for (double r = 0.5; r <= extent + 1e-9; r += 0.5)
    add_grid_curve(
        grid, unit, view, [&](double s) { return chart_point(unit, r, 2 * kPi * s).X; }, around);
  for (int k = 0; k < 12; ++k)
    add_grid_curve(
        grid, unit, view, [&](double s) { return chart_point(unit, extent * s, 2 * kPi * k / 12).X; }, out);
}

// The default bodies: every body the view draws, ellipses first, then arrows.
void ViewModel::add_bodies(FrameScene& scene, const Snapshot& snapshot, const ViewOptions& view) const {
  const Surface& surface = snapshot.surface;
  // The companions first, the main body last: where they overlap (a geodesic companion at the
  // same start) the main body is on top, under the page's drag ring.
  if (view.layers & kBody)
    for (auto body = snapshot.bodies.rbegin(); body != snapshot.bodies.rend(); ++body)
      if (draws(surface, body->X))
        add_body(scene, surface, *this, body_drawing_scale(surface, *body, view.scale), *body);
  if (view.layers & kFrame)
    for (auto body = snapshot.bodies.rbegin(); body != snapshot.bodies.rend(); ++body)
      if (draws(surface, body->X))
        add_frame_arrows(scene, surface, *this, body_drawing_scale(surface, *body, view.scale), *body);
  if (view.layers & kDrift)
    for (auto body = snapshot.bodies.rbegin(); body != snapshot.bodies.rend(); ++body)
      if (draws(surface, body->X))
        add_drift_arrow(scene, surface, *this, body_drawing_scale(surface, *body, view.scale), *body);
}

double ViewModel::body_drawing_scale(const Surface& surface, const BodySnapshot& body, double scale) const {
  return drawn_scale(surface, body, scale);
}

std::string caption_number(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

}  // namespace spinfold::render
