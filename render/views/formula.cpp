// A surface given by a formula (implicit F = 0 or a graph z = f(x, y)) in space: the mesh of its
// drawn box (render/implicit_mesh.h) lit by the exact normal ∇F/|∇F|, a grid that needs no symmetry
// (the level curves of x, y and z, the contour lines of a map), the K = 0 curves marked, and the
// curvature layer's colours from K(F) at the vertices. World units are (X − c)/ℓ with c the box's
// centre and ℓ its half-size (SurfaceModel), so that every shape fits the same camera.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "engine/surface_geodesics.h"
#include "engine/surface_model.h"
#include "render/implicit_mesh.h"
#include "render/views/camera.h"
#include "render/views/drawing.h"
#include "render/views/profile_drawing.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

// Overlays lie on the true surface; the mesh's flat faces cut inside it by their sagitta, which this
// bias (a fraction of the distance to the camera, as the revolution view's) covers.
constexpr float kFormulaDepthBias = 0.01f;
// The patch round a main body beyond the box: a cube of this many framing radii each way, at most
// the box's half-size, meshed as finely as the box.
// A closed zero set's half-extent [world units]: its box has an eighth of its largest span to spare
// each side (engine/surface_model.cpp), so the span is 0.8 of the box's largest side.
constexpr double kClosedPieceHalf = 0.8;

constexpr double kPatchHalf = 3.0;
// How far from the box's centre a point may be drawn, in its half-size (profile_drawing.h says why).
constexpr double kMaxDrawn = kMaxDrawnDistance;

std::shared_ptr<const SurfaceModel> shape_of(const Surface& surface) {
  return surface_model_of(surface);
}

// The camera's least framing radius when it follows one body [length]: 2.5 features, at least a
// third of the box's half-size.
double framing_radius(const SurfaceModel& shape) {
  return std::clamp(2.5 * shape.feature, 0.35 * shape.length, shape.length);
}

bool in_box(const SurfaceBounds& box, const Vec3& X) {
  for (int k = 0; k < 3; ++k) {
    const double margin = 1e-9 * (box[k][1] - box[k][0]);
    if (!(X[k] >= box[k][0] - margin && X[k] <= box[k][1] + margin)) return false;
  }
  return true;
}

// The grid's spacing: 1, 2 or 5 times a power of ten, about a quarter of the box's half-size.
double grid_step(const SurfaceModel& shape) {
  const double target = shape.length / 4.0, decade = std::pow(10.0, std::floor(std::log10(target)));
  for (const double m : {1.0, 2.0, 5.0})
    if (m * decade >= 0.75 * target) return m * decade;
  return 10.0 * decade;
}

// The level curves of a function over the mesh's triangles: each crossing of a multiple of `step`
// a segment between the two crossed edges' points, found along each edge by `crossing` (from the
// values at its ends).
template <class Value, class Crossing>
void add_level_curves(std::vector<Vertex>& lines, const ImplicitMesh& mesh, const SurfaceModel& shape,
                      Value value, Crossing crossing, double step, const glm::vec4& color) {
  const double l = shape.length;
  const auto world = [&](const Vec3& X) {
    const Vec3 w = (X - shape.centre) / l;
    return glm::dvec3(w.x(), w.y(), w.z());
  };
  for (const auto& t : mesh.triangles) {
    const double v[3] = {value(t[0]), value(t[1]), value(t[2])};
    const double lo = std::min({v[0], v[1], v[2]}), hi = std::max({v[0], v[1], v[2]});
    if (!(hi - lo < 64.0 * step)) continue;  // a triangle across many levels is left bare (or NaN)
    for (double level = std::ceil(lo / step) * step; level < hi; level += step) {
      glm::dvec3 ends[2];
      int found = 0;
      for (int e = 0; e < 3 && found < 2; ++e) {
        const int a = e, b = (e + 1) % 3;
        if ((v[a] < level) == (v[b] < level)) continue;
        ends[found++] = world(crossing(t[a], t[b], v[a], v[b], level));
      }
      if (found == 2) add_segment(lines, ends[0], ends[1], color);
    }
  }
}

// The point of the edge from a to b where a linear function takes `level`.
Vec3 linear_crossing(const ImplicitMesh& mesh, std::uint32_t a, std::uint32_t b, double va, double vb,
                     double level) {
  const double s = (level - va) / (vb - va);
  return mesh.points[a] + s * (mesh.points[b] - mesh.points[a]);
}

// Where K changes sign along the edge from a to b: bisected kKBisections times on the chord pushed
// onto the surface (K is far from linear across a cube where it changes fast; a straight guess
// draws the K = 0 curve as a coastline).
constexpr int kKBisections = 10;
Vec3 zero_curvature_crossing(const SurfaceModel& shape, const ImplicitMesh& mesh, std::uint32_t a,
                             std::uint32_t b) {
  double lo = 0.0, hi = 1.0;
  const bool positive_at_a = mesh.K[a] > 0.0;
  const auto point = [&](double s) -> Vec3 {
    return project_onto_surface(*shape.implicit, mesh.points[a] + s * (mesh.points[b] - mesh.points[a]));
  };
  for (int i = 0; i < kKBisections; ++i) {
    const double m = 0.5 * (lo + hi);
    const double K = bordered_hessian_curvature(shape.implicit->at(point(m)));
    if (!std::isfinite(K)) break;
    ((K > 0.0) == positive_at_a ? lo : hi) = m;
  }
  return mesh.points[a] + 0.5 * (lo + hi) * (mesh.points[b] - mesh.points[a]);
}

// Where F changes sign along the segment from the eye to a point of the surface before it (32 samples
// short of the last 2%), at a crossing within the box (beyond it nothing is drawn to hide it).
bool occluded(const SurfaceModel& shape, const glm::dvec3& eye_world, const glm::dvec3& at_world) {
  const auto embedded = [&](const glm::dvec3& w) -> Vec3 {
    return Vec3(w.x, w.y, w.z) * shape.length + shape.centre;
  };
  const double F0 = shape.value(embedded(eye_world));
  bool outside = F0 > 0.0;
  for (int i = 1; i <= 32; ++i) {
    const Vec3 X = embedded(glm::mix(eye_world, at_world, 0.98 * i / 32));
    const double F = shape.value(X);
    if (!std::isfinite(F) || (F > 0.0) == outside) continue;
    if (in_box(shape.box, X)) return true;
    outside = !outside;
  }
  return false;
}

// The mesh as lit triangles and its grid: level curves of x, y and z every grid_step, and the K = 0
// curves darker. Colours: K scaled so that the largest |K| drawn is the full colour.
StaticGeometry geometry_of(const SurfaceModel& shape, const ImplicitMesh& mesh) {
  StaticGeometry g;
  const double l = shape.length;
  double full = 0.0;
  for (const double K : mesh.K)
    if (std::isfinite(K)) full = std::max(full, std::abs(K));
  if (!(full > 0.0)) full = 1.0;
  const auto vertex = [&](std::uint32_t i) {
    const Vec3& X = mesh.points[i];
    const Vec3& n = mesh.normals[i];
    return LitVertex{
        to_float(glm::dvec3(X.x() - shape.centre.x(), X.y() - shape.centre.y(), X.z() - shape.centre.z()) /
                 l),
        to_float({n.x(), n.y(), n.z()}), curvature_color(mesh.K[i], full)};
  };
  g.surface.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (const std::uint32_t i : t) g.surface.push_back(vertex(i));
  const double step = grid_step(shape);
  const auto linear = [&](std::uint32_t a, std::uint32_t b, double va, double vb, double level) {
    return linear_crossing(mesh, a, b, va, vb, level);
  };
  for (int axis = 0; axis < 3; ++axis)
    add_level_curves(
        g.grid, mesh, shape, [&](std::uint32_t i) { return mesh.points[i][axis]; }, linear, step, kGridColor);
  // K = 0: the only multiple of 4 that K/full (in [−1, 1]) crosses; each edge's crossing found once.
  std::map<std::pair<std::uint32_t, std::uint32_t>, Vec3> zeros;
  const auto zero = [&](std::uint32_t a, std::uint32_t b, double, double, double) {
    const auto key = std::minmax(a, b);
    auto it = zeros.find(key);
    if (it == zeros.end())
      it = zeros.emplace(key, zero_curvature_crossing(shape, mesh, key.first, key.second)).first;
    return it->second;
  };
  add_level_curves(
      g.grid, mesh, shape, [&](std::uint32_t i) { return mesh.K[i] / full; }, zero, 4.0, kZeroCurvatureColor);
  return g;
}

class FormulaView final : public ViewModel {
 public:
  glm::dvec3 world_position(const Surface& surface, const Vec3& X) const override {
    const auto shape = shape_of(surface);
    const Vec3 w = (X - shape->centre) / shape->length;
    return {w.x(), w.y(), w.z()};
  }
  // Within the drawn box (surface.bounds, or the one the shape chose).
  bool on_view(const Surface& surface, const Vec3& X) const override {
    return in_box(shape_of(surface)->box, X);
  }
  std::string_view off_view_note(const Surface& surface, const Vec3& X) const override {
    return draws(surface, X) ? "body 1 is beyond the box drawn whole (surface.bounds)" : kBeyondDrawingNote;
  }
  bool draws(const Surface& surface, const Vec3& X) const override {
    const auto shape = shape_of(surface);
    return X.allFinite() && (X - shape->centre).norm() <= kMaxDrawn * shape->length;
  }

  // A main body beyond the box: a cube of the surface round it, its centre on a lattice of powers of
  // two no coarser than a quarter of its half-side (it moves in steps: a frame and the next share one).
  std::optional<PatchPlace> patch_at(const Snapshot& snapshot) const override {
    if (snapshot.bodies.empty()) return std::nullopt;
    const Vec3& X = snapshot.bodies.front().X;
    if (on_view(snapshot.surface, X) || !draws(snapshot.surface, X)) return std::nullopt;
    const double half = patch_half(surface_model(snapshot));
    const double quantum = std::exp2(std::floor(std::log2(half / 4)));
    return PatchPlace{std::round(X.x() / quantum) * quantum, std::round(X.y() / quantum) * quantum,
                      std::round(X.z() / quantum) * quantum};
  }
  bool paints_surface_at(const Snapshot& snapshot, const Vec3& X) const override {
    if (on_view(snapshot.surface, X)) return true;
    const std::optional<PatchPlace> at = patch_at(snapshot);
    return at && in_box(patch_box(surface_model(snapshot), *at), X);
  }
  StaticGeometry build_patch(const Surface& surface, PatchPlace at) const override {
    const auto shape = shape_of(surface);
    // As fine as the box: its cubes' side, over the patch's side.
    double longest = 0.0;
    for (const auto& side : shape->box) longest = std::max(longest, side[1] - side[0]);
    const int cells = static_cast<int>(std::ceil(2.0 * patch_half(*shape) / (longest / mesh_cells(*shape))));
    return geometry_of(*shape, mesh_implicit_surface(*shape, patch_box(*shape, at), cells));
  }
  glm::dvec3 normal(const Surface& surface, const glm::dvec3& w) const override {
    const auto shape = shape_of(surface);
    const Vec3 n = embedded_normal(*shape->implicit, Vec3(w.x, w.y, w.z) * shape->length + shape->centre);
    return n.allFinite() ? glm::dvec3(n.x(), n.y(), n.z()) : glm::dvec3(0.0, 0.0, 1.0);
  }
  StaticGeometry build_static(const Surface& surface) const override {
    const auto shape = shape_of(surface);
    return geometry_of(*shape, mesh_implicit_surface(*shape, shape->box, mesh_cells(*shape)));
  }

  glm::mat4 camera(const ViewOptions& view) const override { return orbit_camera(view, orbit_home()); }
  // What is behind the surface is drawn through it (from above, kLowestSpacePitch, the underside is).
  bool shows_through() const override { return true; }
  // A closed piece (an ellipsoid) has no up: seen from any side, as the sphere.
  double lowest_pitch(const Surface& surface) const override {
    return surface_model_of(surface)->closed ? -kPi / 2 : kLowestSpacePitch;
  }
  void add_bodies(FrameScene& scene, const Snapshot& snapshot, const ViewOptions& view) const override {
    ViewModel::add_bodies(scene, snapshot, view);
    add_ghosts(scene, *this, snapshot, view);
  }
  float depth_bias() const override { return kFormulaDepthBias; }
  bool hidden(const Surface& surface, const glm::dvec3& at, const glm::dvec3& eye) const override {
    return occluded(*shape_of(surface), eye, at);
  }
  double body_scale_length(const Surface& surface) const override { return shape_of(surface)->feature; }

  // Orbiting the bodies from their side (aim_in_space), in the box, framing at least 2.5 features.
  void aim(ViewOptions& view, const Snapshot& snapshot, const HudLayout& hud) const override {
    const SurfaceModel* shape = &surface_model(snapshot);
    const Vec3 n = embedded_normal(*shape->implicit, snapshot.bodies.front().X);
    aim_in_space(*this, view, snapshot, hud,
                 {n.allFinite() ? glm::dvec3(n.x(), n.y(), n.z()) : glm::dvec3(0.0, 0.0, 1.0),
                  framing_radius(*shape) / shape->length,
                  [&](const glm::dvec3& w) {
                    return in_box(shape->box, Vec3(w.x, w.y, w.z) * shape->length + shape->centre);
                  },
                  shape->closed ? kClosedPieceHalf : 0.0});
  }
  std::string grid_caption(const Snapshot& snapshot, const ViewOptions& view) const override {
    const SurfaceModel* shape = &surface_model(snapshot);
    return "Grid: level curves of x, y and z every " + caption_number("%g", grid_step(*shape)) +
           "; the K = 0 curves darker." +
           (patch_at(snapshot) ? " Round body 1, beyond the box drawn whole, a patch of the surface." : "") +
           (view.layers & kCurvature
                ? " Colour: the Gaussian curvature K, warm where K > 0, cool where K < 0, white where K = 0, "
                  "full at the largest |K| drawn."
                : "");
  }

 private:
  static double patch_half(const SurfaceModel& shape) {
    return std::min(kPatchHalf * framing_radius(shape), shape.length);
  }
  static SurfaceBounds patch_box(const SurfaceModel& shape, const PatchPlace& at) {
    const double half = patch_half(shape);
    SurfaceBounds box;
    for (int k = 0; k < 3; ++k) box[k] = {at[k] - half, at[k] + half};
    return box;
  }
};

}  // namespace

const ViewModel& formula_view() {
  static const FormulaView view;
  return view;
}

}  // namespace spinfold::render
