// H² as the upper sheet of the hyperboloid x₃² − x₁² − x₂² = R² in Minkowski space, seen by an
// orbiting camera from across its bowl.
#include <cmath>

#include "render/views/camera.h"
#include "render/views/drawing.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

// Overlays sit this far [radii] above the surface so that the depth test keeps them.
constexpr double kLift = 0.004;
constexpr float kHyperboloidDepthBias = 0.004f;
// Extent of the mesh and of the grid: geodesic distance from the vertex [radii].
constexpr double kHyperboloidExtent = 7.0;

constexpr double kMaxDrawnRadii = 1e4;

class HyperboloidView final : public ViewModel {
 public:
  // X/R moved down by one radius: the vertex at the origin.
  glm::dvec3 world_position(const Surface& surface, const Vec3& X) const override {
    const double R = surface.radius;
    return glm::dvec3(X.x() / R, X.y() / R, X.z() / R - 1.0);
  }
  // Bodies, trails and paths within 10⁴ radii of the vertex (r ≤ ~9.9 R): the GL draws in floats, and
  // a geodesic companion run off to r = 250 R (~1e108 radii) made lines that llvmpipe took minutes
  // over (issue 48's hunt).
  bool draws(const Surface& surface, const Vec3& X) const override {
    return X.allFinite() && X.norm() <= kMaxDrawnRadii * surface.radius;
  }
  // The Minkowski normal (−x₁, −x₂, x₃) at the world point w (x₃ = w_z + 1), normalised.
  glm::dvec3 normal(const Surface& /*surface*/, const glm::dvec3& w) const override {
    return glm::normalize(glm::dvec3(-w.x, -w.y, w.z + 1.0));
  }
  double lift() const override { return kLift; }

  // Rings of geodesic polar coordinates out to kHyperboloidExtent and H²'s polar grid.
  StaticGeometry build_static(const Surface& surface) const override {
    const SurfaceKind kind = surface.kind;
    StaticGeometry g;
    const Surface unit{kind, 1.0};
    const int rings = 56, slices = 64;
    const auto vertex = [&](double r, double phi) {
      const Vec3 X = chart_point(unit, r, phi).X;
      const glm::dvec3 w = world_position(unit, X);
      return LitVertex{to_float(w), to_float(glm::normalize(glm::dvec3(-X.x(), -X.y(), X.z())))};
    };
    for (int i = 0; i < rings; ++i)
      for (int j = 0; j < slices; ++j) {
        const double r0 = kHyperboloidExtent * i / rings, r1 = kHyperboloidExtent * (i + 1) / rings;
        const double p0 = 2 * kPi * j / slices, p1 = 2 * kPi * (j + 1) / slices;
        add_quad(g, vertex(r0, p0), vertex(r1, p0), vertex(r1, p1), vertex(r0, p1));
      }
    add_geodesic_polar_grid(g.grid, unit, *this, kHyperboloidExtent, 128, 64);
    return g;
  }

  // By default orbiting a point above the vertex.
  glm::mat4 camera(const ViewOptions& view) const override { return orbit_camera(view, orbit_home()); }
  glm::dvec3 orbit_home() const override { return glm::dvec3(0, 0, 1.6); }
  float depth_bias() const override { return kHyperboloidDepthBias; }
  // Inside the bowl, a fifth of a radius above the sheet (x₃ = w_z + 1 ≥ √(1 + x₁² + x₂²) + 0.2).
  bool on_lit_side(const glm::dvec3& eye) const override {
    return eye.z + 1.0 >= std::sqrt(1.0 + eye.x * eye.x + eye.y * eye.y) + 0.2;
  }
  // From across the bowl (the near side would see the surface edge-on), the vertex's
  // neighbourhood at least.
  void aim(ViewOptions& view, const Snapshot& snapshot, const HudLayout& hud) const override {
    aim_orbit(*this, view, snapshot, hud, 1.5, 0.55, kPi);
  }
  std::string grid_caption(const Snapshot& /*snapshot*/, const ViewOptions& /*view*/) const override {
    return "Grid: geodesic circles r = 0.5 R, 1 R, ... about the pole; radial geodesics every 30 degrees.";
  }
};

}  // namespace

const ViewModel& hyperboloid_view() {
  static const HyperboloidView view;
  return view;
}

}  // namespace spinfold::render
