// The sphere in space, seen by an orbiting camera.
#include <algorithm>
#include <cmath>
#include <limits>

#include "render/views/camera.h"
#include "render/views/drawing.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

// FrameScene::depth_bias: overlays lie on the sphere exactly (its mesh is circumscribed, every
// face outside the unit sphere, so nothing drawn on the sphere pokes out past the mesh's limb) and
// the bias keeps them in front of the faces.
constexpr float kSphereDepthBias = 0.01f;

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

class SphereView final : public ViewModel {
 public:
  // X/R: the unit sphere.
  glm::dvec3 world_position(const Surface& surface, const Vec3& X) const override {
    return glm::dvec3(X.x(), X.y(), X.z()) / surface.radius;
  }
  glm::dvec3 normal(const Surface& /*surface*/, const glm::dvec3& w) const override {
    return glm::normalize(w);
  }

  // A UV sphere of 64 slices and 32 stacks, circumscribed; parallels every 15°, meridians every 30°.
  StaticGeometry build_static(const Surface& surface) const override {
    const SurfaceKind kind = surface.kind;
    StaticGeometry g;
    const Surface unit{kind, 1.0};
    const int slices = 64, stacks = 32;
    const auto vertex = [](double theta, double phi) {
      const glm::dvec3 p(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      return LitVertex{to_float(p), to_float(p)};
    };
    for (int i = 0; i < stacks; ++i)
      for (int j = 0; j < slices; ++j) {
        const double t0 = kPi * i / stacks, t1 = kPi * (i + 1) / stacks;
        const double p0 = 2 * kPi * j / slices, p1 = 2 * kPi * (j + 1) / slices;
        add_quad(g, vertex(t0, p0), vertex(t1, p0), vertex(t1, p1), vertex(t0, p1));
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
      add_grid_curve(
          g.grid, unit, *this, [&](double s) { return chart_point(unit, kPi * k / 12, 2 * kPi * s).X; }, 96);
    for (int k = 0; k < 12; ++k)  // meridians every 30°
      add_grid_curve(
          g.grid, unit, *this, [&](double s) { return chart_point(unit, kPi * s, 2 * kPi * k / 12).X; }, 48);
    return g;
  }

  glm::mat4 camera(const ViewOptions& view) const override { return orbit_camera(view, orbit_home()); }
  float depth_bias() const override { return kSphereDepthBias; }
  // Beyond the limb, or so near it (more than 60° from the camera's direction) that it is seen edge-on.
  bool hidden(const Surface& /*surface*/, const glm::dvec3& at, const glm::dvec3& eye) const override {
    return glm::dot(at, glm::normalize(eye)) < 0.5;
  }

  // Looking at the centre of everything drawn of the bodies, turned and tilted until every body
  // and as much of every trail as can be are in the frame and out of the boxes. When that loses a
  // body (trails round the sphere put the centre of everything far from the bodies), looking at
  // the bodies' own centre instead, then at the main body; the best of these.
  // Every body as usual, and a body behind the sphere (its centre hidden) once more, faintly, through
  // it: bodies far apart on the sphere (a fan, a geodesic companion on the far side) fit in no
  // camera's face-on cap, and the far one must not vanish.
  void add_bodies(FrameScene& scene, const Snapshot& snapshot, const ViewOptions& view) const override {
    ViewModel::add_bodies(scene, snapshot, view);
    add_ghosts(scene, *this, snapshot, view);
  }

  void aim(ViewOptions& view, const Snapshot& snapshot, const HudLayout& hud) const override {
    view.target.reset();
    const std::vector<Sight> points = sights(*this, snapshot, view, false);
    Vec3 bodies = Vec3::Zero();
    for (const BodySnapshot& body : snapshot.bodies) bodies += body.X.normalized();
    const Vec3 main = snapshot.bodies.front().X.normalized();
    const Vec3 starts[] = {snapshot.bodies.size() > 1 ? drawn_centre(snapshot) : main,
                           bodies.norm() > 1e-9 ? Vec3(bodies.normalized()) : main, main};
    const double a_body = 50.0;  // a companion's weight (sights): less than that lost is trail only
    double best = std::numeric_limits<double>::infinity();
    const ViewOptions start = view;
    for (const Vec3& n : starts) {
      ViewOptions v = start;
      v.yaw = std::atan2(n.y(), n.x());
      v.pitch = std::clamp(std::asin(n.z()), -1.3, 1.3);
      // Drawn back as far as 1.75× when nearer cameras cannot clear the boxes: bodies far apart
      // (one near the pole, one on the equator, with the HUD across the top of a 640×480 frame)
      // otherwise end with the camera tilted over one of them and the other beside the limb, its
      // ellipse seen edge-on.
      const double bad = clear_the_boxes(*this, snapshot.surface, v, points, hud, {1.0, 1.2, 1.45, 1.75});
      if (bad < best) best = bad, view = v;
      if (best < a_body) return;
    }
    // Still a body lost (the turns that clear the HUD take one of two far-apart bodies past the
    // limb): face the bodies' centre and slide the sphere across the frame instead.
    for (const double pull : {1.0, 1.2, 1.45}) {
      ViewOptions v = start;
      v.yaw = std::atan2(starts[1].y(), starts[1].x());
      v.pitch = std::clamp(std::asin(starts[1].z()), -1.3, 1.3);
      v.distance = start.distance * pull;
      v.target = std::array<double, 3>{0.0, 0.0, 0.0};
      const double bad = slide_clear_of_boxes(*this, snapshot.surface, v, points, hud);
      if (bad < best) best = bad, view = v;
      if (best < a_body) return;
    }
  }
  std::string grid_caption(const Snapshot& /*snapshot*/, const ViewOptions& /*view*/) const override {
    return "Grid: parallels every 15 degrees, meridians every 30 degrees.";
  }
};

}  // namespace

const ViewModel& sphere_view() {
  static const SphereView view;
  return view;
}

}  // namespace spinfold::render
