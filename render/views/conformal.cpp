// Every surface in one flat map, continuous in K (conformal_radius in scene_builder.h):
// stereographic (K > 0), the plane itself (K = 0), the Poincaré disk (K < 0), in lengths and
// following the body.
#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/integer_cast.h"
#include "render/views/camera.h"
#include "render/views/drawing.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

// The window: kPlaneHalfHeight [length] about view.target's (x, y), else the origin, as the
// plane view's, so that at K = 0 the two are the same picture; view.zoom times smaller in a
// close-up (aim_2d_window).
Window2d conformal_window(const ViewOptions& view) {
  return zoomed_window(view, glm::dvec2(0.0), kPlaneHalfHeight);
}

// The image of normal coordinates p = r(cos φ, sin φ) about the pole: w = T_K(|p|) p/|p|.
glm::dvec2 conformal_image(double K, const glm::dvec2& p) {
  const double r = glm::length(p);
  return r > 0.0 ? (conformal_radius(K, r) / r) * p : p;
}

// Points of a circle |w| = rho about the origin at angles a0 + (a1 − a0)k/n, n chosen so that the
// chords stray from the circle by less than `tolerance` [length] (at most 65536 of them).
std::vector<glm::dvec2> arc(double rho, double a0, double a1, double tolerance) {
  const double step = 2.0 * std::sqrt(std::max(1e-300, 2.0 * tolerance / rho));  // sagitta ≈ ρ step²/8
  const int n = clamped_integer(std::ceil((a1 - a0) / step), 16, 65536);         // NaN: 16
  std::vector<glm::dvec2> points;
  for (int k = 0; k <= n; ++k) {
    const double a = a0 + (a1 - a0) * k / n;
    points.push_back(rho * glm::dvec2(std::cos(a), std::sin(a)));
  }
  return points;
}

// The directions [rad] in which the window lies as seen from the origin: the whole turn when it
// holds the origin, else the range of its corners' directions about its centre's.
std::pair<double, double> window_directions(const Window2d& w) {
  if (std::abs(w.centre.x) <= w.hx && std::abs(w.centre.y) <= w.hy) return {-kPi, kPi};
  const double mid = std::atan2(w.centre.y, w.centre.x);
  double lo = 0.0, hi = 0.0;
  for (const double sx : {-1.0, 1.0})
    for (const double sy : {-1.0, 1.0}) {
      const double a =
          std::remainder(std::atan2(w.centre.y + sy * w.hy, w.centre.x + sx * w.hx) - mid, 2 * kPi);
      lo = std::min(lo, a), hi = std::max(hi, a);
    }
  return {mid + lo, mid + hi};
}

// Distances from the origin to the window's nearest and farthest points.
std::pair<double, double> window_distances(const Window2d& w) {
  const glm::dvec2 lo = w.centre - glm::dvec2(w.hx, w.hy), hi = w.centre + glm::dvec2(w.hx, w.hy);
  const glm::dvec2 nearest = glm::clamp(glm::dvec2(0.0), lo, hi);
  const glm::dvec2 farthest(std::max(std::abs(lo.x), std::abs(hi.x)),
                            std::max(std::abs(lo.y), std::abs(hi.y)));
  return {glm::length(nearest), glm::length(farthest)};
}

// The conformal view's grid: the plane view's grid (lines at whole multiples of kPlaneGridSpacing)
// laid out in normal coordinates p about the pole and mapped, so that at K = 0 it is the plane
// view's grid; on H² also the ideal boundary |w| = 2R where the frame shows it. Only the part of
// the grid whose image falls in the frame is laid out: its normal coordinates' bounding box is
// that of the window's boundary mapped back (the preimage's boundary), taken no farther out than
// just short of the sphere's antipode or of H²'s boundary.
std::vector<Vertex> conformal_grid(const ViewOptions& view, double K) {
  const Window2d win = conformal_window(view);
  const double tolerance = 1e-3 * win.hy;  // of the drawn curves [length], ~¼ px
  const double R = K != 0.0 ? 1.0 / std::sqrt(std::abs(K)) : std::numeric_limits<double>::infinity();
  const double reach = K > 0.0   ? kPi * R
                       : K < 0.0 ? conformal_distance(K, std::max(0.0, 2.0 * R - tolerance))
                                 : std::numeric_limits<double>::infinity();
  glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  constexpr int kSamples = 256;  // per side of the window
  for (int side = 0; side < 4; ++side)
    for (int i = 0; i <= kSamples; ++i) {
      const double s = 2.0 * i / kSamples - 1.0;
      const glm::dvec2 w = win.centre + glm::dvec2(side < 2 ? (side == 0 ? -win.hx : win.hx) : s * win.hx,
                                                   side < 2 ? s * win.hy : (side == 2 ? -win.hy : win.hy));
      const double t = glm::length(w);
      const double r = std::min(conformal_distance(K, t), reach);
      const glm::dvec2 p = t > 0.0 ? (r / t) * w : w;
      lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
  lo -= kPlaneGridSpacing, hi += kPlaneGridSpacing;
  std::vector<Vertex> lines;
  // Lines closer than two pixels on average would fill the frame (far out on a large H², the
  // window spans thousands of spacings): none are drawn. Drawing them took 11 s at 96×72 (the
  // unbounded-input hunt's frame timed out), up to 2000 lines of 16384 pieces each. The ideal
  // boundary below is drawn either way.
  const double across = (hi.x - lo.x + hi.y - lo.y) / kPlaneGridSpacing;
  const bool drawn = across <= 0.5 * (view.width + view.height);
  // A grid line's image as runs of points (a run ends where the line leaves the drawn part), each
  // drawn with as few chords as stay within the tolerance of its points: straight lines (K = 0, or
  // nearly) as one segment like the plane view's, with no joints to show.
  std::vector<glm::dvec2> run;
  const auto flush = [&] {
    for (std::size_t i = 0; i + 1 < run.size();) {
      std::size_t j = i + 1;
      const auto straight = [&](std::size_t end) {
        const glm::dvec2 d = run[end] - run[i];
        const double length = glm::length(d);
        for (std::size_t k = i + 1; k < end; ++k) {
          const glm::dvec2 q = run[k] - run[i];
          if (std::abs(q.x * d.y - q.y * d.x) > tolerance * length) return false;
        }
        return true;
      };
      while (j + 1 < run.size() && straight(j + 1)) ++j;
      add_segment(lines, glm::dvec3(run[i], 0.0), glm::dvec3(run[j], 0.0), kGridColor);
      i = j;
    }
    run.clear();
  };
  // Pieces a quarter spacing long, each halved until the image of its middle is within the
  // tolerance of its chord's.
  const auto add_piece = [&](const auto& self, const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& wa,
                             const glm::dvec2& wb, int depth) -> void {
    if (glm::length(a) >= reach || glm::length(b) >= reach || !win.near(wa) || !win.near(wb)) {
      flush();
      return;
    }
    const glm::dvec2 m = 0.5 * (a + b), wm = conformal_image(K, m);
    if (depth < 10 && glm::length(wm - 0.5 * (wa + wb)) > tolerance) {
      self(self, a, m, wa, wm, depth + 1);
      self(self, m, b, wm, wb, depth + 1);
      return;
    }
    if (run.empty()) run.push_back(wa);
    run.push_back(wb);
  };
  // Pieces end on multiples of a quarter spacing along the line, wherever the box's edges fall, so
  // that nearby curvatures cut a line alike (and draw the same pixels).
  const double quarter = 0.25 * kPlaneGridSpacing;
  const auto add_line = [&](const glm::dvec2& origin, const glm::dvec2& along, double from, double to) {
    const double k0 = std::floor(from / quarter), k1 = std::min(std::ceil(to / quarter), k0 + 16384.0);
    glm::dvec2 p0 = origin + k0 * quarter * along, w0 = conformal_image(K, p0);
    // Counted too: far out (k ~ 1e100) ++k no longer moves k (issue 48's hunt).
    for (double k = k0 + 1.0, n = 0; k <= k1 && n < 16384; ++k, ++n) {
      const glm::dvec2 p1 = origin + k * quarter * along, w1 = conformal_image(K, p1);
      add_piece(add_piece, p0, p1, w0, w1, 0);
      p0 = p1, w0 = w1;
    }
    flush();
  };
  const auto first = [](double x) { return std::ceil(x / kPlaneGridSpacing); };
  for (double k = first(lo.x), n = 0; drawn && k * kPlaneGridSpacing <= hi.x && n < 2000; ++k, ++n)
    add_line({k * kPlaneGridSpacing, 0.0}, {0.0, 1.0}, lo.y, hi.y);
  for (double k = first(lo.y), n = 0; drawn && k * kPlaneGridSpacing <= hi.y && n < 2000; ++k, ++n)
    add_line({0.0, k * kPlaneGridSpacing}, {1.0, 0.0}, lo.x, hi.x);
  if (K < 0.0) {  // the ideal boundary, where the frame crosses it
    const auto [nearest, farthest] = window_distances(win);
    if (nearest < 2.0 * R && 2.0 * R < farthest) {
      const auto [a0, a1] = window_directions(win);
      const std::vector<glm::dvec2> rim = arc(2.0 * R, a0, a1, tolerance);
      for (std::size_t i = 0; i + 1 < rim.size(); ++i)
        add_segment(lines, glm::dvec3(rim[i], 0.0), glm::dvec3(rim[i + 1], 0.0), kSeamColor);
    }
  }
  return lines;
}

// The Poincaré disk |w| < 2R as a fan about the origin over the directions the window lies in:
// empty when it covers the window (the frame is cleared to the surface's colour instead) or
// misses it.
std::vector<Vertex> conformal_disk(const ViewOptions& view, double K, const glm::vec4& color) {
  const Window2d win = conformal_window(view);
  const double rho = 2.0 / std::sqrt(-K);
  const auto [nearest, farthest] = window_distances(win);
  if (!(nearest < rho && rho < farthest)) return {};
  const auto [a0, a1] = window_directions(win);
  const std::vector<glm::dvec2> rim = arc(rho, a0, a1, 1e-3 * win.hy);
  std::vector<Vertex> fan;
  for (std::size_t i = 0; i + 1 < rim.size(); ++i)
    fan.insert(fan.end(), {{glm::vec3(0.0f), color},
                           {glm::vec3(glm::dvec3(rim[i], 0.0)), color},
                           {glm::vec3(glm::dvec3(rim[i + 1], 0.0)), color}});
  return fan;
}

// A body's position and frame in the conformal view: w and the images of e₁, e₂ there, to first
// order (the body is infinitesimal): a tangent vector c₁E₁ + c₂E₂ goes to (1 + K|w|²/4)(c₁ ŵ + c₂ ŵ⊥),
// ŵ = (cos φ, sin φ) the radial direction and ŵ⊥ it turned by 90° (E₂ = jE₁). The components
// cᵢ = ⟨e_A, Eᵢ⟩ are rescaled to the Gram matrix's lengths (far out on H² the embedded
// components are ~e^{r/R} and their η-products lose digits).
struct ConformalFrame {
  glm::dvec2 w;     // [length]
  glm::dvec2 e[2];  // the images of e₁, e₂ [length]
};
ConformalFrame conformal_frame(const Surface& surface, const BodySnapshot& body) {
  ConformalFrame f;
  f.w = conformal_point(surface, body.X);
  const PolarCoordinates p = polar_coordinates(surface, body.X);
  const double phi = p.rho > 0.0 ? p.phi : 0.0;
  const ChartPoint c = chart_point(surface, p.r, phi);
  const glm::dvec2 radial(std::cos(phi), std::sin(phi)), angular(-radial.y, radial.x);
  const double factor = conformal_factor(curvature(surface), f.w);
  for (int a = 0; a < 2; ++a) {
    glm::dvec2 comp(dot(surface, body.e[a], c.E1), dot(surface, body.e[a], c.E2));
    const double length = std::sqrt(std::max(0.0, body.gram(a, a))), got = glm::length(comp);
    if (got > 0.0) comp *= length / got;
    f.e[a] = factor * (comp.x * radial + comp.y * angular);
  }
  return f;
}

// A body's ellipse in the conformal view: the image of scale·(unit circle) under e_A, mapped to
// first order (conformal_frame): a translucent fill and its outline.
void add_conformal_body(FrameScene& scene, const ConformalFrame& f, double scale, const BodySnapshot& body) {
  const glm::vec4 fill = rgba(body.color, kFillAlpha);
  constexpr int kPoints = 64;
  const auto at = [&](double radius, int i) {
    const double theta = 2 * kPi * (i % kPoints) / kPoints;
    return glm::dvec3(f.w + radius * (std::cos(theta) * f.e[0] + std::sin(theta) * f.e[1]), 0.0);
  };
  for (int i = 0; i < kPoints; ++i)
    scene.fills.insert(
        scene.fills.end(),
        {{to_float(at(0.0, i)), fill}, {to_float(at(scale, i)), fill}, {to_float(at(scale, i + 1)), fill}});
  for (int i = 0; i < kPoints; ++i)
    add_segment(scene.lines, at(scale, i), at(scale, i + 1), outline_color(body));
}

// A body's frame arrows e₁ (red) and e₂ (green) in the conformal view: straight, to first order.
void add_conformal_arrows(FrameScene& scene, const ConformalFrame& f, double scale) {
  for (int a = 0; a < 2; ++a) {
    const glm::dvec3 base(f.w, 0.0), tip(f.w + 1.3 * scale * f.e[a], 0.0);
    const glm::dvec3 before(f.w + 1.3 * scale * 0.75 * f.e[a], 0.0);
    add_segment(scene.lines, base, tip, kArrowColors[a]);
    const glm::dvec3 back = before - tip;
    if (glm::length(back) > 0.0) {
      const glm::dvec3 side =
          0.45 * glm::length(back) * glm::normalize(glm::cross(glm::dvec3(0, 0, 1), back));
      add_segment(scene.lines, tip, before + side, kArrowColors[a]);
      add_segment(scene.lines, tip, before - side, kArrowColors[a]);
    }
  }
}

class ConformalView final : public ViewModel {
 public:
  glm::dvec3 world_position(const Surface& surface, const Vec3& X) const override {
    return glm::dvec3(conformal_point(surface, X), 0.0);
  }
  // The background depends on K, which no static geometry (nor the background cache's key)
  // holds: it is drawn from grid_lines and backdrop every frame.
  bool uses_static() const override { return false; }
  // The plane's colour on every surface, so that nothing changes as K passes through 0; the map
  // fills the frame but for what lies beyond H²'s boundary.
  void add_background(FrameScene& scene, const Surface& surface, const ViewOptions& view) const override {
    const double K = curvature(surface);
    scene.surface_color = FrameScene{}.surface_color;
    if (scene.draw_surface) {
      if (K < 0.0) scene.backdrop = conformal_disk(view, K, scene.surface_color);
      if (K >= 0.0 || window_distances(conformal_window(view)).second <= 2.0 / std::sqrt(-K))
        scene.clear_color = scene.surface_color;
    }
    if (scene.draw_grid) scene.grid_lines = conformal_grid(view, K);
  }
  std::optional<Window2d> clip(const ViewOptions& view) const override { return conformal_window(view); }
  // Bodies near the frame only (one by the sphere's antipode would cover it), drawn to first order.
  void add_bodies(FrameScene& scene, const Snapshot& snapshot, const ViewOptions& view) const override {
    const Window2d window = conformal_window(view);
    std::vector<std::pair<ConformalFrame, const BodySnapshot*>> frames;
    for (auto body = snapshot.bodies.rbegin(); body != snapshot.bodies.rend(); ++body) {  // main body last
      const ConformalFrame f = conformal_frame(snapshot.surface, *body);
      if (window.near(f.w)) frames.emplace_back(f, &*body);
    }
    if (view.layers & kBody)
      for (const auto& [f, body] : frames) add_conformal_body(scene, f, view.scale, *body);
    if (view.layers & kFrame)
      for (const auto& [f, body] : frames) add_conformal_arrows(scene, f, view.scale);
  }
  glm::mat4 camera(const ViewOptions& view) const override { return window_camera(conformal_window(view)); }
  // On the bodies, and a close-up where the map shrinks them (K < 0, far from the pole).
  void aim(ViewOptions& view, const Snapshot& snapshot, const HudLayout& hud) const override {
    aim_at_bodies_centre(*this, view, snapshot);
    aim_2d_window(*this, view, snapshot, hud, kPlaneHalfHeight);
  }
  // Lengths, not R: the picture must not change with K (the dial); a sphere of R = 1e6 would
  // otherwise draw a body the size of a continent.
  double body_scale_length(const Surface& /*surface*/) const override { return 1.0; }
  // The frame to first order in the flat picture: an ellipse at any size, nothing wraps.
  double body_drawing_scale(const Surface& /*surface*/, const BodySnapshot& /*body*/,
                            double scale) const override {
    return scale;
  }
  std::string grid_caption(const Snapshot& snapshot, const ViewOptions& /*view*/) const override {
    return "Grid: the image of a square grid of geodesic normal coordinates, every " +
           caption_number("%g", kPlaneGridSpacing * body_scale_length(snapshot.surface)) + " length units.";
  }
  FigureScale figure_scale() const override { return FigureScale::scale_bar; }
};

}  // namespace

double conformal_radius(double curvature, double r) {
  if (curvature == 0.0) return r;
  const double R = 1.0 / std::sqrt(std::abs(curvature));
  return curvature > 0.0 ? 2.0 * R * std::tan(r / (2.0 * R)) : 2.0 * R * std::tanh(r / (2.0 * R));
}

double conformal_distance(double curvature, double t) {
  if (curvature == 0.0) return t;
  const double R = 1.0 / std::sqrt(std::abs(curvature));
  if (curvature > 0.0) return 2.0 * R * std::atan(t / (2.0 * R));
  return t < 2.0 * R ? 2.0 * R * std::atanh(t / (2.0 * R)) : std::numeric_limits<double>::infinity();
}

double conformal_factor(double curvature, const glm::dvec2& w) {
  return 1.0 + 0.25 * curvature * glm::dot(w, w);
}

glm::dvec2 conformal_point(const Surface& surface, const Vec3& X) {
  if (offers(surface, Offer::zero_curvature)) return {X.x(), X.y()};
  const PolarCoordinates p = polar_coordinates(surface, X);
  if (p.rho == 0.0)  // the pole, or the sphere's antipode (at infinity: as far as double goes)
    return {offers(surface, Offer::positive_curvature) && X.z() < 0.0
                ? conformal_radius(curvature(surface), p.r)
                : 0.0,
            0.0};
  return conformal_radius(curvature(surface), p.r) / p.rho * glm::dvec2(X.x(), X.y());
}

const ViewModel& conformal_view() {
  static const ConformalView view;
  return view;
}

}  // namespace spinfold::render
