#include "render/figure.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>

#include "render/view_table.h"
#include "render/views/drawing.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

const glm::dvec4 kOutlineColor{0.22, 0.25, 0.30, 1.0};
const glm::dvec4 kLabelColor{0.25, 0.32, 0.42, 1.0};
const glm::dvec4 kProvenanceColor{0.40, 0.40, 0.40, 1.0};
constexpr double kMargin = 8.0;           // around the caption [pt]
constexpr double kTitleSize = 10.0;       // [pt]
constexpr double kCaptionSize = 8.0;      // [pt]
constexpr double kProvenanceSize = 6.0;   // [pt]
constexpr double kLabelSize = 7.0;        // grid labels and the scale bar's [pt]
constexpr double kLineSpacing = 1.35;     // baseline to baseline over the font size
constexpr float kDepthTolerance = 1e-5f;  // [NDC depth] a line on the surface is not hidden by it

// The scene's camera and, in the 3-D views, a depth buffer of its surface rasterised in software
// (pixel centres, depth interpolated linearly in screen space as GL does for NDC z): what hides a
// line. Points are moved the scene's depth_bias of the way towards the camera, as flat.vert moves
// them, so that the grid on the surface stays in front of the mesh's faces.
class Camera {
 public:
  Camera(const FrameScene& scene, const ViewOptions& view)
      : vp_(scene.view_projection), width_(view.width), height_(view.height), bias_(scene.depth_bias) {
    const glm::dvec4 eye = glm::inverse(vp_) * glm::dvec4(0, 0, 1, 0);  // sent to w = 0
    has_eye_ = std::abs(eye.w) > 1e-12;
    if (has_eye_) eye_ = glm::dvec3(eye) / eye.w;
    if (scene.depth_test && scene.statics) rasterise(scene.statics->surface);
  }

  // Pixel position (x right, y down) and NDC depth, or nullopt behind the camera.
  std::optional<glm::dvec3> project(const glm::dvec3& world, bool biased = true) const {
    const glm::dvec3 p = biased && has_eye_ ? glm::mix(world, eye_, static_cast<double>(bias_)) : world;
    const glm::dvec4 clip = vp_ * glm::dvec4(p, 1.0);
    if (clip.w <= 0.0) return std::nullopt;
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    return glm::dvec3((ndc.x + 1.0) * 0.5 * width_, (1.0 - ndc.y) * 0.5 * height_, ndc.z);
  }

  // Whether a projected point is in front of the surface (always, without a depth buffer). The
  // farthest depth of the 3×3 pixels around it is taken, so that a line along the silhouette is
  // not cut by the pixel grid.
  bool visible(const glm::dvec3& p) const {
    if (depth_.empty()) return true;
    const int x = static_cast<int>(std::floor(p.x)), y = static_cast<int>(std::floor(p.y));
    float farthest = -std::numeric_limits<float>::infinity();
    for (int j = y - 1; j <= y + 1; ++j)
      for (int i = x - 1; i <= x + 1; ++i) {
        if (i < 0 || j < 0 || i >= width_ || j >= height_) return true;
        farthest = std::max(farthest, depth_[static_cast<std::size_t>(j) * width_ + i]);
      }
    return static_cast<float>(p.z) <= farthest + kDepthTolerance;
  }

  bool depth_tested() const { return !depth_.empty(); }

 private:
  void rasterise(const std::vector<LitVertex>& triangles) {
    depth_.assign(static_cast<std::size_t>(width_) * height_, std::numeric_limits<float>::infinity());
    for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
      std::optional<glm::dvec3> v[3];
      bool behind = false;
      for (int k = 0; k < 3; ++k) {
        v[k] = project(glm::dvec3(triangles[t + k].position), false);
        behind = behind || !v[k];
      }
      if (behind) continue;
      const glm::dvec3 a = *v[0], b = *v[1], c = *v[2];
      const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      if (std::abs(area) < 1e-12) continue;
      const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
      const int x1 = std::min(width_ - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))));
      const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
      const int y1 = std::min(height_ - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const double px = x + 0.5, py = y + 0.5;
          // Barycentric weights of the pixel's centre.
          const double wa = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
          const double wb = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
          const double wc = 1.0 - wa - wb;
          if (wa < 0 || wb < 0 || wc < 0) continue;
          float& d = depth_[static_cast<std::size_t>(y) * width_ + x];
          d = std::min(d, static_cast<float>(wa * a.z + wb * b.z + wc * c.z));
        }
    }
  }

  glm::dmat4 vp_;
  int width_, height_;
  float bias_;
  bool has_eye_ = false;
  glm::dvec3 eye_{0.0};
  std::vector<float> depth_;
};

// A pixel position on the page [pt], rounded to 1/100 pt (a hundredth of a point is 3.5 µm on
// paper; the files are a third smaller for it).
glm::dvec2 to_page(const glm::dvec3& pixel) {
  return glm::round(glm::dvec2(pixel) * kPointsPerPixel * 100.0) / 100.0;
}

// Whether b lies on the straight line from a to c, within 0.02 pt (b can go from a polyline).
bool on_line(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  const glm::dvec2 ac = c - a, ab = b - a;
  const double length = glm::length(ac);
  if (length < 1e-9) return false;
  return std::abs(ac.x * ab.y - ac.y * ab.x) / length < 0.02 && glm::dot(ab, ac) > 0.0 &&
         glm::dot(ab, ac) < length * length;
}

// Whether a segment of the frame [pixels] misses the frame (both ends beyond one of its edges).
bool outside_frame(const glm::dvec3& a, const glm::dvec3& b, const ViewOptions& view) {
  return (a.x < 0 && b.x < 0) || (a.y < 0 && b.y < 0) || (a.x > view.width && b.x > view.width) ||
         (a.y > view.height && b.y > view.height);
}

bool same_color(const glm::vec4& a, const glm::vec4& b) {
  return glm::all(glm::equal(a, b));
}

// Line segments (pairs of vertices, as GL_LINES) as polylines on the page: hidden pieces left out
// (each segment cut into pieces of about 2 px, each tested at its middle) unless `through` (a
// ghost, drawn through the surface), consecutive segments that meet joined into one path while
// their colour stays the same.
void add_segments(FigurePage& page, const Camera& camera, const ViewOptions& view,
                  const std::vector<Vertex>& segments, double width, const std::string& role,
                  const std::optional<glm::dvec4>& color = std::nullopt, bool through = false) {
  FigurePath* open = nullptr;  // the path the last visible piece ended
  glm::vec4 open_color{-1.0f};
  const auto add_piece = [&](const glm::dvec3& a, const glm::dvec3& b, const glm::vec4& c) {
    const glm::dvec2 pa = to_page(a), pb = to_page(b);
    if (open && same_color(c, open_color) && glm::distance(open->points.back(), pa) < 1e-6) {
      std::vector<glm::dvec2>& points = open->points;
      if (points.size() >= 2 && on_line(points[points.size() - 2], points.back(), pb))
        points.back() = pb;  // straight on: one point fewer
      else if (glm::distance(points.back(), pb) > 1e-9)
        points.push_back(pb);
      return;
    }
    FigurePath path;
    path.points = {pa, pb};
    path.color = color.value_or(glm::dvec4(c));
    path.width = width;
    path.role = role;
    page.paths.push_back(std::move(path));
    open = &page.paths.back();
    open_color = c;
  };
  for (std::size_t i = 0; i + 1 < segments.size(); i += 2) {
    const auto a = camera.project(glm::dvec3(segments[i].position));
    const auto b = camera.project(glm::dvec3(segments[i + 1].position));
    if (!a || !b || outside_frame(*a, *b, view)) {
      open = nullptr;
      continue;
    }
    const glm::vec4 c = segments[i].color;
    if (!camera.depth_tested() || through) {
      add_piece(*a, *b, c);
      continue;
    }
    const int pieces =
        std::clamp(static_cast<int>(std::ceil(glm::distance(glm::dvec2(*a), glm::dvec2(*b)) / 2.0)), 1, 512);
    for (int k = 0; k < pieces; ++k) {
      const glm::dvec3 p0 = glm::mix(*a, *b, static_cast<double>(k) / pieces);
      const glm::dvec3 p1 = glm::mix(*a, *b, static_cast<double>(k + 1) / pieces);
      if (camera.visible(0.5 * (p0 + p1)))
        add_piece(p0, p1, c);
      else
        open = nullptr;
    }
  }
}

// Triangles as one filled path each colour (their union: every triangle turned counter-clockwise
// on the page, filled with the non-zero rule, so that neither seams nor overlaps show). Hidden
// triangles (tested at the centroid) are left out when `depth_tested`.
// Triangles of a mesh made of quads (a, b, c, a, c, d) are joined back into their quads where
// both halves are kept and turn the same way on the page (a quad folded over the silhouette stays
// two triangles). Triangles off the frame or hidden are left out.
template <typename V>
void add_triangles(FigurePage& page, const Camera& camera, const ViewOptions& view,
                   const std::vector<V>& triangles, const std::optional<glm::dvec4>& color, bool depth_tested,
                   const std::string& role) {
  FigurePath* path = nullptr;
  glm::dvec4 path_color{-1.0};
  const auto signed_area = [](const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  };
  // The page's corners of triangle t, or nullopt when it is not drawn.
  const auto corners = [&](std::size_t t) -> std::optional<std::array<glm::dvec2, 3>> {
    std::optional<glm::dvec3> v[3];
    for (int k = 0; k < 3; ++k) {
      v[k] = camera.project(glm::dvec3(triangles[t + k].position), depth_tested);
      if (!v[k]) return std::nullopt;
    }
    const double x0 = std::min({v[0]->x, v[1]->x, v[2]->x}), x1 = std::max({v[0]->x, v[1]->x, v[2]->x});
    const double y0 = std::min({v[0]->y, v[1]->y, v[2]->y}), y1 = std::max({v[0]->y, v[1]->y, v[2]->y});
    if (x1 < 0 || y1 < 0 || x0 > view.width || y0 > view.height) return std::nullopt;  // off the frame
    if (depth_tested && !camera.visible((*v[0] + *v[1] + *v[2]) / 3.0)) return std::nullopt;
    return std::array<glm::dvec2, 3>{to_page(*v[0]), to_page(*v[1]), to_page(*v[2])};
  };
  const auto color_of = [&](std::size_t t) {
    if constexpr (std::is_same_v<V, Vertex>) {
      return color.value_or(glm::dvec4(triangles[t].color));
    } else {  // no colour given: the curvature layer's tint, the face's mean in steps of 1/16 (fewer paths)
      if (color) return *color;
      const glm::dvec3 mean = (glm::dvec3(triangles[t].tint) + glm::dvec3(triangles[t + 1].tint) +
                               glm::dvec3(triangles[t + 2].tint)) /
                              3.0;
      return glm::dvec4(glm::round(mean * 16.0) / 16.0, 1.0);
    }
  };
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const auto p = corners(t);
    if (!p) continue;
    const glm::dvec4 c = color_of(t);
    if (!path || c != path_color) {
      page.paths.push_back(FigurePath{.color = c, .filled = true, .role = role});
      path = &page.paths.back();
      path_color = c;
    }
    std::vector<glm::dvec2> polygon{(*p)[0], (*p)[1], (*p)[2]};
    const double area = signed_area((*p)[0], (*p)[1], (*p)[2]);
    // The quad's other half: (a, c, d) after (a, b, c).
    const std::size_t u = t + 3;
    if (u + 2 < triangles.size() && triangles[u].position == triangles[t].position &&
        triangles[u + 1].position == triangles[t + 2].position && color_of(u) == c) {
      if (const auto q = corners(u); q && signed_area((*q)[0], (*q)[1], (*q)[2]) * area > 0) {
        polygon.push_back((*q)[2]);
        t = u;  // both halves drawn
      }
    }
    if (area < 0) std::reverse(polygon.begin(), polygon.end());
    path->points.insert(path->points.end(), polygon.begin(), polygon.end());
    path->runs.push_back(polygon.size());
  }
}

// The flat views' outline: the edges of the surface's mesh that bound one face only (the disk's
// rim, the half-plane's y = 0).
std::vector<Vertex> boundary_edges(const StaticGeometry& g) {
  std::vector<Vertex> lines;
  for (const SurfaceEdge& e : g.edges)
    if (e.faces == 1) {
      lines.push_back({g.surface[e.a].position, glm::vec4(kOutlineColor)});
      lines.push_back({g.surface[e.b].position, glm::vec4(kOutlineColor)});
    }
  return lines;
}

struct Box {
  double x0, y0, x1, y1;
  bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

// Labels on the grid's geodesic circles about the pole, each where it fits: inside the picture,
// clear of the other labels and of the bodies, at the first of a few directions that works.
void add_circle_labels(FigurePage& page, const Snapshot& snapshot, const ViewOptions& view,
                       const FrameScene& scene) {
  const Surface& surface = snapshot.surface;
  const bool sphere = offers(surface, Offer::positive_curvature);
  std::vector<double> radii;  // [R], those of the grid (render/scene_builder.cpp's build_static)
  if (sphere)
    for (int k = 1; k < 10; ++k) radii.push_back(kPi * k / 12);
  else
    for (double r = 0.5; r <= 6.0 + 1e-9; r += 0.5) radii.push_back(r);
  std::vector<Box> taken;
  for (const BodySnapshot& body : snapshot.bodies)
    if (const auto px = pixel_position(scene, view, world_position(surface, view.kind, body.X))) {
      const glm::dvec2 p = *px * kPointsPerPixel;
      const double clear = 40.0 * kPointsPerPixel;
      taken.push_back({p.x - clear, p.y - clear, p.x + clear, p.y + clear});
    }
  // Nor over a trail: every few of its points keep a small box clear.
  for (const BodySnapshot& body : snapshot.bodies)
    for (std::size_t i = 0; i < body.trail.size(); i += std::max<std::size_t>(1, body.trail.size() / 256))
      if (const auto px = pixel_position(scene, view, world_position(surface, view.kind, body.trail[i]))) {
        const glm::dvec2 p = *px * kPointsPerPixel;
        taken.push_back({p.x - 3.0, p.y - 3.0, p.x + 3.0, p.y + 3.0});
      }
  const double directions[] = {0.25 * kPi, 0.75 * kPi, -0.25 * kPi, -0.75 * kPi,
                               0.5 * kPi,  -0.5 * kPi, 0.0,         kPi};
  const double w = view.width * kPointsPerPixel, h = view.height * kPointsPerPixel;
  const double spacing = radii[1] - radii[0];
  // Where the circle of radius r [R] crosses the ray at φ, on the page.
  const auto at = [&](double r, double phi) -> std::optional<glm::dvec2> {
    const Vec3 X = chart_point(surface, std::max(0.0, r) * surface.radius, phi).X;
    const auto px = pixel_position(scene, view, world_position(surface, view.kind, X));
    if (!px) return std::nullopt;
    return *px * kPointsPerPixel;
  };
  for (const double r : radii) {
    const std::string text = circle_label(r, sphere);
    const double half = 0.5 * text_width(text, kLabelSize) + 1.0;
    for (const double phi : directions) {
      const auto here = at(r, phi), inside = at(r - spacing, phi), outside = at(r + spacing, phi);
      if (!here || !inside || !outside) continue;
      const glm::dvec2 p = *here;
      // Room for the text between the neighbouring circles (none near the disk's rim, where they crowd).
      if (glm::distance(p, *inside) < 1.6 * kLabelSize || glm::distance(p, *outside) < 1.6 * kLabelSize)
        continue;
      const Box box{p.x - half, p.y - 0.5 * kLabelSize - 1.0, p.x + half, p.y + 0.5 * kLabelSize + 1.0};
      if (box.x0 < 2 || box.y0 < 2 || box.x1 > w - 2 || box.y1 > h - 2) continue;
      if (std::any_of(taken.begin(), taken.end(), [&](const Box& b) { return b.overlaps(box); })) continue;
      taken.push_back(box);
      page.texts.push_back({.at = {p.x, p.y + 0.35 * kLabelSize},
                            .text = text,
                            .size = kLabelSize,
                            .align = TextAlign::centre,
                            .color = kLabelColor,
                            .halo = true,
                            .role = "label"});
      break;
    }
  }
}

// A bar of 1, 2 or 5 × 10ᵏ lengths in the picture's lower left corner, measured at the pole (the
// conformal view's scale 1 + K|w|²/4 grows away from it).
void add_scale_bar(FigurePage& page, const Snapshot& snapshot, const ViewOptions& view,
                   const FrameScene& scene) {
  const Surface& surface = snapshot.surface;
  const double step = 1e-3 * surface.radius;  // [length]
  const auto a =
      pixel_position(scene, view, world_position(surface, view.kind, chart_point(surface, 0.0, 0.0).X));
  const auto b =
      pixel_position(scene, view, world_position(surface, view.kind, chart_point(surface, step, 0.0).X));
  if (!a || !b) return;
  const double per_length = glm::distance(*a, *b) / step * kPointsPerPixel;  // [pt per length]
  if (!(per_length > 0.0) || !std::isfinite(per_length)) return;
  const double w = view.width * kPointsPerPixel, h = view.height * kPointsPerPixel;
  const double length = scale_bar_length(0.25 * w / per_length);
  const double bar = length * per_length;
  const glm::dvec2 start{12.0, h - 12.0};
  const glm::dvec2 end = start + glm::dvec2(bar, 0.0);
  const double tick = 3.0;
  page.paths.push_back({.points = {start + glm::dvec2(0, -tick), start, end, end + glm::dvec2(0, -tick)},
                        .color = kOutlineColor,
                        .width = 1.0,
                        .role = "scale_bar"});
  const bool exact = curvature(surface) == 0.0;  // else the bar holds at the centre only
  char number[32];
  std::snprintf(number, sizeof number, "%g", length);
  page.texts.push_back({.at = {0.5 * (start.x + end.x), start.y - tick - 2.0},
                        .text = std::string(number) + (length == 1.0 ? " length unit" : " length units") +
                                (exact ? "" : " (at the centre)"),
                        .size = kLabelSize,
                        .align = TextAlign::centre,
                        .color = kLabelColor,
                        .halo = true,
                        .role = "scale_bar"});
}

}  // namespace

FigureScale figure_scale(ViewKind view) {
  return view_model(view).figure_scale();
}

double scale_bar_length(double most) {
  if (!(most > 0.0) || !std::isfinite(most)) return 0.0;
  const double power = std::pow(10.0, std::floor(std::log10(most)));
  for (const double m : {5.0, 2.0, 1.0})
    if (m * power <= most * (1 + 1e-12)) return m * power;
  return power;
}

std::string circle_label(double r_over_R, bool sphere) {
  if (sphere) {  // r = (k/12)·πR, the fraction reduced
    const int k = static_cast<int>(std::lround(r_over_R / kPi * 12));
    const int g = std::gcd(k, 12);
    const int num = k / g, den = 12 / g;
    std::string text = "r = ";
    if (num != 1) text += caption_number("%.0f", num);
    text += "\u03C0R";
    if (den != 1) text += caption_number("/%.0f", den);
    return text;
  }
  return "r = " + caption_number("%g", r_over_R) + " R";
}

FigurePage figure_page(const Snapshot& snapshot, const ViewOptions& view_in, const FigureCaption& caption) {
  ViewOptions view = view_in;
  const bool captioned = (view.layers & kHud) != 0;  // the caption takes the HUD's place
  view.layers &= ~static_cast<unsigned>(kHud);
  const FrameScene scene = build_scene(snapshot, view);
  const Camera camera(scene, view);
  const LineWidths widths = line_widths(view.width, view.height);
  const double line_width = widths.lines * kPointsPerPixel, grid_width = widths.grid * kPointsPerPixel;
  const double w = view.width * kPointsPerPixel, h = view.height * kPointsPerPixel;

  FigurePage page;
  page.width = w;
  page.picture = {0, 0, w, h};
  page.title = caption.title;
  page.metadata = caption.metadata;
  // The picture's ground: the surface's colour where it fills the frame (the plane), else white.
  const glm::dvec4 ground =
      same_color(scene.clear_color, scene.surface_color) ? glm::dvec4(scene.clear_color) : glm::dvec4(1.0);
  page.paths.push_back(
      {.points = {{0, 0}, {w, 0}, {w, h}, {0, h}}, .color = ground, .filled = true, .role = "ground"});

  const bool three_d = scene.depth_test;
  if (!scene.backdrop.empty())
    add_triangles(page, camera, view, scene.backdrop, std::nullopt, false, "surface");
  // The surface's fill: its visible faces (hidden ones lie under them) in one flat colour.
  if (scene.statics && scene.draw_surface)
    add_triangles(page, camera, view, scene.statics->surface,
                  scene.tint_by_curvature ? std::nullopt : std::optional(glm::dvec4(scene.surface_color)),
                  three_d, "surface");
  if (scene.statics && scene.draw_grid)
    add_segments(page, camera, view, scene.statics->grid, grid_width, "grid");
  add_segments(page, camera, view, scene.grid_lines, grid_width, "grid");
  if (scene.statics && (scene.draw_surface || scene.draw_grid)) {
    if (three_d)
      add_segments(page, camera, view, silhouette(*scene.statics, scene), line_width, "outline",
                   kOutlineColor);
    else
      add_segments(page, camera, view, boundary_edges(*scene.statics), line_width, "outline", kOutlineColor);
  }
  // Bodies behind the surface, faintly through it (FrameScene::ghost_fills), under the rest.
  add_triangles(page, camera, view, scene.ghost_fills, std::nullopt, false, "ghost");
  add_segments(page, camera, view, scene.ghost_lines, line_width, "ghost", std::nullopt, true);
  add_triangles(page, camera, view, scene.fills, std::nullopt, three_d, "body");
  // The lines: trails (by their colour), then the bodies' outlines and arrows.
  std::vector<Vertex> trails, others;
  for (std::size_t i = 0; i + 1 < scene.lines.size(); i += 2) {
    const bool trail = i >= scene.trails_begin && i < scene.trails_end;
    (trail ? trails : others).insert((trail ? trails : others).end(), {scene.lines[i], scene.lines[i + 1]});
  }
  add_segments(page, camera, view, trails, line_width, "trail");
  add_segments(page, camera, view, others, line_width, "body");

  if (view.layers & kGrid) {
    if (figure_scale(view.kind) == FigureScale::circle_labels && scene.statics)
      add_circle_labels(page, snapshot, view, scene);
    if (figure_scale(view.kind) == FigureScale::scale_bar) add_scale_bar(page, snapshot, view, scene);
  }
  // A thin frame round the picture.
  page.paths.push_back({.points = {{0, 0}, {w, 0}, {w, h}, {0, h}},
                        .color = {0.6, 0.6, 0.6, 1.0},
                        .width = 0.5,
                        .closed = true,
                        .role = "frame"});

  // The legend: the PNG's entries (or, in a frame too narrow for the PNG's, the same ones).
  std::vector<LegendEntry> legend = scene.legend;
  if (legend.empty()) {
    ViewOptions wide = view;
    wide.width = std::max(wide.width, kFullOverlayWidth);
    wide.height = std::max(wide.height, kFullOverlayHeight);
    legend = legend_entries(snapshot, wide);
  }
  const double line = kCaptionSize * kLineSpacing, swatch = 22.0;
  double legend_width = 0.0;
  for (const LegendEntry& e : legend)
    legend_width = std::max(legend_width, swatch + 6.0 + text_width(e.label, kCaptionSize));
  double y = h + kMargin;
  const double legend_x = w - kMargin - legend_width;
  for (std::size_t i = 0; i < legend.size(); ++i) {
    const double base = y + kCaptionSize + i * line;
    const double mid = base - 0.35 * kCaptionSize;
    FigurePath trail{.points = {{legend_x, mid}, {legend_x + swatch, mid}},
                     .color = glm::dvec4(legend[i].trail_color),
                     .width = line_width,
                     .clip_to_picture = false,
                     .role = "legend"};
    if (legend[i].dashed) trail.dash = {3.0, 2.0};
    if (legend[i].right_half) {  // a two-colour key: half each, in the label's order
      trail.points[1].x = legend_x + 0.5 * swatch;
      page.paths.push_back(trail);
      trail.points = {{legend_x + 0.5 * swatch, mid}, {legend_x + swatch, mid}};
      trail.color = glm::dvec4(*legend[i].right_half);
    }
    page.paths.push_back(trail);
    std::vector<glm::dvec2> dot;
    for (int k = 0; k < 16; ++k)
      dot.push_back({legend_x + 0.5 * swatch + 4.0 * std::cos(2 * kPi * k / 16),
                     mid + 2.6 * std::sin(2 * kPi * k / 16)});
    if (legend[i].dot)
      page.paths.push_back({.points = dot,
                            .color = glm::dvec4(legend[i].color),
                            .filled = true,
                            .clip_to_picture = false,
                            .role = "legend"});
    page.texts.push_back({.at = {legend_x + swatch + 6.0, base},
                          .text = legend[i].label,
                          .size = kCaptionSize,
                          .role = "legend"});
  }
  const double text_right = legend.empty() ? w - kMargin : legend_x - 2 * kMargin;
  const double text_width_left = std::max(60.0, text_right - kMargin);
  const auto add_lines = [&](const std::string& text, double size, bool bold, const glm::dvec4& color) {
    for (const std::string& l : wrap_text(text, size, bold, text_width_left)) {
      y += size * kLineSpacing;
      page.texts.push_back({.at = {kMargin, y - 0.3 * size},
                            .text = l,
                            .size = size,
                            .bold = bold,
                            .color = color,
                            .role = "caption"});
    }
  };
  if (!captioned) {  // a bare figure (the paper's own caption says it): the legend only
    page.height = h + (legend.empty() ? 0.0 : 2 * kMargin + legend.size() * line);
    return page;
  }
  if (!caption.title.empty()) add_lines(caption.title, kTitleSize, true, {0.1, 0.1, 0.1, 1});
  if (!caption.description.empty()) add_lines(caption.description, kCaptionSize, false, {0.1, 0.1, 0.1, 1});
  std::vector<std::string> lines = readout_lines(snapshot, view);
  std::string view_line = "View: " + std::string(view_info(view.kind).title) + ".";
  if (const std::string grid = view.layers & kGrid ? view_model(view.kind).grid_caption(snapshot, view) : "";
      !grid.empty())
    view_line += " " + grid;
  lines.push_back(view_line);
  for (const std::string& l : lines) add_lines(l, kCaptionSize, false, {0.1, 0.1, 0.1, 1});
  if (!caption.provenance.empty()) add_lines(caption.provenance, kProvenanceSize, false, kProvenanceColor);
  page.height = std::max(y, h + kMargin + legend.size() * line) + kMargin;
  return page;
}

}  // namespace spinfold::render
