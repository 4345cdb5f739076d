// A surface of revolution whose curvature varies (torus, spheroid, bump, catenoid) in space, drawn
// from its profile (engine/revolution.h): meridians and parallels as its grid, the K = 0 parallels
// marked, the curvature layer's colours at the vertices. World units are X/ℓ with ℓ the picture's
// length (ProfilePicture), so that every shape fits the same camera.
#include "engine/revolution.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/surface_geodesics.h"
#include "render/views/camera.h"
#include "render/views/drawing.h"
#include "render/views/profile_drawing.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

// Overlays lie on the true surface; the mesh's flat faces cut inside it on convex parts and outside
// it by less than its sagitta (~1e-3 world units) on saddle parts, which this bias (a fraction of the
// distance to the camera, as the sphere's) covers.
constexpr float kRevolutionDepthBias = 0.01f;
// The mesh: rings along the profile, slices round the axis.
constexpr int kRings = 48, kSlices = 72;
// The patch round a main body beyond the drawn piece: quads along u and round the axis, and its
// half-size in arc length, in units of the camera's least framing radius (aim's): it fills the frame.
constexpr int kPatchQuads = 32;
constexpr double kPatchHalf = 3.0;
// The most parallels or meridians a patch draws each way (its step halves until one is no wider
// than a feature: about 2 × kPatchHalf × 2.5 of them, more only where the feature is uneven).
constexpr double kMaxPatchLines = 4.0 * kPatchQuads;

// The camera's least framing radius when it follows one body [length]: 2.5 features, at least a
// third of the picture's unit (aim).
double framing_radius(const ProfilePicture& picture) {
  return std::clamp(2.5 * picture.feature, 0.35 * picture.length, picture.length);
}

// The patch round u: its half-extents in u and φ (an arc of kPatchHalf framing radii each way, φ at
// most the whole turn), and the spacing of its grid: parallels and meridians at whole fractions
// 1/2ᵏ of the piece's steps (grid_step, 30°), the largest no wider than a feature along the surface.
struct PatchShape {
  double du = 0, dphi = 0, step_u = 0, step_phi = 0;
};
PatchShape patch_shape(const ProfileShape& shape, double u) {
  const ProfilePoint p = shape.entry->profile(shape.surface, u);
  const double f = std::hypot(p.rho_u, p.z_u), half = kPatchHalf * framing_radius(shape.picture);
  const double feature = shape.picture.feature;
  const auto halved = [&](double step, double arc_per_unit) {  // step/2ᵏ with arc ≤ feature
    for (int k = 0; k < 64 && step * arc_per_unit > feature; ++k) step /= 2.0;
    return step;
  };
  return {half / f, std::min(kPi, half / p.rho), halved(shape.picture.grid_step, f), halved(kPi / 6, p.rho)};
}

// Whether the segment from the eye to a point of the surface crosses the surface as drawn before it:
// F changes sign along it, sampled at 32 points short of the last 2% (the point itself), at a
// crossing on the drawn piece (beyond it, on an unbounded surface, nothing is drawn to hide it).
bool occluded(const Surface& surface, const glm::dvec3& eye_world, const glm::dvec3& at_world) {
  const ProfileShape shape = profile_shape(surface);
  const double l = shape.picture.length;
  const auto embedded = [&](const glm::dvec3& w) { return Vec3(w.x * l, w.y * l, w.z * l); };
  const auto F = [&](const glm::dvec3& w) { return shape.entry->implicit(shape.surface, embedded(w)).F; };
  bool outside = F(eye_world) > 0.0;
  for (int i = 1; i <= 32; ++i) {
    const glm::dvec3 w = glm::mix(eye_world, at_world, 0.98 * i / 32);
    if ((F(w) > 0.0) == outside) continue;
    if (on_drawn_piece(surface, embedded(w))) return true;
    outside = !outside;
  }
  return false;
}

class RevolutionView final : public ViewModel {
 public:
  glm::dvec3 world_position(const Surface& surface, const Vec3& X) const override {
    return glm::dvec3(X.x(), X.y(), X.z()) / profile_shape(surface).picture.length;
  }
  // Within the drawn piece (the bump's plane to 4w, the catenoid to |z| = 2c).
  bool on_view(const Surface& surface, const Vec3& X) const override { return on_drawn_piece(surface, X); }
  std::string_view off_view_note(const Surface& surface, const Vec3& X) const override {
    return off_drawn_piece_note(surface, X);
  }
  // Within the drawing range (within_drawing_range): beyond it, floats cannot place a vertex.
  bool draws(const Surface& surface, const Vec3& X) const override {
    return within_drawing_range(surface, X);
  }

  // A main body beyond the drawn piece: a patch of the surface round it, its centre on a lattice of
  // powers of two no coarser than a quarter of its half-extents (it moves in steps: a frame and the
  // next share one).
  std::optional<PatchPlace> patch_at(const Snapshot& snapshot) const override {
    if (snapshot.bodies.empty() || on_view(snapshot.surface, snapshot.bodies.front().X)) return std::nullopt;
    const Vec3& X = snapshot.bodies.front().X;
    if (!within_drawing_range(snapshot.surface, X)) return std::nullopt;  // the note says so
    const ProfileShape shape = profile_shape(snapshot.surface);
    const double u = shape.entry->u_of(shape.surface, X), phi = std::atan2(X.y(), X.x());
    const PatchShape patch = patch_shape(shape, u);
    const auto snapped = [](double v, double extent) {
      const double quantum = std::exp2(std::floor(std::log2(extent / 4)));
      return std::round(v / quantum) * quantum;
    };
    return PatchPlace{snapped(u, patch.du), snapped(phi, patch.dphi), 0.0};
  }
  bool paints_surface_at(const Snapshot& snapshot, const Vec3& X) const override {
    if (on_view(snapshot.surface, X)) return true;
    const std::optional<PatchPlace> at = patch_at(snapshot);
    if (!at) return false;
    const ProfileShape shape = profile_shape(snapshot.surface);
    const PatchShape patch = patch_shape(shape, (*at)[0]);
    const double u = shape.entry->u_of(shape.surface, X);
    const double dphi = std::remainder(std::atan2(X.y(), X.x()) - (*at)[1], 2.0 * kPi);
    return std::abs(u - (*at)[0]) <= patch.du && std::abs(dphi) <= patch.dphi;
  }
  // Lit and tinted as the piece (the same full scale of |K|), with its own parallels and meridians;
  // never over the piece (its range in u stops at the piece's end).
  StaticGeometry build_patch(const Surface& surface, PatchPlace at) const override {
    const ProfileShape shape = profile_shape(surface);
    const double l = shape.picture.length, full = largest_curvature(shape, kRings);
    const PatchShape patch = patch_shape(shape, at[0]);
    double lo = at[0] - patch.du, hi = at[0] + patch.du;
    if (at[0] >= shape.picture.u_max) lo = std::max(lo, shape.picture.u_max);
    if (at[0] <= shape.picture.u_min) hi = std::min(hi, shape.picture.u_min);
    const double phi0 = at[1] - patch.dphi, phi1 = at[1] + patch.dphi;
    const auto u_of = [&](int i) { return lo + (hi - lo) * i / kPatchQuads; };
    const auto phi_of = [&](int j) { return phi0 + (phi1 - phi0) * j / kPatchQuads; };
    StaticGeometry g;
    const auto vertex = [&](double u, double phi) {
      const RevolutionFrame f = revolution_frame(shape.surface, u, phi);
      return LitVertex{to_float(glm::dvec3(f.X.x(), f.X.y(), f.X.z()) / l),
                       to_float({f.n.x(), f.n.y(), f.n.z()}),
                       curvature_color(shape.entry->profile(shape.surface, u).K, full)};
    };
    for (int i = 0; i < kPatchQuads; ++i)
      for (int j = 0; j < kPatchQuads; ++j)
        add_quad(g, vertex(u_of(i), phi_of(j)), vertex(u_of(i + 1), phi_of(j)),
                 vertex(u_of(i + 1), phi_of(j + 1)), vertex(u_of(i), phi_of(j + 1)));
    // The grid's lines counted, never stepped (a step below the rounding of u would not move it),
    // and at most kMaxPatchLines each way: a patch whose lines would crowd closer is drawn bare.
    const auto lines = [](double from, double to, double step, auto&& draw) {
      const double first = std::ceil(from / step) * step, count = std::floor((to - first) / step) + 1.0;
      if (!(count <= kMaxPatchLines)) return;
      for (int k = 0; k < static_cast<int>(count); ++k) draw(first + k * step);
    };
    lines(lo, hi, patch.step_u, [&](double u) {
      std::vector<Vec3> pts;
      for (int j = 0; j <= kPatchQuads; ++j) pts.push_back(revolution_frame(shape.surface, u, phi_of(j)).X);
      add_polyline(g.grid, surface, *this, pts, kGridColor, false);
    });
    lines(phi0, phi1, patch.step_phi, [&](double phi) {
      std::vector<Vec3> pts;
      for (int i = 0; i <= kPatchQuads; ++i) pts.push_back(revolution_frame(shape.surface, u_of(i), phi).X);
      add_polyline(g.grid, surface, *this, pts, kGridColor, false);
    });
    return g;
  }
  glm::dvec3 normal(const Surface& surface, const glm::dvec3& w) const override {
    const ProfileShape shape = profile_shape(surface);
    const double l = shape.picture.length;
    const Vec3 n = embedded_normal(RevolutionImplicit(shape.surface), Vec3(w.x * l, w.y * l, w.z * l));
    return {n.x(), n.y(), n.z()};
  }

  // The profile swept round the axis; each vertex lit by the surface's normal and tinted by the
  // curvature layer's colour of K there, scaled so that the largest |K| drawn is the full colour.
  StaticGeometry build_static(const Surface& surface) const override {
    const ProfileShape shape = profile_shape(surface);
    const double l = shape.picture.length;
    StaticGeometry g;
    const auto u_of = [&](int i) {
      return shape.picture.u_min + (shape.picture.u_max - shape.picture.u_min) * i / kRings;
    };
    const double full = largest_curvature(shape, kRings);
    const auto vertex = [&](double u, double phi) {
      const RevolutionFrame f = revolution_frame(shape.surface, u, phi);
      const double K = shape.entry->profile(shape.surface, u).K;
      return LitVertex{to_float(glm::dvec3(f.X.x(), f.X.y(), f.X.z()) / l),
                       to_float({f.n.x(), f.n.y(), f.n.z()}), curvature_color(K, full)};
    };
    for (int i = 0; i < kRings; ++i)
      for (int j = 0; j < kSlices; ++j) {
        const double p0 = 2 * kPi * j / kSlices, p1 = 2 * kPi * (j + 1) / kSlices;
        add_quad(g, vertex(u_of(i), p0), vertex(u_of(i + 1), p0), vertex(u_of(i + 1), p1),
                 vertex(u_of(i), p1));
      }
    const auto parallel = [&](double u, const glm::vec4& color) {
      std::vector<Vec3> pts;
      for (int j = 0; j <= kSlices; ++j)
        pts.push_back(revolution_frame(shape.surface, u, 2 * kPi * j / kSlices).X);
      add_polyline(g.grid, surface, *this, pts, color, false);
    };
    for (const double u : grid_parallels(shape)) parallel(u, kGridColor);
    for (int k = 0; k < 12; ++k) {  // meridians every 30°
      std::vector<Vec3> pts;
      for (int i = 0; i <= kRings; ++i)
        pts.push_back(revolution_frame(shape.surface, u_of(i), 2 * kPi * k / 12).X);
      add_polyline(g.grid, surface, *this, pts, kGridColor, false);
    }
    for (const double u : zero_curvature_parallels(shape)) parallel(u, kZeroCurvatureColor);
    return g;
  }

  glm::mat4 camera(const ViewOptions& view) const override { return orbit_camera(view, orbit_home()); }
  // What is behind the surface is drawn through it (from above, kLowestSpacePitch, the underside is).
  bool shows_through() const override { return true; }
  double lowest_pitch(const Surface& /*surface*/) const override { return kLowestSpacePitch; }
  void add_bodies(FrameScene& scene, const Snapshot& snapshot, const ViewOptions& view) const override {
    ViewModel::add_bodies(scene, snapshot, view);
    add_ghosts(scene, *this, snapshot, view);
  }
  float depth_bias() const override { return kRevolutionDepthBias; }
  bool hidden(const Surface& surface, const glm::dvec3& at, const glm::dvec3& eye) const override {
    return occluded(surface, eye, at);
  }
  double body_scale_length(const Surface& surface) const override {
    return profile_shape(surface).picture.feature;
  }

  // Orbiting the bodies from their side (aim_in_space), on the drawn piece, framing at least 2.5
  // features.
  void aim(ViewOptions& view, const Snapshot& snapshot, const HudLayout& hud) const override {
    const Surface& surface = snapshot.surface;
    const Vec3 n3 =
        embedded_normal(RevolutionImplicit(profile_shape(surface).surface), snapshot.bodies.front().X);
    const ProfilePicture picture = profile_shape(surface).picture;
    const double l = picture.length;
    aim_in_space(*this, view, snapshot, hud,
                 {n3.allFinite() ? glm::dvec3(n3.x(), n3.y(), n3.z()) : glm::dvec3(0.0, 0.0, 1.0),
                  framing_radius(picture) / l,
                  [&](const glm::dvec3& w) { return on_view(surface, Vec3(w.x, w.y, w.z) * l); },
                  surface_model(snapshot).closed ? 1.0 : 0.0});
  }
  std::string grid_caption(const Snapshot& snapshot, const ViewOptions& view) const override {
    return std::string("Grid: meridians every 30 degrees and parallels; the K = 0 parallels darker.") +
           (patch_at(snapshot)
                ? " Round body 1, beyond the piece drawn whole, a patch of the surface with "
                  "meridians and parallels at halves of those steps, no wider than its feature."
                : "") +
           (view.layers & kCurvature
                ? " Colour: the Gaussian curvature K, warm where K > 0, cool where K < 0, "
                  "white where K = 0, full at the largest |K| drawn."
                : "");
  }
};

}  // namespace

const ViewModel& revolution_view() {
  static const RevolutionView view;
  return view;
}

}  // namespace spinfold::render
