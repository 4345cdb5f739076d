#include "render/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <initializer_list>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>

#include "engine/integer_cast.h"

namespace spinfold::render {

namespace {

constexpr double kPi = std::numbers::pi;

// Colours of the layers.
const glm::vec4 kGridColor{0.45f, 0.52f, 0.62f, 1.0f};
constexpr float kFillAlpha = 0.55f;
const glm::vec4 kArrowColors[2] = {{0.85f, 0.10f, 0.10f, 1.0f}, {0.10f, 0.60f, 0.15f, 1.0f}};
// The geodesic companion's trail: dashes and gaps of these lengths [world units, radii].
constexpr double kDash = 0.045, kGap = 0.03;

// Overlays sit this far (in radii) above the hyperboloid so that the depth test keeps them. On the
// sphere they lie on it exactly: its mesh is circumscribed (every face outside the unit sphere), so
// nothing drawn on the sphere pokes out past the mesh's limb, and the depth bias (FrameScene) keeps
// them in front of the faces.
constexpr double kLift = 0.004;
// FrameScene::depth_bias of the 3-D views: a fraction of the distance to the camera.
constexpr float kSphereDepthBias = 0.01f, kHyperboloidDepthBias = 0.004f;
// Extent of the hyperboloid mesh and of the H² grid [radii].
constexpr double kHyperboloidExtent = 7.0;
// The tractricoid: ρ = R sech u, z = R(u − tanh u) for 0 ≤ u ≤ kTractricoidExtent (its rim at
// u = 0); the seam where the strip's edges meet is drawn in kSeamColor.
constexpr double kTractricoidExtent = 5.0;
const glm::vec4 kSeamColor{0.80f, 0.35f, 0.55f, 1.0f};
// The 3-D views' vertical field of view [degrees].
constexpr double kFovY = 35.0;

bool three_d(ViewKind view) {
  return view_info(view).three_d;
}

// The tractricoid's outward unit normal at a world point (ρ cos θ, ρ sin θ, z), ρ = sech u:
// (tanh u cos θ, tanh u sin θ, sech u).
glm::dvec3 tractricoid_normal(const glm::dvec3& w) {
  const double rho = std::min(1.0, glm::length(glm::dvec2(w)));
  const double t = std::sqrt(std::max(0.0, 1.0 - rho * rho));  // tanh u
  const glm::dvec2 radial = rho > 0.0 ? glm::dvec2(w) / rho : glm::dvec2(1.0, 0.0);
  return {t * radial.x, t * radial.y, rho};
}

// The surface normal a 3-D view lifts overlays along and tilts arrowheads in; +z in the 2-D views.
glm::dvec3 view_normal(ViewKind view, const glm::dvec3& w) {
  switch (view) {
    case ViewKind::sphere: return glm::normalize(w);
    case ViewKind::hyperboloid: return glm::normalize(glm::dvec3(-w.x, -w.y, w.z + 1.0));
    case ViewKind::tractricoid: return tractricoid_normal(w);
    default: return {0, 0, 1};
  }
}

// The body-frame vector a e₁ + b e₂ and its intrinsic length from the Gram matrix.
struct FrameVector {
  Vec3 v;
  double length;
};
FrameVector frame_vector(const BodySnapshot& s, double a, double b) {
  const double q = s.gram(0, 0) * a * a + 2.0 * s.gram(0, 1) * a * b + s.gram(1, 1) * b * b;
  return {a * s.e[0] + b * s.e[1], std::sqrt(std::max(0.0, q))};
}

Vec3 exp_frame(const Surface& surface, const BodySnapshot& s, double a, double b) {
  const FrameVector f = frame_vector(s, a, b);
  return exponential_map(surface, s.X, f.v, f.length);
}

glm::vec4 rgba(const std::array<float, 3>& c, float alpha = 1.0f) {
  return {c[0], c[1], c[2], alpha};
}

// The outline of an ellipse: the main body's dark orange as before, a companion's own colour
// darkened by a quarter.
glm::vec4 outline_color(const BodySnapshot& body) {
  if (body.color == kMainBodyColor) return {0.70f, 0.30f, 0.02f, 1.0f};
  return {0.75f * body.color[0], 0.75f * body.color[1], 0.75f * body.color[2], 1.0f};
}

// A world point lifted off the 3-D surfaces along the normal.
glm::dvec3 lifted(ViewKind view, const glm::dvec3& w) {
  if (view == ViewKind::hyperboloid || view == ViewKind::tractricoid) return w + kLift * view_normal(view, w);
  return w;
}

glm::vec3 to_float(const glm::dvec3& w) {
  return glm::vec3(w);
}

void add_segment(std::vector<Vertex>& lines, const glm::dvec3& a, const glm::dvec3& b,
                 const glm::vec4& color) {
  lines.push_back({to_float(a), color});
  lines.push_back({to_float(b), color});
}

// The centre and half-extents of the 2-D views' orthographic frame [world units].
struct Window2d {
  glm::dvec2 centre{0.0};
  double hx = 1.0, hy = 1.0;
  // Whether a world point is within the window grown by its own size on every side. The conformal
  // view draws a segment only when both its ends are: near the sphere's antipode (at infinity) the
  // images of neighbouring points lie far apart on opposite sides, and their chord would cross the
  // frame.
  bool near(const glm::dvec2& w) const {
    return std::abs(w.x - centre.x) <= 3.0 * hx && std::abs(w.y - centre.y) <= 3.0 * hy;
  }
};

// A polyline through embedded points, mapped and lifted; with `clip`, only its segments near it.
void add_polyline(std::vector<Vertex>& lines, const Surface& surface, ViewKind view,
                  const std::vector<Vec3>& points, const glm::vec4& color, bool closed,
                  const Window2d* clip = nullptr) {
  for (std::size_t i = 0; i + 1 < points.size() + (closed ? 1 : 0); ++i) {
    const Vec3& a = points[i];
    const Vec3& b = points[(i + 1) % points.size()];
    if (!on_view(surface, view, a) || !on_view(surface, view, b)) continue;
    const glm::dvec3 wa = lifted(view, world_position(surface, view, a)),
                     wb = lifted(view, world_position(surface, view, b));
    if (clip && !(clip->near(glm::dvec2(wa)) && clip->near(glm::dvec2(wb)))) continue;
    add_segment(lines, wa, wb, color);
  }
}

// The same polyline dashed: kDash on, kGap off, measured along the drawn (world) path, so that the
// dashes keep their length however densely the path is sampled.
void add_dashed_polyline(std::vector<Vertex>& lines, const Surface& surface, ViewKind view,
                         const std::vector<Vec3>& points, const glm::vec4& color,
                         const Window2d* clip = nullptr) {
  double phase = 0.0;  // distance into the current dash + gap period
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    if (!on_view(surface, view, points[i]) || !on_view(surface, view, points[i + 1])) continue;
    const glm::dvec3 a = lifted(view, world_position(surface, view, points[i]));
    const glm::dvec3 b = lifted(view, world_position(surface, view, points[i + 1]));
    if (clip && !(clip->near(glm::dvec2(a)) && clip->near(glm::dvec2(b)))) continue;
    const double length = glm::length(b - a);
    double done = 0.0;
    while (done < length) {
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

// Points along the geodesic-like path between two nearby embedded points (chords pushed back onto
// the surface), so that a trail follows the surface instead of cutting through it.
void append_path(std::vector<Vec3>& out, const Surface& surface, const Vec3& a, const Vec3& b) {
  const double R = surface.radius;
  if (std::max(a.norm(), b.norm()) > 1e3 * R) {  // far out on H²: η-norms cancel; a chord will do
    out.push_back(b);
    return;
  }
  const double gap = (b - a).norm() / std::max(R, std::max(a.norm(), b.norm()) * 1e-3);
  const int n = clamped_integer(std::ceil(gap / 0.03), 1, 16);  // clamped before the cast (NaN: 1)
  for (int i = 1; i <= n; ++i) {
    Vec3 p = a + (b - a) * (static_cast<double>(i) / n);
    if (surface.kind == SurfaceKind::sphere)
      p *= R / p.norm();
    else if (surface.kind == SurfaceKind::pseudosphere)
      p *= R / std::sqrt(std::max(1e-300, -dot(surface, p, p)));
    out.push_back(p);
  }
}

StaticGeometry build_static(SurfaceKind kind, ViewKind view) {
  StaticGeometry g;
  const Surface unit{kind, 1.0};
  const auto add_quad = [&](const LitVertex& a, const LitVertex& b, const LitVertex& c, const LitVertex& d) {
    g.surface.insert(g.surface.end(), {a, b, c, a, c, d});
  };
  const auto grid_curve = [&](auto point_at, int segments) {
    std::vector<Vec3> pts;
    for (int i = 0; i <= segments; ++i) pts.push_back(point_at(static_cast<double>(i) / segments));
    add_polyline(g.grid, unit, view, pts, kGridColor, false);
  };
  if (view == ViewKind::sphere) {
    const int slices = 64, stacks = 32;
    const auto vertex = [](double theta, double phi) {
      const glm::dvec3 p(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      return LitVertex{to_float(p), to_float(p)};
    };
    for (int i = 0; i < stacks; ++i)
      for (int j = 0; j < slices; ++j) {
        const double t0 = kPi * i / stacks, t1 = kPi * (i + 1) / stacks;
        const double p0 = 2 * kPi * j / slices, p1 = 2 * kPi * (j + 1) / slices;
        add_quad(vertex(t0, p0), vertex(t1, p0), vertex(t1, p1), vertex(t0, p1));
      }
    // Circumscribe: a face through three points of the unit sphere lies at distance n̂·a from the
    // centre (its plane's); scaling every vertex by 1/min(n̂·a) puts all faces outside the sphere.
    double inner = 1.0;
    for (std::size_t i = 0; i + 2 < g.surface.size(); i += 3) {
      const glm::dvec3 a(g.surface[i].position), b(g.surface[i + 1].position), c(g.surface[i + 2].position);
      const glm::dvec3 n = glm::cross(b - a, c - a);
      if (glm::length(n) > 1e-12) inner = std::min(inner, std::abs(glm::dot(glm::normalize(n), a)));
    }
    for (LitVertex& v : g.surface) v.position = to_float(glm::dvec3(v.position) * (1.0 / inner));
    for (int k = 1; k < 12; ++k)  // parallels every 15°
      grid_curve([&](double s) { return chart_point(unit, kPi * k / 12, 2 * kPi * s).X; }, 96);
    for (int k = 0; k < 12; ++k)  // meridians every 30°
      grid_curve([&](double s) { return chart_point(unit, kPi * s, 2 * kPi * k / 12).X; }, 48);
    return g;
  }
  if (view == ViewKind::hyperboloid) {
    const int rings = 56, slices = 64;
    const auto vertex = [&](double r, double phi) {
      const Vec3 X = chart_point(unit, r, phi).X;
      const glm::dvec3 w = world_position(unit, view, X);
      return LitVertex{to_float(w), to_float(glm::normalize(glm::dvec3(-X.x(), -X.y(), X.z())))};
    };
    for (int i = 0; i < rings; ++i)
      for (int j = 0; j < slices; ++j) {
        const double r0 = kHyperboloidExtent * i / rings, r1 = kHyperboloidExtent * (i + 1) / rings;
        const double p0 = 2 * kPi * j / slices, p1 = 2 * kPi * (j + 1) / slices;
        add_quad(vertex(r0, p0), vertex(r1, p0), vertex(r1, p1), vertex(r0, p1));
      }
  }
  if (view == ViewKind::tractricoid) {
    // The surface of revolution, with its meridians (geodesics) every 30° and its parallels
    // (horocycles) every 0.5 in u; the seam and the rim (u = 0, where the surface ends) marked.
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
        add_quad(vertex(u_of(i), t0), vertex(u_of(i + 1), t0), vertex(u_of(i + 1), t1), vertex(u_of(i), t1));
      }
    const auto curve = [&](auto point_at, int segments, const glm::vec4& color) {
      for (int i = 0; i < segments; ++i)
        add_segment(g.grid, lifted(view, point_at(static_cast<double>(i) / segments)),
                    lifted(view, point_at(static_cast<double>(i + 1) / segments)), color);
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
  if (view == ViewKind::klein || view == ViewKind::halfplane) {
    if (view == ViewKind::klein) {  // the disk and its rim
      const int slices = 128;
      for (int j = 0; j < slices; ++j) {
        const double p0 = 2 * kPi * j / slices, p1 = 2 * kPi * (j + 1) / slices;
        g.surface.push_back({{0, 0, 0}, {0, 0, 1}});
        g.surface.push_back({glm::vec3(std::cos(p0), std::sin(p0), 0), {0, 0, 1}});
        g.surface.push_back({glm::vec3(std::cos(p1), std::sin(p1), 0), {0, 0, 1}});
        add_segment(g.grid, {std::cos(p0), std::sin(p0), 0}, {std::cos(p1), std::sin(p1), 0}, kGridColor);
      }
    } else {  // y > 0, and its boundary y = 0
      constexpr float far = 1e4f;
      for (const glm::vec2 c : {glm::vec2(-far, 0), glm::vec2(far, 0), glm::vec2(far, far),
                                glm::vec2(-far, 0), glm::vec2(far, far), glm::vec2(-far, far)})
        g.surface.push_back({glm::vec3(c, 0.0f), {0, 0, 1}});
      add_segment(g.grid, {-far, 0, 0}, {far, 0, 0}, kGridColor);
    }
  }
  if (view == ViewKind::hyperboloid || view == ViewKind::klein || view == ViewKind::halfplane ||
      (view == ViewKind::disk && kind == SurfaceKind::pseudosphere)) {
    // Geodesic polar grid: circles r = 0.5, 1, … and radial geodesics every 30°.
    const double extent = view == ViewKind::hyperboloid ? kHyperboloidExtent : 6.0;
    // The half-plane magnifies by e^r towards one side: its circles need more points.
    const int around = view == ViewKind::halfplane ? 512 : 128, out = view == ViewKind::halfplane ? 256 : 64;
    for (double r = 0.5; r <= extent + 1e-9; r += 0.5)
      grid_curve([&](double s) { return chart_point(unit, r, 2 * kPi * s).X; }, around);
    for (int k = 0; k < 12; ++k)
      grid_curve([&](double s) { return chart_point(unit, extent * s, 2 * kPi * k / 12).X; }, out);
  }
  if (view == ViewKind::disk) {
    const double radius = kind == SurfaceKind::pseudosphere ? 1.0 : 3.0;
    const int slices = 128;
    for (int j = 0; j < slices; ++j) {
      const double p0 = 2 * kPi * j / slices, p1 = 2 * kPi * (j + 1) / slices;
      const LitVertex c{{0, 0, 0}, {0, 0, 1}};
      g.surface.push_back(c);
      g.surface.push_back({glm::vec3(radius * std::cos(p0), radius * std::sin(p0), 0), {0, 0, 1}});
      g.surface.push_back({glm::vec3(radius * std::cos(p1), radius * std::sin(p1), 0), {0, 0, 1}});
    }
    if (kind == SurfaceKind::sphere) {
      for (int k = 1; k < 10; ++k)  // parallels down to 150°
        grid_curve([&](double s) { return chart_point(unit, kPi * k / 12, 2 * kPi * s).X; }, 128);
      for (int k = 0; k < 12; ++k)
        grid_curve([&](double s) { return chart_point(unit, kPi * 0.8 * s, 2 * kPi * k / 12).X; }, 64);
    } else {
      for (int j = 0; j < slices; ++j) {  // the rim
        const double p0 = 2 * kPi * j / slices, p1 = 2 * kPi * (j + 1) / slices;
        add_segment(g.grid, {std::cos(p0), std::sin(p0), 0}, {std::cos(p1), std::sin(p1), 0}, kGridColor);
      }
    }
  }
  // The plane has no static geometry: it is the whole frame (build_scene clears to its colour) and
  // its grid follows the camera (FrameScene::grid_lines).
  return g;
}

Window2d window_2d(const ViewOptions& view) {
  const double aspect = static_cast<double>(view.width) / view.height;
  // The unit disk, the plane's window, or the half-plane's from just below y = 0 to twice the
  // centre's height (a window that scales with the height is the same picture at any height).
  double half = kPlaneHalfHeight;
  Window2d w;
  if (view.kind == ViewKind::disk || view.kind == ViewKind::klein) half = 1.08;
  if (view.kind == ViewKind::halfplane) {
    w.centre = view.target ? glm::dvec2((*view.target)[0], (*view.target)[1]) : glm::dvec2(0.0, 1.0);
    half = 1.08 * w.centre.y;
  }
  w.hx = aspect >= 1 ? half * aspect : half;
  w.hy = aspect >= 1 ? half : half / aspect;
  if ((view.kind == ViewKind::plane || view.kind == ViewKind::conformal) && view.target)
    w.centre = {(*view.target)[0], (*view.target)[1]};
  return w;
}

glm::mat4 camera(const ViewOptions& view) {
  const double aspect = static_cast<double>(view.width) / view.height;
  if (three_d(view.kind)) {
    const glm::dvec3 target = view.target
                                  ? glm::dvec3((*view.target)[0], (*view.target)[1], (*view.target)[2])
                              : view.kind == ViewKind::hyperboloid ? glm::dvec3(0, 0, 1.6)
                              : view.kind == ViewKind::tractricoid ? glm::dvec3(0, 0, 0.8)
                                                                   : glm::dvec3(0);
    const glm::dvec3 dir(std::cos(view.pitch) * std::cos(view.yaw), std::cos(view.pitch) * std::sin(view.yaw),
                         std::sin(view.pitch));
    const glm::dvec3 eye = target + view.distance * dir;
    const glm::dvec3 up = std::abs(dir.z) > 0.999 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    // Near and far planes grow with a camera drawn back to frame a body far out on H².
    const double reach = std::max(1.0, view.distance / 5.0);
    return glm::mat4(glm::perspective(glm::radians(kFovY), aspect, 0.05 * reach, 100.0 * reach) *
                     glm::lookAt(eye, target, up));
  }
  const Window2d w = window_2d(view);
  return glm::mat4(
      glm::ortho(w.centre.x - w.hx, w.centre.x + w.hx, w.centre.y - w.hy, w.centre.y + w.hy, -1.0, 1.0));
}

// The plane's grid across the frame: lines at whole multiples of kPlaneGridSpacing, so that the
// grid stays put in the world while the frame follows the body.
std::vector<Vertex> plane_grid(const ViewOptions& view) {
  const Window2d w = window_2d(view);
  const double x0 = w.centre.x - w.hx, x1 = w.centre.x + w.hx, y0 = w.centre.y - w.hy, y1 = w.centre.y + w.hy;
  std::vector<Vertex> lines;
  for (double k = std::floor(x0 / kPlaneGridSpacing); k <= std::ceil(x1 / kPlaneGridSpacing); ++k)
    add_segment(lines, {k * kPlaneGridSpacing, y0 - 1.0, 0}, {k * kPlaneGridSpacing, y1 + 1.0, 0},
                kGridColor);
  for (double k = std::floor(y0 / kPlaneGridSpacing); k <= std::ceil(y1 / kPlaneGridSpacing); ++k)
    add_segment(lines, {x0 - 1.0, k * kPlaneGridSpacing, 0}, {x1 + 1.0, k * kPlaneGridSpacing, 0},
                kGridColor);
  return lines;
}

// ---- The conformal view (conformal_radius).

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
  const Window2d win = window_2d(view);
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
    for (double k = k0 + 1.0; k <= k1; ++k) {
      const glm::dvec2 p1 = origin + k * quarter * along, w1 = conformal_image(K, p1);
      add_piece(add_piece, p0, p1, w0, w1, 0);
      p0 = p1, w0 = w1;
    }
    flush();
  };
  const auto first = [](double x) { return std::ceil(x / kPlaneGridSpacing); };
  for (double k = first(lo.x), n = 0; k * kPlaneGridSpacing <= hi.x && n < 2000; ++k, ++n)
    add_line({k * kPlaneGridSpacing, 0.0}, {0.0, 1.0}, lo.y, hi.y);
  for (double k = first(lo.y), n = 0; k * kPlaneGridSpacing <= hi.y && n < 2000; ++k, ++n)
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
  const Window2d win = window_2d(view);
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

// A body's ellipse: a translucent fill following the surface and its outline.
void add_body(FrameScene& scene, const Surface& surface, ViewKind kind, double scale,
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
        kind,
        world_position(surface, kind, exp_frame(surface, body, f * std::cos(theta), f * std::sin(theta)))));
  };
  for (int ring = 0; ring < kRings; ++ring)
    for (std::size_t i = 0; i < outline.size(); ++i) {
      const glm::vec3 a = ring_point(ring, i), b = ring_point(ring + 1, i), c = ring_point(ring + 1, i + 1),
                      d = ring_point(ring, i + 1);
      scene.fills.insert(scene.fills.end(), {{a, fill}, {b, fill}, {c, fill}});
      if (ring > 0) scene.fills.insert(scene.fills.end(), {{a, fill}, {c, fill}, {d, fill}});
    }
  add_polyline(scene.lines, surface, kind, outline, outline_color(body), true);
}

// A body's frame arrows e₁ (red) and e₂ (green).
void add_frame_arrows(FrameScene& scene, const Surface& surface, ViewKind kind, double scale,
                      const BodySnapshot& body) {
  for (int a = 0; a < 2; ++a) {
    std::vector<Vec3> shaft;
    for (int i = 0; i <= 16; ++i) {
      const double f = scale * 1.3 * i / 16;
      shaft.push_back(exp_frame(surface, body, a == 0 ? f : 0.0, a == 0 ? 0.0 : f));
    }
    add_polyline(scene.lines, surface, kind, shaft, kArrowColors[a], false);
    // Arrowhead in world space: two barbs back from the tip, in the surface's tangent plane.
    const glm::dvec3 tip = lifted(kind, world_position(surface, kind, shaft.back()));
    const glm::dvec3 before = lifted(kind, world_position(surface, kind, shaft[12]));
    const glm::dvec3 back = before - tip;
    if (glm::length(back) > 0.0) {
      const glm::dvec3 normal = view_normal(kind, tip);
      const glm::dvec3 side = 0.45 * glm::length(back) * glm::normalize(glm::cross(normal, back));
      add_segment(scene.lines, tip, before + side, kArrowColors[a]);
      add_segment(scene.lines, tip, before - side, kArrowColors[a]);
    }
  }
}

// Each edge of the surface's triangles once, with the normals of the faces it bounds. Vertices are
// the same point when their coordinates agree to 1e-6 (the mesh repeats them per triangle, and the
// sphere's seam at φ = 2π lands on φ = 0 only up to rounding).
void add_edges(StaticGeometry& g) {
  std::map<std::array<long, 3>, std::uint32_t> ids;
  const auto id = [&](std::uint32_t i) {
    const glm::vec3& p = g.surface[i].position;
    const std::array<long, 3> key{std::lround(p.x * 1e6), std::lround(p.y * 1e6), std::lround(p.z * 1e6)};
    return ids.try_emplace(key, static_cast<std::uint32_t>(ids.size())).first->second;
  };
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> index;
  for (std::uint32_t t = 0; t + 2 < g.surface.size(); t += 3) {
    const glm::vec3 n = glm::cross(g.surface[t + 1].position - g.surface[t].position,
                                   g.surface[t + 2].position - g.surface[t].position);
    if (glm::length(n) == 0.0f) continue;  // the sphere's quads at the poles are triangles
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t + k, b = t + (k + 1) % 3;
      const std::uint32_t ia = id(a), ib = id(b);
      if (ia == ib) continue;
      const auto [it, fresh] = index.try_emplace(std::minmax(ia, ib), g.edges.size());
      if (fresh)
        g.edges.push_back({a, b, {n, glm::vec3(0.0f)}, 1});
      else if (g.edges[it->second].faces == 1)
        g.edges[it->second].face[g.edges[it->second].faces++] = n;
    }
  }
}

}  // namespace

glm::vec3 headlight(const FrameScene& scene) {
  if (!scene.depth_test) return {0, 0, 1};
  const glm::mat4 inverse = glm::inverse(scene.view_projection);
  return glm::normalize(glm::vec3(inverse * glm::vec4(0, 0, -1, 0)));
}

std::vector<Vertex> silhouette(const StaticGeometry& g, const FrameScene& scene) {
  std::vector<Vertex> lines;
  // The camera: the point the projection sends to w = 0; for an orthographic projection a
  // direction (the one that goes into the screen).
  const glm::dvec4 h = glm::inverse(glm::dmat4(scene.view_projection)) * glm::dvec4(0, 0, 1, 0);
  const bool perspective = std::abs(h.w) > 1e-12;
  const glm::dvec3 eye = perspective ? glm::dvec3(h) / h.w : glm::dvec3(0.0);
  const glm::dvec3 towards_camera = perspective ? glm::dvec3(0.0) : -glm::dvec3(h);
  const glm::vec3 light = headlight(scene);
  const float ambient = scene.depth_test ? 0.35f : 1.0f;
  const auto shaded = [&](const LitVertex& v) {  // lit.vert's colour
    const float diffuse = std::abs(glm::dot(v.normal, light));
    return glm::vec4(glm::vec3(scene.surface_color) * (ambient + (1.0f - ambient) * diffuse),
                     scene.surface_color.a);
  };
  for (const SurfaceEdge& e : g.edges) {
    const glm::dvec3 a(g.surface[e.a].position);
    const glm::dvec3 view = perspective ? eye - a : towards_camera;
    const bool outline = e.faces == 1 || (glm::dot(glm::dvec3(e.face[0]), view) > 0.0) !=
                                             (glm::dot(glm::dvec3(e.face[1]), view) > 0.0);
    if (!outline) continue;
    lines.push_back({g.surface[e.a].position, shaded(g.surface[e.a])});
    lines.push_back({g.surface[e.b].position, shaded(g.surface[e.b])});
  }
  return lines;
}

const StaticGeometry& static_geometry(SurfaceKind surface, ViewKind view) {
  static std::mutex mutex;
  static std::map<std::pair<SurfaceKind, ViewKind>, StaticGeometry> cache;
  const std::lock_guard lock(mutex);
  auto it = cache.find({surface, view});
  if (it == cache.end()) {
    StaticGeometry g = build_static(surface, view);
    add_edges(g);
    it = cache.emplace(std::pair{surface, view}, std::move(g)).first;
  }
  return it->second;
}

LineWidths line_widths(int width, int height) {
  const double side = std::min(0.75 * width, static_cast<double>(height)) / 480.0;
  const double lines = 1.5 * side;
  return {static_cast<float>(std::max(1.0, lines)), static_cast<float>(std::max(1.0, lines * 2.0 / 3.0))};
}

HudLayout hud_layout(const std::vector<std::string>& lines, const std::vector<std::string>& legend_labels,
                     int width, int height) {
  HudLayout h;
  const double side = std::min(0.75 * width, static_cast<double>(height)) / 540.0;
  h.scale = std::max(1.0, std::round(2.0 * side) / 2.0);
  h.font_size = 13.0 * h.scale;
  // ImGui snaps the default font's advance to whole pixels (ImFontConfig::PixelSnapH).
  h.advance = std::floor(7.0 * h.scale + 0.5);
  h.line = h.font_size + 2.0 * h.scale;
  h.padding = 5.0 * h.scale;
  h.swatch = 30.0 * h.scale;
  const double margin = 6.0 * h.scale;
  // Glyphs, not bytes: a UTF-8 continuation byte starts none.
  const auto glyphs = [](const std::string& text) {
    return static_cast<double>(
        std::count_if(text.begin(), text.end(), [](char c) { return (c & 0xC0) != 0x80; }));
  };
  const auto box_height = [&](std::size_t n) { return n * h.line - 2.0 * h.scale + 2.0 * h.padding; };
  if (!lines.empty()) {
    double longest = 0.0;
    for (const std::string& line : lines) longest = std::max(longest, glyphs(line));
    h.hud = {margin, margin, longest * h.advance + 2.0 * h.padding, box_height(lines.size())};
  }
  if (!legend_labels.empty()) {
    double longest = 0.0;
    for (const std::string& label : legend_labels) longest = std::max(longest, glyphs(label));
    const double w = h.swatch + h.advance + longest * h.advance + 2.0 * h.padding;
    h.legend = {width - margin - w, margin, w, box_height(legend_labels.size())};
  }
  return h;
}

Vec3 exponential_map(const Surface& surface, const Vec3& X, const Vec3& v, double length) {
  if (length == 0.0 || surface.kind == SurfaceKind::plane) return X + v;
  return polar_C(surface, length) * X + (polar_S(surface, length) / length) * v;
}

glm::dvec3 world_position(const Surface& surface, ViewKind view, const Vec3& X) {
  const double R = surface.radius;
  switch (view) {
    case ViewKind::sphere: return glm::dvec3(X.x(), X.y(), X.z()) / R;
    case ViewKind::hyperboloid: return glm::dvec3(X.x() / R, X.y() / R, X.z() / R - 1.0);
    case ViewKind::disk: {
      // Poincaré disk (H²) or stereographic projection from the south pole (S²): (X₁, X₂)/(R + X₃).
      // Far out on H² both grow like e^{r/R} and the ratio stays below 1 without overflow.
      const double d = R + X.z();
      return glm::dvec3(X.x() / d, X.y() / d, 0.0);
    }
    case ViewKind::plane: return glm::dvec3(X.x() / R, X.y() / R, 0.0);
    case ViewKind::klein: return glm::dvec3(X.x() / X.z(), X.y() / X.z(), 0.0);
    case ViewKind::halfplane: return glm::dvec3(half_plane_point(surface, X), 0.0);
    case ViewKind::tractricoid: {
      const glm::dvec2 h = kTractricoidDilation * half_plane_point(surface, X);
      const double rho = 1.0 / h.y;
      const double z = h.y >= 1.0 ? std::acosh(h.y) - std::sqrt(1.0 - rho * rho) : 0.0;
      return {rho * std::cos(h.x), rho * std::sin(h.x), z};
    }
    case ViewKind::conformal: return glm::dvec3(conformal_point(surface, X), 0.0);
  }
  return {};
}

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
  if (surface.kind == SurfaceKind::plane) return {X.x(), X.y()};
  const PolarCoordinates p = polar_coordinates(surface, X);
  if (p.rho == 0.0)  // the pole, or the sphere's antipode (at infinity: as far as double goes)
    return {
        surface.kind == SurfaceKind::sphere && X.z() < 0.0 ? conformal_radius(curvature(surface), p.r) : 0.0,
        0.0};
  return conformal_radius(curvature(surface), p.r) / p.rho * glm::dvec2(X.x(), X.y());
}

glm::dvec2 half_plane_point(const Surface& surface, const Vec3& X) {
  const double R = surface.radius;
  const double k = (X.z() + X.x()) / (R * R + X.y() * X.y());
  return {-X.y() * k, R * k};
}

bool on_view(const Surface& surface, ViewKind view, const Vec3& X) {
  // (The conformal view shows every point but the sphere's antipode, which its segments' clipping
  // leaves out.)
  return view != ViewKind::tractricoid || kTractricoidDilation * half_plane_point(surface, X).y >= 1.0;
}

std::vector<Vec3> ellipse_points(const Surface& surface, const BodySnapshot& body, double scale, int count) {
  std::vector<Vec3> points;
  points.reserve(count);
  for (int i = 0; i < count; ++i) {
    const double theta = 2 * kPi * i / count;
    points.push_back(exp_frame(surface, body, scale * std::cos(theta), scale * std::sin(theta)));
  }
  return points;
}

namespace {
// The HUD's lines: the snapshot's, the action variables' with that layer, and on the tractricoid a
// line when the main body is off the surface.
std::vector<std::string> hud_lines(const Snapshot& snapshot, const ViewOptions& view) {
  if (!(view.layers & kHud)) return {};
  std::vector<std::string> lines = snapshot.hud_lines;
  if (view.layers & kActions)
    lines.insert(lines.end(), snapshot.action_lines.begin(), snapshot.action_lines.end());
  if (!snapshot.bodies.empty() && !on_view(snapshot.surface, view.kind, snapshot.bodies.front().X))
    lines.push_back("body 1 is beyond the rim: off the part of H2 this surface shows");
  return lines;
}
}  // namespace

FrameScene build_scene(const Snapshot& snapshot, const ViewOptions& view) {
  FrameScene scene;
  const Surface& surface = snapshot.surface;
  const ViewKind kind = view.kind;
  scene.draw_surface = (view.layers & kSurface) != 0;
  scene.draw_grid = (view.layers & kGrid) != 0;
  const bool conformal = kind == ViewKind::conformal;
  // The conformal view's background depends on K, which no static geometry (nor the background
  // cache's key) holds: it is drawn from grid_lines and backdrop every frame.
  if ((scene.draw_surface || scene.draw_grid) && !conformal)
    scene.statics = &static_geometry(surface.kind, kind);
  scene.view_projection = camera(view);
  scene.depth_test = three_d(kind);
  scene.depth_bias = kind == ViewKind::sphere        ? kSphereDepthBias
                     : kind == ViewKind::hyperboloid ? kHyperboloidDepthBias
                                                     : 0.0f;
  if (surface.kind == SurfaceKind::pseudosphere) scene.surface_color = {0.83f, 0.86f, 0.78f, 1.0f};
  if (kind == ViewKind::plane) {
    if (scene.draw_surface) scene.clear_color = scene.surface_color;  // the plane fills the frame
    if (scene.draw_grid) scene.grid_lines = plane_grid(view);
  }
  const Window2d window = window_2d(view);
  const Window2d* clip = conformal ? &window : nullptr;
  if (conformal) {
    // The plane's colour on every surface, so that nothing changes as K passes through 0; the
    // map fills the frame but for what lies beyond H²'s boundary.
    const double K = curvature(surface);
    scene.surface_color = FrameScene{}.surface_color;
    if (scene.draw_surface) {
      if (K < 0.0) scene.backdrop = conformal_disk(view, K, scene.surface_color);
      if (K >= 0.0 || window_distances(window).second <= 2.0 / std::sqrt(-K))
        scene.clear_color = scene.surface_color;
    }
    if (scene.draw_grid) scene.grid_lines = conformal_grid(view, K);
  }

  // Trails first, then the bodies over them: every body's, main body first.
  if (view.layers & kTrail)
    for (const BodySnapshot& body : snapshot.bodies) {
      if (body.trail.size() < 2) continue;
      std::vector<Vec3> path{body.trail.front()};
      for (std::size_t i = 1; i < body.trail.size(); ++i)
        append_path(path, surface, body.trail[i - 1], body.trail[i]);
      if (body.geodesic)
        add_dashed_polyline(scene.lines, surface, kind, path, rgba(body.trail_color), clip);
      else
        add_polyline(scene.lines, surface, kind, path, rgba(body.trail_color), false, clip);
    }
  if (conformal) {  // bodies near the frame only (one by the sphere's antipode would cover it)
    std::vector<std::pair<ConformalFrame, const BodySnapshot*>> frames;
    for (const BodySnapshot& body : snapshot.bodies) {
      const ConformalFrame f = conformal_frame(surface, body);
      if (window.near(f.w)) frames.emplace_back(f, &body);
    }
    if (view.layers & kBody)
      for (const auto& [f, body] : frames) add_conformal_body(scene, f, view.scale, *body);
    if (view.layers & kFrame)
      for (const auto& [f, body] : frames) add_conformal_arrows(scene, f, view.scale);
  } else {
    if (view.layers & kBody)
      for (const BodySnapshot& body : snapshot.bodies)
        if (on_view(surface, kind, body.X)) add_body(scene, surface, kind, view.scale, body);
    if (view.layers & kFrame)
      for (const BodySnapshot& body : snapshot.bodies)
        if (on_view(surface, kind, body.X)) add_frame_arrows(scene, surface, kind, view.scale, body);
  }
  if (snapshot.bodies.size() > 1 && (view.layers & (kBody | kTrail)) && view.width >= kLegendMinWidth)
    for (const BodySnapshot& body : snapshot.bodies)
      scene.legend.push_back({body.label, rgba(body.color), rgba(body.trail_color), body.geodesic});
  scene.hud_lines = hud_lines(snapshot, view);
  std::vector<std::string> labels;
  for (const LegendEntry& entry : scene.legend) labels.push_back(entry.label);
  scene.hud = hud_layout(scene.hud_lines, labels, view.width, view.height);
  return scene;
}

namespace {

// The direction at the centre of everything drawn of the bodies (positions and trails, on the
// unit sphere): the centre of their smallest enclosing ball by Bădoiu–Clarkson's iteration
// (c ← c + (p_far − c)/(k + 1), within 1/√k of the optimum), so that a comparison shows all its
// bodies however far apart they went. Up to 256 points of each trail are used.
Vec3 drawn_centre(const Snapshot& snapshot) {
  std::vector<Vec3> points;
  for (const BodySnapshot& body : snapshot.bodies) {
    points.push_back(body.X.normalized());
    const std::size_t stride = body.trail.size() / 256 + 1;
    for (std::size_t i = 0; i < body.trail.size(); i += stride) points.push_back(body.trail[i].normalized());
  }
  Vec3 c = points.front();
  for (int k = 1; k <= 64; ++k) {
    const Vec3* far = &points.front();
    for (const Vec3& p : points)
      if ((p - c).squaredNorm() > (*far - c).squaredNorm()) far = &p;
    c += (*far - c) / (k + 1.0);
  }
  return c.norm() > 1e-3 ? c.normalized() : snapshot.bodies.front().X.normalized();
}

}  // namespace

namespace {

// The HUD's and legend's boxes the frame of this snapshot will have (as build_scene lays them out).
HudLayout layout_for(const Snapshot& snapshot, const ViewOptions& view) {
  std::vector<std::string> labels;
  if (snapshot.bodies.size() > 1 && (view.layers & (kBody | kTrail)) && view.width >= kLegendMinWidth)
    for (const BodySnapshot& body : snapshot.bodies) labels.push_back(body.label);
  return hud_layout(hud_lines(snapshot, view), labels, view.width, view.height);
}

// What a camera must show [world units] and how much each counts: the main body's centre above
// all (1000), each companion's (50), each body's outline (5 a point) and its trail (10 in all).
struct Sight {
  glm::dvec3 at;
  double weight;
};

std::vector<Sight> sights(const Snapshot& snapshot, const ViewOptions& view, bool recent_only) {
  const Surface& surface = snapshot.surface;
  std::vector<Sight> out;
  for (const BodySnapshot& body : snapshot.bodies) {
    if (!on_view(surface, view.kind, body.X)) continue;
    const double weight = &body == &snapshot.bodies.front() ? 1000.0 : 50.0;
    out.push_back({world_position(surface, view.kind, body.X), weight});
    for (const Vec3& P : ellipse_points(surface, body, view.scale, 8))
      if (on_view(surface, view.kind, P)) out.push_back({world_position(surface, view.kind, P), 5.0});
  }
  for (const BodySnapshot& body : snapshot.bodies) {
    const std::size_t stride = body.trail.size() / 96 + 1;
    const double weight = 10.0 * static_cast<double>(stride) / static_cast<double>(body.trail.size());
    for (std::size_t i = 0; i < body.trail.size(); i += stride) {
      const Vec3& P = body.trail[i];
      if (!on_view(surface, view.kind, P)) continue;
      if (recent_only) {  // the trail's last stretch: within 3 radii (intrinsic) of its body
        const double R = surface.radius, c = -dot(surface, P, body.X) / (R * R);
        if (R * std::acosh(std::max(1.0, c)) > 3.0 * R) continue;
      }
      out.push_back({world_position(surface, view.kind, P), weight});
    }
  }
  return out;
}

// How badly a camera shows the sights: the weight of those behind the sphere or the camera, out of
// the frame (less a margin) or under the HUD's or legend's box (grown by the margin).
double badness(const ViewOptions& view, const std::vector<Sight>& points, const HudLayout& hud) {
  FrameScene scene;
  scene.view_projection = camera(view);
  const double margin = 0.04 * std::min(view.width, view.height),
               edge = 0.01 * std::min(view.width, view.height);
  const auto grown = [&](const PixelBox& b) {
    return b.w > 0.0 ? PixelBox{b.x - margin, b.y - margin, b.w + 2 * margin, b.h + 2 * margin} : b;
  };
  const PixelBox hud_box = grown(hud.hud), legend_box = grown(hud.legend);
  const glm::dvec4 h = glm::inverse(glm::dmat4(scene.view_projection)) * glm::dvec4(0, 0, 1, 0);
  const glm::dvec3 eye = glm::dvec3(h) / h.w;
  double bad = 0.0;
  for (const Sight& p : points) {
    // Beyond the limb, or so near it (more than 60° from the camera's direction) that it is seen edge-on.
    const bool hidden = view.kind == ViewKind::sphere && glm::dot(p.at, glm::normalize(eye)) < 0.5;
    const std::optional<glm::dvec2> px = pixel_position(scene, view, p.at);
    if (hidden || !px || px->x < edge || px->y < edge || px->x > view.width - edge ||
        px->y > view.height - edge || hud_box.contains(*px) || legend_box.contains(*px))
      bad += p.weight;
  }
  return bad;
}

// Tries the camera turned by each (Δyaw, Δpitch) and drawn back by each factor, in this order,
// and keeps the first that shows the sights best.
void clear_the_boxes(ViewOptions& view, const std::vector<Sight>& points, const HudLayout& hud,
                     std::initializer_list<double> pulls) {
  constexpr double kTurns[][2] = {{0, 0},    {0, 0.1},    {0, 0.2},     {0.1, 0.1},  {-0.1, 0.1},
                                  {0, 0.3},  {0.15, 0.2}, {-0.15, 0.2}, {0.2, 0.3},  {-0.2, 0.3},
                                  {0, 0.45}, {0.3, 0.3},  {-0.3, 0.3},  {0.3, 0.45}, {-0.3, 0.45},
                                  {0.15, 0}, {-0.15, 0},  {0.3, 0},     {-0.3, 0}};
  const ViewOptions start = view;
  double best = std::numeric_limits<double>::infinity();
  for (const double pull : pulls)
    for (const auto& turn : kTurns) {
      ViewOptions v = start;
      v.yaw = start.yaw + turn[0];
      v.pitch = std::clamp(start.pitch + turn[1], -1.3, 1.3);
      v.distance = start.distance * pull;
      const double bad = badness(v, points, hud);
      if (bad < best) best = bad, view = v;
      if (best == 0.0) return;
    }
}

}  // namespace

void aim_camera_at_body(ViewOptions& view, const Snapshot& snapshot) {
  if (snapshot.bodies.empty()) return;
  const HudLayout hud = layout_for(snapshot, view);
  if (view.kind == ViewKind::sphere) {
    const Vec3 n =
        snapshot.bodies.size() > 1 ? drawn_centre(snapshot) : snapshot.bodies.front().X.normalized();
    view.yaw = std::atan2(n.y(), n.x());
    view.pitch = std::clamp(std::asin(n.z()), -1.3, 1.3);
    view.target.reset();
    const std::vector<Sight> points = sights(snapshot, view, false);
    // Drawn back as far as 1.75× when nearer cameras cannot clear the boxes: bodies far apart
    // (one near the pole, one on the equator, with the HUD across the top of a 640×480 frame)
    // otherwise end with the camera tilted over one of them and the other beside the limb, its
    // ellipse seen edge-on.
    clear_the_boxes(view, points, hud, {1.0, 1.2, 1.45, 1.75});
    if (badness(view, points, hud) >= points.front().weight) {  // the main body lost: start from it
      const Vec3 m = snapshot.bodies.front().X.normalized();
      view.yaw = std::atan2(m.y(), m.x());
      view.pitch = std::clamp(std::asin(m.z()), -1.3, 1.3);
      clear_the_boxes(view, points, hud, {1.0, 1.2, 1.45, 1.75});
    }
  } else if (view.kind == ViewKind::hyperboloid || view.kind == ViewKind::tractricoid) {
    // Orbit the centre of the bounding box of the bodies and their recent trails, at the distance
    // at which a sphere round all of them fills 85% of the narrower field of view: from across
    // the hyperboloid's bowl (the near side would see the surface edge-on), from the bodies' own
    // side of the tractricoid (its far side faces away).
    const std::vector<Sight> points = sights(snapshot, view, true);
    if (points.empty()) return;  // every body beyond the tractricoid's rim: the default camera
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const Sight& p : points) lo = glm::min(lo, p.at), hi = glm::max(hi, p.at);
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const bool bowl = view.kind == ViewKind::hyperboloid;
    double radius = bowl ? 1.5 : 0.9;  // at least the vertex's or the rim's neighbourhood
    for (const Sight& p : points) radius = std::max(radius, glm::length(p.at - centre));
    const double aspect = static_cast<double>(view.width) / view.height;
    const double half_fov = std::atan(std::tan(glm::radians(kFovY) / 2) * std::min(1.0, aspect));
    view.target = std::array<double, 3>{centre.x, centre.y, centre.z};
    view.distance = radius / std::sin(0.85 * half_fov);
    view.pitch = bowl ? 0.55 : 0.35;
    if (glm::length(glm::dvec2(centre)) > 1e-9)
      view.yaw = std::atan2(centre.y, centre.x) + (bowl ? kPi : 0.0);
    clear_the_boxes(view, points, hud, {1.0, 1.25, 1.6});
  } else if (view.kind == ViewKind::plane || view.kind == ViewKind::conformal) {
    // The centre of the bodies' bounding box.
    glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const BodySnapshot& body : snapshot.bodies) {
      const glm::dvec3 w = world_position(snapshot.surface, view.kind, body.X);
      lo = glm::min(lo, glm::dvec2(w)), hi = glm::max(hi, glm::dvec2(w));
    }
    const glm::dvec2 c = 0.5 * (lo + hi);
    view.target = std::array<double, 3>{c.x, c.y, 0.0};
  } else if (view.kind == ViewKind::halfplane) {
    // Centred across the bodies and their recent trails, at a height that keeps the highest of
    // them and the widest spread in the window (which spans y ∈ (−0.08, 2.16)·centre height), and
    // never below the main body's (which is then drawn as large as at the centre, or smaller).
    const std::vector<Sight> points = sights(snapshot, view, true);
    const double main = points.front().at.y;
    double lo = points.front().at.x, hi = lo, top = main;
    for (const Sight& p : points)
      lo = std::min(lo, p.at.x), hi = std::max(hi, p.at.x), top = std::max(top, p.at.y);
    const double aspect = static_cast<double>(view.width) / view.height;
    const double height = std::max({main, top / 1.9, (hi - lo) / (2.0 * 0.9 * 1.08 * std::max(1.0, aspect))});
    view.target = std::array<double, 3>{0.5 * (lo + hi), height, 0.0};
  }
}

std::optional<glm::dvec2> pixel_position(const FrameScene& scene, const ViewOptions& view,
                                         const glm::dvec3& world) {
  const glm::dvec4 clip = glm::dmat4(scene.view_projection) * glm::dvec4(world, 1.0);
  if (clip.w <= 0.0) return std::nullopt;
  const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  return glm::dvec2((ndc.x + 1.0) * 0.5 * view.width, (1.0 - ndc.y) * 0.5 * view.height);
}

}  // namespace spinfold::render
