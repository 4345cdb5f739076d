#include "render/scene_builder.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <tuple>

#include "engine/integer_cast.h"
#include "engine/path_bending.h"
#include "engine/readout.h"
#include "engine/surface_geodesics.h"
#include "engine/surface_model.h"
#include "render/view_table.h"
#include "render/views/camera.h"
#include "render/views/drawing.h"
#include "render/views/view_model.h"

// What differs between views (projection, static geometry, camera, background, bodies, aiming) is
// each view's own file in render/views/, reached through the view table (render/view_table.h);
// what is left here is the same for every view.

namespace spinfold::render {

namespace {

// Points along the geodesic-like path between two nearby embedded points (chords pushed back onto
// the surface), so that a trail follows the surface instead of cutting through it.
void append_path(std::vector<Vec3>& out, const Surface& surface, const Vec3& a, const Vec3& b) {
  if (chart_free(surface)) {  // chords of 1/32 of the smallest feature, pushed back onto it
    const std::shared_ptr<const SurfaceModel> shape = surface_model_of(surface);
    const int n = clamped_integer(std::ceil(32.0 * (b - a).norm() / shape->feature), 1, 16);
    for (int i = 1; i < n; ++i)
      out.push_back(project_onto_surface(*shape->implicit, a + (b - a) * (static_cast<double>(i) / n)));
    out.push_back(b);
    return;
  }
  const double R = surface.radius;
  if (std::max(a.norm(), b.norm()) > 1e3 * R) {  // far out on H²: η-norms cancel; a chord will do
    out.push_back(b);
    return;
  }
  const double gap = (b - a).norm() / std::max(R, std::max(a.norm(), b.norm()) * 1e-3);
  const int n = clamped_integer(std::ceil(gap / 0.03), 1, 16);  // clamped before the cast (NaN: 1)
  for (int i = 1; i <= n; ++i) {
    Vec3 p = a + (b - a) * (static_cast<double>(i) / n);
    if (offers(surface, Offer::positive_curvature))
      p *= R / p.norm();
    else if (offers(surface, Offer::negative_curvature))
      p *= R / std::sqrt(std::max(1e-300, -dot(surface, p, p)));
    out.push_back(p);
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

glm::vec4 lit_color(const FrameScene& scene, const LitVertex& v, const glm::vec3& light, float ambient) {
  const float diffuse = std::abs(glm::dot(v.normal, light));
  const glm::vec3 base = scene.tint_by_curvature ? v.tint : glm::vec3(scene.surface_color);
  return glm::vec4(base * (ambient + (1.0f - ambient) * diffuse), scene.surface_color.a);
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
  const auto shaded = [&](const LitVertex& v) { return lit_color(scene, v, light, ambient); };
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

namespace {

std::uint64_t next_static_id() {
  static std::atomic<std::uint64_t> next{1};
  return next++;
}

StaticGeometry built_static(const Surface& surface, ViewKind view) {
  StaticGeometry g = view_model(view).build_static(surface);
  add_edges(g);
  g.id = next_static_id();
  return g;
}

// A varying surface's mesh in a view: its shape (held, so that its address is never another's) and
// the view.
using ShapeKey = std::pair<std::shared_ptr<const SurfaceModel>, ViewKind>;
ShapeKey shape_key(const Surface& s, ViewKind view) {
  return {surface_model_of(s), view};
}

std::size_t bytes_of(const StaticGeometry& g) {
  return g.surface.size() * sizeof(LitVertex) + g.grid.size() * sizeof(Vertex) +
         g.edges.size() * sizeof(SurfaceEdge) + sizeof g;
}

// Keeps the newest entries within kStaticGeometryCache entries and kStaticGeometryBytes (the newest
// always, however large).
template <class Entries>
void trim(Entries& recent) {
  std::size_t bytes = 0;
  for (const auto& entry : recent) bytes += bytes_of(*entry.second);
  while (recent.size() > 1 && (recent.size() > kStaticGeometryCache || bytes > kStaticGeometryBytes)) {
    bytes -= bytes_of(*recent.front().second);
    recent.erase(recent.begin());
  }
}

}  // namespace

const StaticGeometry& static_geometry(SurfaceKind surface, ViewKind view) {
  static std::mutex mutex;
  static std::map<std::pair<SurfaceKind, ViewKind>, StaticGeometry> cache;
  const std::lock_guard lock(mutex);
  auto it = cache.find({surface, view});
  if (it == cache.end())
    it = cache.emplace(std::pair{surface, view}, built_static(Surface{surface, 1.0}, view)).first;
  return it->second;
}

std::shared_ptr<const StaticGeometry> static_geometry(const Surface& surface, ViewKind view) {
  if (!chart_free(surface))  // kept for ever: a shared_ptr that frees nothing
    return std::shared_ptr<const StaticGeometry>(std::shared_ptr<void>(),
                                                 &static_geometry(surface.kind, view));
  static std::mutex mutex;
  static std::vector<std::pair<ShapeKey, std::shared_ptr<const StaticGeometry>>> recent;  // newest last
  const ShapeKey key = shape_key(surface, view);
  {
    const std::lock_guard lock(mutex);
    for (auto it = recent.begin(); it != recent.end(); ++it)
      if (it->first == key) {
        auto entry = std::move(*it);
        recent.erase(it);
        recent.push_back(std::move(entry));
        return recent.back().second;
      }
  }
  auto built = std::make_shared<const StaticGeometry>(built_static(surface, view));  // outside the lock
  const std::lock_guard lock(mutex);
  recent.emplace_back(key, built);
  trim(recent);
  return built;
}

std::shared_ptr<const StaticGeometry> static_geometry(const Surface& surface, ViewKind view, PatchPlace at) {
  static std::mutex mutex;
  using Key = std::pair<ShapeKey, PatchPlace>;
  static std::vector<std::pair<Key, std::shared_ptr<const StaticGeometry>>> recent;  // newest last
  const Key key{shape_key(surface, view), at};
  {
    const std::lock_guard lock(mutex);
    for (const auto& [k, g] : recent)
      if (k == key) return g;
  }
  // The piece's triangles and lines, then the patch's: one mesh, its edges found anew (the patch's
  // border is an outline, as the piece's rim is).
  StaticGeometry g = *static_geometry(surface, view);
  StaticGeometry patch = view_model(view).build_patch(surface, at);
  g.surface.insert(g.surface.end(), patch.surface.begin(), patch.surface.end());
  g.grid.insert(g.grid.end(), patch.grid.begin(), patch.grid.end());
  g.edges.clear();
  add_edges(g);
  g.id = next_static_id();
  auto built = std::make_shared<const StaticGeometry>(std::move(g));
  const std::lock_guard lock(mutex);
  recent.emplace_back(key, built);
  if (recent.size() > 4) recent.erase(recent.begin());
  trim(recent);
  return built;
}

glm::vec3 curvature_color(double k, double full) {
  const double t = std::clamp(k / full, -1.0, 1.0);
  const glm::dvec3 white(0.97, 0.97, 0.96), warm(0.87, 0.33, 0.13), cool(0.16, 0.40, 0.80);
  return glm::vec3(t >= 0.0 ? white + t * (warm - white) : white - t * (cool - white));
}

LineWidths line_widths(int width, int height) {
  const double side = std::min(0.75 * width, static_cast<double>(height)) / 480.0;
  const double lines = 1.5 * side;
  return {static_cast<float>(std::max(1.0, lines)), static_cast<float>(std::max(1.0, lines * 2.0 / 3.0))};
}

namespace {

// The HUD's and legend's distance from the frame's edges [pixels at scale 1].
constexpr double kHudMargin = 6.0;

// Glyphs, not bytes: a UTF-8 continuation byte starts none.
std::size_t glyph_count(const std::string& text) {
  return static_cast<std::size_t>(
      std::count_if(text.begin(), text.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}
// The byte offset of glyph `n` (the text's size when it has fewer).
std::size_t glyph_offset(const std::string& text, std::size_t n) {
  for (std::size_t i = 0; i < text.size(); ++i)
    if ((text[i] & 0xC0) != 0x80 && n-- == 0) return i;
  return text.size();
}

}  // namespace

double hud_text_scale(int width, int height, int shown_width) {
  const double shown = shown_width > 0 ? shown_width : width;
  const double factor = width / shown;  // drawn pixels per shown pixel
  const double side = std::min(0.75 * shown, height / factor) / 540.0;
  double scale = std::max(1.0, std::round(2.0 * side) / 2.0);
  // The projector floor: a frame a page shows large (500 px high in 4:3 terms, the picture of a
  // 1366-wide page) gets at least 16 px text, legible from the back of a room.
  if (side * 540.0 >= kHudProjectorSide) scale = std::max(scale, 1.25);
  return scale * factor;
}

HudLayout hud_layout(const std::vector<std::string>& lines, const std::vector<std::string>& legend_labels,
                     int width, int height, int shown_width) {
  HudLayout h;
  const double wanted = hud_text_scale(width, height, shown_width);
  for (const double s : kHudScales)  // the nearest (the full picture's own scale where unpaced)
    if (std::abs(s - wanted) < std::abs(h.scale - wanted)) h.scale = s;
  h.font_size = 13.0 * h.scale;
  // ImGui snaps the default font's advance to whole pixels (ImFontConfig::PixelSnapH).
  h.advance = std::floor(7.0 * h.scale + 0.5);
  h.line = h.font_size + 2.0 * h.scale;
  h.padding = 5.0 * h.scale;
  h.swatch = 30.0 * h.scale;
  const double margin = kHudMargin * h.scale;
  const auto glyphs = [](const std::string& text) { return static_cast<double>(glyph_count(text)); };
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
  if (length == 0.0 || offers(surface, Offer::zero_curvature)) return X + v;
  if (chart_free(surface)) {
    // RK4's error is O((|v|κ/steps)⁴): a step per eighth of the smallest feature (a body's ellipse,
    // a quarter feature across, takes 2) keeps it under 1e-4 of the length drawn, below a pixel.
    const std::shared_ptr<const SurfaceModel> shape = surface_model_of(surface);
    const int steps = clamped_integer(std::ceil(8.0 * length / shape->feature), 1, 16);
    return implicit_exponential_map(*shape->implicit, X, v, steps);
  }
  return polar_C(surface, length) * X + (polar_S(surface, length) / length) * v;
}

glm::dvec3 world_position(const Surface& surface, ViewKind view, const Vec3& X) {
  return view_model(view).world_position(surface, X);
}

bool on_view(const Surface& surface, ViewKind view, const Vec3& X) {
  return view_model(view).on_view(surface, X);
}

double drawn_scale(const Surface& surface, const BodySnapshot& body, double scale) {
  if (offers(surface, Offer::zero_curvature)) return scale;
  // The frame's largest length over a² + b² = 1: √ of the Gram matrix's larger eigenvalue [length].
  const Mat2& g = body.gram;
  const double half_trace = 0.5 * (g(0, 0) + g(1, 1)), half_gap = 0.5 * (g(0, 0) - g(1, 1));
  const double extent = std::sqrt(std::max(0.0, half_trace + std::hypot(half_gap, g(0, 1))));
  double radius = surface.radius;
  if (chart_free(surface)) radius = surface_model_of(surface)->feature;
  const double limit = kMaxDrawnExtent * radius;
  return scale * extent > limit ? limit / extent : scale;
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

glm::vec4 bending_color(double kappa_length) {
  const double size = std::abs(kappa_length);
  if (!(size >= kStraightBending)) return kStraightColor;
  const double w = std::min(1.0, 0.4 + 0.6 * (size - kStraightBending) / (kFullBending - kStraightBending));
  return glm::mix(kStraightColor, kappa_length > 0.0 ? kBendsLeftColor : kBendsRightColor,
                  static_cast<float>(w));
}

bool main_trail_bends(const Snapshot& snapshot, const ViewOptions& view) {
  return (view.layers & kBending) && (view.layers & kTrail) && !snapshot.bodies.empty() &&
         !snapshot.bodies.front().geodesic && snapshot.bodies.front().trail.size() >= 3;
}

std::vector<double> main_trail_bending(const Snapshot& snapshot, const ViewOptions& view) {
  if (!main_trail_bends(snapshot, view)) return {};
  const BodySnapshot& body = snapshot.bodies.front();
  const SurfaceModel& surface = surface_model(snapshot);
  std::vector<double> kappa = geodesic_curvatures(surface, body.trail);
  for (double& k : kappa) k *= surface.feature;
  return kappa;
}

std::vector<LegendEntry> legend_entries(const Snapshot& snapshot, const ViewOptions& view) {
  std::vector<LegendEntry> legend;
  if (compact_overlay(view)) return legend;
  const bool bending = main_trail_bends(snapshot, view);
  if (snapshot.bodies.size() > 1 && (view.layers & (kBody | kTrail)))
    for (const BodySnapshot& body : snapshot.bodies)
      legend.push_back(
          {&body == &snapshot.bodies.front() && (view.layers & kPlain) && !snapshot.plain_main_label.empty()
               ? snapshot.plain_main_label
               : body.label,
           rgba(body.color),
           &body == &snapshot.bodies.front() && bending ? kStraightColor : rgba(body.trail_color),
           body.geodesic, true, std::nullopt});
  // The key whenever the trail is coloured, not as each colour first shows, and in one row: a
  // legend that grows moves its box, and the camera with it.
  if (bending)
    legend.push_back(
        {"path bends left / right", kBendsLeftColor, kBendsLeftColor, false, false, kBendsRightColor});
  if ((view.layers & kDrift) &&
      std::ranges::any_of(snapshot.bodies, [](const BodySnapshot& b) { return b.drift.has_value(); }))
    legend.push_back({"drift of the loops' centre", kDriftColor, kDriftColor, false, false, std::nullopt});
  return legend;
}

namespace {

// What the picture itself needs said: the main body off what the view draws, a 2-D close-up, a
// body drawn smaller than its scale.
std::vector<std::string> picture_notes(const Snapshot& snapshot, const ViewOptions& view) {
  std::vector<std::string> lines;
  if (!snapshot.bodies.empty() && !on_view(snapshot.surface, view.kind, snapshot.bodies.front().X))
    lines.push_back(
        std::string(view_model(view.kind).off_view_note(snapshot.surface, snapshot.bodies.front().X)));
  // A 2-D close-up (aim_2d_window): by how much.
  if (view.zoom > 1.0) {
    char text[64];
    std::snprintf(text, sizeof text, "close-up %gx (bodies far out)", view.zoom);
    lines.push_back(text);
  }
  // A frame too large to draw at the picture's scale is drawn smaller: say by how much.
  if (!snapshot.bodies.empty() && (view.layers & (kBody | kFrame))) {
    const double shrink =
        view_model(view.kind).body_drawing_scale(snapshot.surface, snapshot.bodies.front(), view.scale) /
        view.scale;
    if (shrink < 1.0) {
      char text[64];
      std::snprintf(text, sizeof text, " drawn at %.2g x its size", shrink);
      const std::string& label = snapshot.bodies.front().label;
      lines.push_back((label.empty() ? std::string("body 1") : label) + text);
    }
  }
  return lines;
}

}  // namespace

std::vector<std::string> readout_lines(const Snapshot& snapshot, const ViewOptions& view) {
  const bool plain = (view.layers & kPlain) != 0;
  std::vector<std::string> lines = plain ? snapshot.plain_lines : snapshot.hud_lines;
  const std::size_t surface_line = plain ? kPlainSurfaceLine : kSurfaceReadoutLine;
  if (view.layers & kActions)
    lines.insert(lines.end(), snapshot.action_lines.begin(), snapshot.action_lines.end());
  // The bending layer in words at the body where the curvature varies (the lesson: the bending
  // follows K's sign), on the line that gives K there: which way the path turns now.
  // (κ_g of the trail's last three points alone: the HUD is asked at every aim.)
  if (main_trail_bends(snapshot, view) && surface_model(snapshot).offers(Offer::implicit_equation) &&
      lines.size() > surface_line) {
    const std::vector<Vec3>& trail = snapshot.bodies.front().trail;
    const SurfaceModel& surface = surface_model(snapshot);
    const double k = geodesic_curvatures(surface, {trail.end() - 3, trail.end()})[1] * surface.feature;
    lines[surface_line] += k >= kStraightBending    ? ": the path bends left"
                           : k <= -kStraightBending ? ": the path bends right"
                                                    : ": the path runs straight";
  }
  const std::vector<std::string> notes = picture_notes(snapshot, view);
  lines.insert(lines.end(), notes.begin(), notes.end());
  return lines;
}

std::vector<std::string> hud_lines(const Snapshot& snapshot, const ViewOptions& view) {
  const bool compact = compact_overlay(view);
  std::vector<std::string> lines;
  if (!compact) {
    lines = readout_lines(snapshot, view);
  } else {
    if (!snapshot.hud_lines.empty()) lines.push_back(snapshot.hud_lines.front());
    // The action variables are asked for (a layer off by default): they stay.
    if (view.layers & kActions)
      lines.insert(lines.end(), snapshot.action_lines.begin(), snapshot.action_lines.end());
    const std::vector<std::string> notes = picture_notes(snapshot, view);
    lines.insert(lines.end(), notes.begin(), notes.end());
  }
  // No line runs past the frame (a compact HUD: past half of it), nor, beside the legend, into it (the
  // bump's companions ran under it): longer ones wrap at a space, the rest indented. The boxes' sizes
  // are hud_layout's.
  std::vector<std::string> labels;
  for (const LegendEntry& entry : legend_entries(snapshot, view)) labels.push_back(entry.label);
  const HudLayout size = hud_layout({}, labels, view.width, view.height, view.shown_width);
  const double margin = kHudMargin * size.scale;
  const auto most_at = [&](std::size_t row) {  // glyphs on the HUD's line `row` (from 0)
    const double top = margin + size.padding + row * size.line;
    const bool beside = size.legend.w > 0.0 && top < size.legend.y + size.legend.h + margin;
    const double right = beside ? size.legend.x - margin : (compact ? 0.5 : 1.0) * view.width - margin;
    const double room = right - margin - 2.0 * size.padding;
    return static_cast<std::size_t>(std::max(16.0, std::floor(room / size.advance)));
  };
  std::vector<std::string> wrapped;
  for (std::string line : lines) {
    for (std::size_t most = most_at(wrapped.size()); glyph_count(line) > most;
         most = most_at(wrapped.size())) {
      const std::size_t cut = line.rfind(' ', glyph_offset(line, most));
      if (cut == std::string::npos || cut <= 2) break;  // one long word: left as it is
      wrapped.push_back(line.substr(0, cut));
      line = "  " + line.substr(cut + 1);
    }
    wrapped.push_back(line);
  }
  return wrapped;
}

FrameScene build_scene(const Snapshot& snapshot, const ViewOptions& view) {
  FrameScene scene;
  const Surface& surface = snapshot.surface;
  const ViewModel& model = view_model(view.kind);
  scene.draw_surface = (view.layers & kSurface) != 0;
  scene.draw_grid = (view.layers & kGrid) != 0;
  if ((scene.draw_surface || scene.draw_grid) && model.uses_static()) {
    const std::optional<PatchPlace> patch = model.patch_at(snapshot);
    scene.statics = patch ? static_geometry(surface, view.kind, *patch) : static_geometry(surface, view.kind);
  }
  scene.tint_by_curvature = (view.layers & kCurvature) != 0;
  scene.view_projection = model.camera(view);
  scene.depth_test = view_info(view.kind).three_d;
  scene.depth_bias = model.depth_bias();
  if (offers(surface, Offer::negative_curvature)) scene.surface_color = {0.83f, 0.86f, 0.78f, 1.0f};
  model.add_background(scene, surface, view);

  // Trails first, then the bodies over them: every body's, main body first; the main body's
  // coloured by its bending where that layer is on (each point's colour, the chords between two
  // points shading from one to the other).
  const std::optional<Window2d> clip = model.clip(view);
  scene.trails_begin = scene.lines.size();
  if (view.layers & kTrail) {
    const std::vector<double> bending = main_trail_bending(snapshot, view);
    for (std::size_t b = 0; b < snapshot.bodies.size(); ++b) {
      const BodySnapshot& body = snapshot.bodies[b];
      if (body.trail.size() < 2) continue;
      const bool coloured = b == 0 && bending.size() == body.trail.size();
      std::vector<Vec3> path{body.trail.front()};
      std::vector<glm::vec4> colors;
      if (coloured) colors.push_back(bending_color(bending.front()));
      for (std::size_t i = 1; i < body.trail.size(); ++i) {
        const std::size_t from = path.size();
        append_path(path, surface, body.trail[i - 1], body.trail[i]);
        if (!coloured) continue;
        const glm::vec4 a = bending_color(bending[i - 1]), c = bending_color(bending[i]);
        const std::size_t n = path.size() - from + 1;
        for (std::size_t k = 1; k < n; ++k) colors.push_back(glm::mix(a, c, static_cast<float>(k) / n));
        colors.back() = c;
      }
      if (body.geodesic)
        add_dashed_polyline(scene.lines, surface, model, path, rgba(body.trail_color),
                            clip ? &*clip : nullptr);
      else if (coloured)
        add_polyline(scene.lines, surface, model, path, colors, clip ? &*clip : nullptr);
      else
        add_polyline(scene.lines, surface, model, path, rgba(body.trail_color), false,
                     clip ? &*clip : nullptr);
    }
  }
  scene.trails_end = scene.lines.size();
  model.add_bodies(scene, snapshot, view);
  scene.legend = legend_entries(snapshot, view);
  if (view.layers & kHud) scene.hud_lines = render::hud_lines(snapshot, view);
  std::vector<std::string> labels;
  for (const LegendEntry& entry : scene.legend) labels.push_back(entry.label);
  scene.hud = hud_layout(scene.hud_lines, labels, view.width, view.height, view.shown_width);
  return scene;
}

void aim_camera_at_body(ViewOptions& view, const Snapshot& snapshot) {
  if (snapshot.bodies.empty()) return;
  view_model(view.kind).aim(view, snapshot, hud_boxes(snapshot, view));
}

std::optional<glm::dvec2> pixel_position(const FrameScene& scene, const ViewOptions& view,
                                         const glm::dvec3& world) {
  const glm::dvec4 clip = glm::dmat4(scene.view_projection) * glm::dvec4(world, 1.0);
  if (clip.w <= 0.0) return std::nullopt;
  const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  return glm::dvec2((ndc.x + 1.0) * 0.5 * view.width, (1.0 - ndc.y) * 0.5 * view.height);
}

}  // namespace spinfold::render
