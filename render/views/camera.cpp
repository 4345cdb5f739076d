#include "render/views/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <utility>

#include "render/view_table.h"
#include "render/views/drawing.h"

namespace spinfold::render {

glm::mat4 orbit_camera(const ViewOptions& view, const glm::dvec3& default_target) {
  const double aspect = static_cast<double>(view.width) / view.height;
  const glm::dvec3 target =
      view.target ? glm::dvec3((*view.target)[0], (*view.target)[1], (*view.target)[2]) : default_target;
  const glm::dvec3 dir(std::cos(view.pitch) * std::cos(view.yaw), std::cos(view.pitch) * std::sin(view.yaw),
                       std::sin(view.pitch));
  const glm::dvec3 eye = target + view.distance * dir;
  const glm::dvec3 up = std::abs(dir.z) > 0.999 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
  // Near and far planes grow with a camera drawn back to frame a body far out on H².
  const double reach = std::max(1.0, view.distance / 5.0);
  return glm::mat4(glm::perspective(glm::radians(kFovY), aspect, 0.05 * reach, 100.0 * reach) *
                   glm::lookAt(eye, target, up));
}

Window2d window_around(const ViewOptions& view, const glm::dvec2& centre, double half) {
  const double aspect = static_cast<double>(view.width) / view.height;
  Window2d w;
  w.centre = centre;
  w.hx = aspect >= 1 ? half * aspect : half;
  w.hy = aspect >= 1 ? half : half / aspect;
  return w;
}

glm::dvec2 target_or(const ViewOptions& view, const glm::dvec2& otherwise) {
  return view.target ? glm::dvec2((*view.target)[0], (*view.target)[1]) : otherwise;
}

glm::dvec3 eye_of(const glm::mat4& view_projection) {
  const glm::dvec4 h = glm::inverse(glm::dmat4(view_projection)) * glm::dvec4(0, 0, 1, 0);
  return glm::dvec3(h) / h.w;
}

glm::mat4 window_camera(const Window2d& w) {
  return glm::mat4(
      glm::ortho(w.centre.x - w.hx, w.centre.x + w.hx, w.centre.y - w.hy, w.centre.y + w.hy, -1.0, 1.0));
}

std::vector<Sight> sights(const ViewModel& model, const Snapshot& snapshot, const ViewOptions& view,
                          bool recent_only) {
  const Surface& surface = snapshot.surface;
  std::vector<Sight> out;
  for (const BodySnapshot& body : snapshot.bodies) {
    if (!model.draws(surface, body.X)) continue;
    const double weight = &body == &snapshot.bodies.front() ? 1000.0 : 50.0;
    out.push_back({model.world_position(surface, body.X), weight});
    for (const Vec3& P :
         ellipse_points(surface, body, model.body_drawing_scale(surface, body, view.scale), 8))
      if (model.draws(surface, P)) out.push_back({model.world_position(surface, P), 5.0});
  }
  for (const BodySnapshot& body : snapshot.bodies) {
    const std::size_t stride = body.trail.size() / 96 + 1;
    const double weight = 10.0 * static_cast<double>(stride) / static_cast<double>(body.trail.size());
    for (std::size_t i = 0; i < body.trail.size(); i += stride) {
      const Vec3& P = body.trail[i];
      if (!model.draws(surface, P)) continue;
      if (recent_only && !chart_free(surface)) {  // the trail's last stretch: within 3 radii
        const double R = surface.radius, c = -dot(surface, P, body.X) / (R * R);  // (intrinsic) of its body
        if (R * std::acosh(std::max(1.0, c)) > 3.0 * R) continue;
      }
      out.push_back({model.world_position(surface, P), weight});
    }
  }
  return out;
}

HudLayout hud_boxes(const Snapshot& snapshot, const ViewOptions& view) {
  std::vector<std::string> labels;
  for (const LegendEntry& entry : legend_entries(snapshot, view)) labels.push_back(entry.label);
  const std::vector<std::string> lines =
      view.layers & kHud ? hud_lines(snapshot, view) : std::vector<std::string>{};
  return hud_layout(lines, labels, view.width, view.height, view.shown_width);
}

double badness(const ViewModel& model, const Surface& surface, const ViewOptions& view,
               const std::vector<Sight>& points, const HudLayout& hud, double enough) {
  FrameScene scene;
  scene.view_projection = model.camera(view);
  const double margin = 0.04 * std::min(view.width, view.height),
               edge = 0.01 * std::min(view.width, view.height);
  const auto grown = [&](const PixelBox& b) {
    return b.w > 0.0 ? PixelBox{b.x - margin, b.y - margin, b.w + 2 * margin, b.h + 2 * margin} : b;
  };
  const PixelBox hud_box = grown(hud.hud), legend_box = grown(hud.legend);
  const glm::dvec3 eye = eye_of(scene.view_projection);
  double bad = 0.0;
  if (!model.on_lit_side(eye)) {  // worse than any camera on the lit side, however much that one hides
    for (const Sight& p : points) bad += p.weight;
    return 2.0 * bad + 1.0;
  }
  for (const Sight& p : points) {
    if (bad >= enough) break;
    // The projection first: a sight out of the frame or under a box costs no ray cast.
    const std::optional<glm::dvec2> px = pixel_position(scene, view, p.at);
    if (!px || px->x < edge || px->y < edge || px->x > view.width - edge || px->y > view.height - edge ||
        hud_box.contains(*px) || legend_box.contains(*px) || model.hidden(surface, p.at, eye))
      bad += p.weight;
  }
  return bad;
}

double clear_the_boxes(const ViewModel& model, const Surface& surface, ViewOptions& view,
                       const std::vector<Sight>& points, const HudLayout& hud,
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
      const double bad = badness(model, surface, v, points, hud, best);
      if (bad < best) best = bad, view = v;
      if (best == 0.0) return best;
    }
  return best;
}

double slide_clear_of_boxes(const ViewModel& model, const Surface& surface, ViewOptions& view,
                            const std::vector<Sight>& points, const HudLayout& hud) {
  double best = badness(model, surface, view, points, hud);
  if (best == 0.0 || !view.target) return best;
  const glm::dvec3 target((*view.target)[0], (*view.target)[1], (*view.target)[2]);
  const glm::dvec3 dir(std::cos(view.pitch) * std::cos(view.yaw), std::cos(view.pitch) * std::sin(view.yaw),
                       std::sin(view.pitch));
  const glm::dvec3 up_hint = std::abs(dir.z) > 0.999 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
  const glm::dvec3 right = glm::normalize(glm::cross(-dir, up_hint)), up = glm::cross(right, -dir);
  // Half the frame's height and width at the target's depth [world units].
  const double half_h = view.distance * std::tan(glm::radians(kFovY) / 2);
  const double half_w = half_h * view.width / view.height;
  // Where on the screen the target goes, in half-frames (x right, y up): the sights move with it.
  constexpr double kSlides[][2] = {{0.3, -0.3}, {0.3, 0},     {0, -0.3},  {0.45, -0.45}, {0.45, 0},
                                   {0, -0.45},  {-0.3, -0.3}, {0.3, 0.3}, {0.45, 0.45},  {-0.45, -0.45}};
  const ViewOptions start = view;
  for (const auto& slide : kSlides) {
    ViewOptions v = start;
    const glm::dvec3 t = target - slide[0] * half_w * right - slide[1] * half_h * up;
    v.target = std::array<double, 3>{t.x, t.y, t.z};
    const double bad = badness(model, surface, v, points, hud, best);
    if (bad < best) best = bad, view = v;
    if (best == 0.0) break;
  }
  return best;
}

void aim_orbit(const ViewModel& model, ViewOptions& view, const Snapshot& snapshot, const HudLayout& hud,
               double min_radius, double pitch, double yaw_turn) {
  const std::vector<Sight> points = sights(model, snapshot, view, true);
  if (points.empty()) return;  // every body off the view (beyond the tractricoid's rim): the default camera
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const Sight& p : points) lo = glm::min(lo, p.at), hi = glm::max(hi, p.at);
  const glm::dvec3 centre = 0.5 * (lo + hi);
  double radius = min_radius;
  for (const Sight& p : points) radius = std::max(radius, glm::length(p.at - centre));
  const double aspect = static_cast<double>(view.width) / view.height;
  const double half_fov = std::atan(std::tan(glm::radians(kFovY) / 2) * std::min(1.0, aspect));
  view.target = std::array<double, 3>{centre.x, centre.y, centre.z};
  view.distance = radius / std::sin(0.85 * half_fov);
  view.pitch = pitch;
  if (glm::length(glm::dvec2(centre)) > 1e-9) view.yaw = std::atan2(centre.y, centre.x) + yaw_turn;
  // Steeper until the camera is on the surface's lit side (near the hyperboloid's vertex a camera
  // drawn back at the preferred pitch ends up under the sheet).
  const auto eye = [&] {
    return centre + view.distance * glm::dvec3(std::cos(view.pitch) * std::cos(view.yaw),
                                               std::cos(view.pitch) * std::sin(view.yaw),
                                               std::sin(view.pitch));
  };
  while (!model.on_lit_side(eye()) && view.pitch < 1.3) view.pitch = std::min(1.3, view.pitch + 0.05);
  clear_the_boxes(model, snapshot.surface, view, points, hud, {1.0, 1.25, 1.6});
}

void aim_at_bodies_centre(const ViewModel& model, ViewOptions& view, const Snapshot& snapshot) {
  glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const BodySnapshot& body : snapshot.bodies) {
    const glm::dvec3 w = model.world_position(snapshot.surface, body.X);
    lo = glm::min(lo, glm::dvec2(w)), hi = glm::max(hi, glm::dvec2(w));
  }
  const glm::dvec2 c = 0.5 * (lo + hi);
  view.target = std::array<double, 3>{c.x, c.y, 0.0};
}

Window2d zoomed_window(const ViewOptions& view, const glm::dvec2& home, double half) {
  return window_around(view, target_or(view, home), half / view.zoom);
}

namespace {

// How many times smaller the map draws lengths at the main body than at the pole: the geometric
// mean over its two frame directions (the Klein disk shrinks radially more), by steps of 1e-4 R.
double shrink_at_main_body(const ViewModel& model, const Snapshot& snapshot) {
  const Surface& surface = snapshot.surface;
  const BodySnapshot& body = snapshot.bodies.front();
  const double step = 1e-4 * surface.radius;
  const auto moved = [&](const Vec3& a, const Vec3& b) {
    return glm::length(model.world_position(surface, a) - model.world_position(surface, b)) / step;
  };
  const double at_pole = moved(chart_point(surface, step, 0.0).X, chart_point(surface, 0.0, 0.0).X);
  double at_body = 1.0;
  for (const int A : {0, 1}) {
    const double a = step / std::sqrt(body.gram(A, A));  // a degenerate frame: NaN, no close-up
    at_body *= moved(exp_frame(surface, body, A == 0 ? a : 0.0, A == 1 ? a : 0.0), body.X);
  }
  return std::sqrt(at_body) / at_pole;
}

}  // namespace

void aim_2d_window(const ViewModel& model, ViewOptions& view, const Snapshot& snapshot, const HudLayout& hud,
                   double half) {
  view.zoom = 1.0;
  const std::vector<Sight> points = sights(model, snapshot, view, true);
  if (points.empty() || !model.draws(snapshot.surface, snapshot.bodies.front().X)) return;
  glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const Sight& p : points) lo = glm::min(lo, glm::dvec2(p.at)), hi = glm::max(hi, glm::dvec2(p.at));
  // Comfortable while the main body is drawn at least a third of its size at the pole.
  const double shrink =
      chart_free(snapshot.surface) ? 1.0 : shrink_at_main_body(model, snapshot);  // the chart
  if (shrink < 1.0 / 3.0) {
    // The half-size of the smallest window (window_around's shape) that holds the sights: they
    // stay within the middle 60% of the frame.
    const Window2d unit = window_around(view, glm::dvec2(0.0), 1.0);
    const double need = std::max(0.5 * (hi.x - lo.x) / unit.hx, 0.5 * (hi.y - lo.y) / unit.hy) / 0.6;
    double zoom = std::min({1.0 / shrink, half / need, kMaxCloseUp});
    if (zoom >= 2.0) {
      // The HUD with the zoom's line (readout_lines adds it).
      HudLayout with_line = hud;
      if (with_line.hud.w > 0.0) with_line.hud.h += with_line.line;
      const glm::dvec2 centre = 0.5 * (lo + hi);
      ViewOptions v = view;
      v.target = std::array<double, 3>{centre.x, centre.y, 0.0};
      for (zoom = std::exp2(std::floor(std::log2(zoom))); zoom >= 2.0; zoom /= 2.0) {
        v.zoom = zoom;
        if (badness(model, snapshot.surface, v, points, with_line) == 0.0) {
          view = v;
          return;
        }
      }
    }
  }
  // The view's own window, unless a sight is out of it or under a box: then slid away from the
  // boxes (the HUD top left, the legend top right) by up to 40% of the window each way, and drawn
  // back by up to 4 times (the stereographic map of a body near the south pole), the first of
  // these that shows them all, else the one whose badness plus a cost of drawing back,
  // 8·(1/zoom − 1), is least: a bit of trail under the HUD is better than a picture half as large.
  double best = badness(model, snapshot.surface, view, points, hud);
  if (best == 0.0) return;
  const glm::dvec2 home = target_or(view, glm::dvec2(0.0));
  constexpr double kSlides[][2] = {{0, 0},      {-0.2, 0},  {0, 0.2},    {-0.2, 0.2}, {-0.4, 0},
                                   {-0.4, 0.2}, {0, 0.4},   {-0.2, 0.4}, {-0.4, 0.4}, {0.2, 0},
                                   {0.2, 0.2},  {0.4, 0.2}, {0.4, 0},    {0, -0.2},   {-0.2, -0.2}};
  const ViewOptions start = view;
  for (const double zoom : {1.0, 0.8, 0.64, 0.5, 0.25})
    for (const auto& slide : kSlides) {
      ViewOptions v = start;
      v.zoom = zoom;
      const Window2d w = window_around(v, home, half / zoom);
      const glm::dvec2 c = home + glm::dvec2(slide[0] * w.hx, slide[1] * w.hy);
      v.target = std::array<double, 3>{c.x, c.y, 0.0};
      const double drawn_back = 8.0 * (1.0 / zoom - 1.0);
      const double bad = drawn_back + badness(model, snapshot.surface, v, points, hud, best - drawn_back);
      if (bad < best) best = bad, view = v;
      if (best == 0.0) return;
    }
}

bool shows_main_body(const ViewOptions& view, const Snapshot& snapshot, bool behind_too) {
  if (snapshot.bodies.empty()) return true;
  const ViewModel& model = view_model(view.kind);
  const Vec3& X = snapshot.bodies.front().X;
  if (!model.draws(snapshot.surface, X)) return true;
  const std::vector<Sight> main{{model.world_position(snapshot.surface, X), 1.0}};
  if (!behind_too || !model.shows_through())
    return badness(model, snapshot.surface, view, main, hud_boxes(snapshot, view)) == 0.0;
  // In the frame and clear of the boxes, in sight or not: a model that sees nothing hidden.
  struct NothingHidden final : ViewModel {
    const ViewModel& of;
    explicit NothingHidden(const ViewModel& m) : of(m) {}
    glm::dvec3 world_position(const Surface& s, const Vec3& P) const override {
      return of.world_position(s, P);
    }
    glm::mat4 camera(const ViewOptions& v) const override { return of.camera(v); }
    bool on_lit_side(const glm::dvec3& eye) const override { return of.on_lit_side(eye); }
  };
  return badness(NothingHidden(model), snapshot.surface, view, main, hud_boxes(snapshot, view)) == 0.0;
}

void add_ghosts(FrameScene& scene, const ViewModel& model, const Snapshot& snapshot,
                const ViewOptions& view) {
  const glm::dvec3 eye = eye_of(scene.view_projection);
  const Surface& surface = snapshot.surface;
  for (const BodySnapshot& body : snapshot.bodies) {
    if (!model.draws(surface, body.X) || !model.hidden(surface, model.world_position(surface, body.X), eye))
      continue;
    FrameScene ghost;
    const double scale = model.body_drawing_scale(surface, body, view.scale);
    if (view.layers & kBody) add_body(ghost, surface, model, scale, body);
    if (view.layers & kFrame) add_frame_arrows(ghost, surface, model, scale, body);
    for (Vertex& v : ghost.fills) v.color.a *= kGhostAlpha;
    for (Vertex& v : ghost.lines) v.color.a *= kGhostAlpha;
    scene.ghost_fills.insert(scene.ghost_fills.end(), ghost.fills.begin(), ghost.fills.end());
    scene.ghost_lines.insert(scene.ghost_lines.end(), ghost.lines.begin(), ghost.lines.end());
  }
  if (!model.shows_through()) return;  // the sphere: its bodies only (a trail round it is seen across)
  for (std::size_t i = scene.trails_begin; i < scene.trails_end; ++i) {
    Vertex v = scene.lines[i];
    v.color.a *= kGhostAlpha;
    scene.ghost_lines.push_back(v);
  }
}

void aim_in_space(const ViewModel& model, ViewOptions& view, const Snapshot& snapshot, const HudLayout& hud,
                  const SpaceAim& aim) {
  const Surface& surface = snapshot.surface;
  const glm::dvec3 n = aim.normal;
  view.target.reset();
  std::vector<Sight> points = sights(model, snapshot, view, true);
  // An unbounded surface is drawn beyond its piece too, but the camera frames what is on the piece
  // (a companion escaping to infinity is not followed) — unless the main body is beyond: then it
  // follows that body, framing it and its outline alone (the HUD says where it is).
  std::erase_if(points, [&](const Sight& p) { return !aim.on_piece(p.at); });
  const BodySnapshot& main = snapshot.bodies.front();
  if (!aim.on_piece(model.world_position(surface, main.X)) && model.draws(surface, main.X)) {
    points = {{model.world_position(surface, main.X), 1000.0}};
    for (const Vec3& P :
         ellipse_points(surface, main, model.body_drawing_scale(surface, main, view.scale), 8))
      points.push_back({model.world_position(surface, P), 5.0});
  }
  if (points.empty()) return;
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const Sight& p : points) lo = glm::min(lo, p.at), hi = glm::max(hi, p.at);
  const glm::dvec3 centre = aim.whole > 0.0 ? glm::dvec3(0.0) : 0.5 * (lo + hi);
  double radius = std::max(aim.radius, aim.whole);
  for (const Sight& p : points) radius = std::max(radius, glm::length(p.at - centre));
  const double aspect = static_cast<double>(view.width) / view.height;
  const double half_fov = std::atan(std::tan(glm::radians(kFovY) / 2) * std::min(1.0, aspect));
  view.target = std::array<double, 3>{centre.x, centre.y, centre.z};
  const double base = radius / std::sin(0.85 * half_fov);
  double best = std::numeric_limits<double>::infinity();
  // The preferences first: the badness is summed only while the camera can still win.
  const auto cost = [&](const ViewOptions& v, double pull) {
    const glm::dvec3 towards(std::cos(v.pitch) * std::cos(v.yaw), std::cos(v.pitch) * std::sin(v.yaw),
                             std::sin(v.pitch));
    const double preference = 4.0 * (pull - 1.0) / 0.6 + 1.5 * (1.0 - std::abs(glm::dot(towards, n))) +
                              0.5 * std::abs(v.pitch - 0.5);
    return badness(model, surface, v, points, hud, best - preference) + preference;
  };
  const auto consider = [&](double yaw, double pitch, double pull) {
    ViewOptions v = view;
    v.yaw = yaw, v.pitch = pitch, v.distance = base * pull;
    const double c = cost(v, pull);
    if (c < best) best = c, view = v;
  };
  const double normal_yaw =
      std::hypot(n.x, n.y) > 1e-6 ? std::atan2(n.y, n.x) : std::atan2(centre.y, centre.x);
  const double lowest = std::max(-1.2, model.lowest_pitch(surface));
  const double facing_pitch = std::clamp(std::asin(std::clamp(n.z, -1.0, 1.0)), lowest, 1.2);
  // Most frames end here: from the body's own side, a little above, everything is seen (badness
  // 0); the wide search (183 cameras, each casting a ray per sight) is for the rest.
  for (const double pitch : {std::max(facing_pitch, 0.5), facing_pitch}) consider(normal_yaw, pitch, 1.0);
  if (best < 3.0) return;  // nothing hidden or boxed: only the preferences are left to weigh
  for (const double pull : {1.0, 1.3, 1.6}) {
    consider(normal_yaw, facing_pitch, pull);
    bool floor_tried = false;  // the elevations below the lowest are tried once, at the lowest
    for (const double wanted : {1.15, 0.75, 0.35, -0.35, -0.75}) {
      if (wanted < lowest && std::exchange(floor_tried, true)) continue;
      for (int k = 0; k < 12; ++k) consider(normal_yaw + 2 * kPi * k / 12, std::max(wanted, lowest), pull);
    }
  }
  // The main body still hidden or boxed: in a small frame the HUD covers the centre, where every
  // orbit puts the body. Slide it to the free side, seen from its own side if that clears it. (Not
  // where it is only behind the surface, drawn through it: on the underside no camera sees it.)
  if (best >= 1000.0 && !shows_main_body(view, snapshot, true)) {
    ViewOptions facing = view;
    facing.yaw = normal_yaw, facing.pitch = std::max(facing_pitch, 0.5), facing.distance = base;
    if (slide_clear_of_boxes(model, surface, facing, points, hud) < 1000.0)
      view = facing;
    else
      slide_clear_of_boxes(model, surface, view, points, hud);
  }
}

}  // namespace spinfold::render
