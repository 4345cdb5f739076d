// The one interface a view implements: its projection, static geometry, camera, per-frame
// background, bodies and aiming. Each view is one file in render/views/ (sphere.cpp, disk.cpp, …)
// listed by one row of the view table (render/view_table.cpp); build_scene and aim_camera_at_body
// ask the view for what differs and never switch on ViewKind. No GL: plain draw lists.
#pragma once

#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>

#include "render/scene_builder.h"

namespace spinfold::render {

// What a figure (render/figure.h) marks lengths with: labels on the geodesic circles (the flat
// maps of H² and the sphere), a scale bar in lengths (plane, conformal), or nothing (3-D views).
enum class FigureScale { none, circle_labels, scale_bar };

// The centre and half-extents of a 2-D view's orthographic frame [world units].
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

// Defaults are those of a flat 2-D view that shows every point; a view overrides what it does
// differently. Implementations are stateless singletons (one const object per view).
class ViewModel {
 public:
  virtual ~ViewModel() = default;

  // ---- Projection
  // Where an embedded point X of `surface` lands in the view's world coordinates (world_position).
  virtual glm::dvec3 world_position(const Surface& surface, const Vec3& X) const = 0;
  // Whether the view shows X (false only off the tractricoid's strip and the revolution view's
  // drawn piece of an unbounded surface), and what the HUD says of a main body at X it does not show.
  virtual bool on_view(const Surface& /*surface*/, const Vec3& /*X*/) const { return true; }
  virtual std::string_view off_view_note(const Surface& /*surface*/, const Vec3& /*X*/) const {
    return "body 1 is off the view";
  }
  // Whether a body, trail or path point at X is drawn: where the view shows it, or anywhere in a
  // view whose world is ℝ³ itself (the revolution view: off its drawn piece the body, its trail and
  // the camera's aim go on, with the note, and only the surface's mesh is missing).
  virtual bool draws(const Surface& surface, const Vec3& X) const { return on_view(surface, X); }
  // Whether a frame of `snapshot` paints the surface itself at X (a drop there picks it; elsewhere
  // the pixel is background, however far the unbounded surface goes): where the view shows X, and in
  // the revolution view also the patch round a main body beyond the drawn piece.
  virtual bool paints_surface_at(const Snapshot& snapshot, const Vec3& X) const {
    return on_view(snapshot.surface, X);
  }
  // The surface's unit normal at a world point: overlays are lifted along it and arrowheads lie
  // across it. +z in the 2-D views.
  virtual glm::dvec3 normal(const Surface& /*surface*/, const glm::dvec3& /*w*/) const {
    return {0.0, 0.0, 1.0};
  }
  // How far overlays sit above the surface along normal() so that the depth test keeps them
  // [world units]; 0: on it.
  virtual double lift() const { return 0.0; }
  // Whether the map tears the segment between two world points (the chart's seam at φ = ±π, where
  // a path that goes on round the surface reappears at the other edge): such a segment is left out.
  virtual bool torn(const glm::dvec3& /*a*/, const glm::dvec3& /*b*/) const { return false; }

  // ---- Geometry that depends only on the surface (cached by static_geometry()).
  // Triangles of the surface and its grid, in world units; empty for a view whose background
  // follows the camera (drawn by add_background instead). Views of constant curvature draw the
  // unit surface of the kind; the revolution view draws the surface's own shape.
  virtual StaticGeometry build_static(const Surface& /*surface*/) const { return {}; }
  // Whether build_scene uses the cached static geometry at all (false: everything is drawn per
  // frame, as the conformal view's background depends on K, which no cache key holds).
  virtual bool uses_static() const { return true; }
  // Where the main body is off the piece build_static draws (an unbounded surface's), the frame adds
  // a patch of the surface round it: patch_at says where (equal places, one patch: it moves in
  // steps, and frames share it), build_patch builds it as build_static builds the piece.
  virtual std::optional<PatchPlace> patch_at(const Snapshot& /*snapshot*/) const { return std::nullopt; }
  virtual StaticGeometry build_patch(const Surface& /*surface*/, PatchPlace /*at*/) const { return {}; }

  // ---- Camera
  // The view-projection matrix of the frame.
  virtual glm::mat4 camera(const ViewOptions& view) const = 0;
  // The point a 3-D view's camera orbits when ViewOptions::target is unset [world units].
  virtual glm::dvec3 orbit_home() const { return glm::dvec3(0.0); }
  // FrameScene::depth_bias: a fraction of the distance to the camera.
  virtual float depth_bias() const { return 0.0f; }
  // Whether a point in the frame is still out of sight from a camera at `eye` (beyond the
  // sphere's limb): aiming counts it as missed.
  virtual bool hidden(const Surface& /*surface*/, const glm::dvec3& /*at*/, const glm::dvec3& /*eye*/) const {
    return false;
  }
  // The lowest elevation its aimed camera takes on this surface [rad]: a surface drawn upright (a
  // torus, a bump, a graph) is never seen from under it (kLowestSpacePitch, render/views/camera.h);
  // one that has no up (the sphere, a closed formula surface) is seen from any side.
  virtual double lowest_pitch(const Surface& /*surface*/) const { return -std::numbers::pi / 2; }
  // Whether what is behind the surface (a body, a trail's stretch) is drawn faintly through it
  // (FrameScene::ghost_fills, ghost_lines): a surface in space seen from above, whose camera never
  // looks from under it (kLowestSpacePitch), shows a body on its underside so.
  virtual bool shows_through() const { return false; }
  // Whether a camera at `eye` [world units] sees the surface from the side it is drawn to be seen
  // from (the hyperboloid from inside its bowl: from under the sheet a frame is its dark underside
  // and no body). Aiming never picks a camera on the other side.
  virtual bool on_lit_side(const glm::dvec3& /*eye*/) const { return true; }
  // Places the camera to show the bodies and their trails clear of the HUD's and legend's boxes
  // (aim_camera_at_body; snapshot.bodies is not empty). Default: the view's fixed camera.
  virtual void aim(ViewOptions& /*view*/, const Snapshot& /*snapshot*/, const HudLayout& /*hud*/) const {}

  // ---- What a frame draws beyond the static geometry
  // The per-frame background: FrameScene's grid_lines, backdrop and colours (after the surface's
  // colour is chosen and the draw_surface/draw_grid flags are set).
  virtual void add_background(FrameScene& /*scene*/, const Surface& /*surface*/,
                              const ViewOptions& /*view*/) const {}
  // Trails' segments are kept only when both ends lie near this window (nullopt: all of them).
  virtual std::optional<Window2d> clip(const ViewOptions& /*view*/) const { return std::nullopt; }
  // The bodies' ellipses (kBody) and frame arrows (kFrame), all ellipses first. Default: each
  // body on the view drawn through world_position (add_body, add_frame_arrows; drawing.cpp).
  virtual void add_bodies(FrameScene& scene, const Snapshot& snapshot, const ViewOptions& view) const;
  // The length ViewOptions::scale is given in (body_scale_length).
  virtual double body_scale_length(const Surface& surface) const { return surface.radius; }
  // The scale a body is drawn at (its ellipse and arrows, and where aiming looks): drawn_scale, a
  // frame too large for the surface drawn smaller (render/scene_builder.h). A view that draws the
  // frame to first order in a flat picture draws any size at `scale`.
  virtual double body_drawing_scale(const Surface& surface, const BodySnapshot& body, double scale) const;

  // ---- What a figure's caption says and marks (render/figure.cpp asks; it never switches on views)
  // The caption's sentence on what the grid shows ("" for none); called only with the grid layer.
  virtual std::string grid_caption(const Snapshot& /*snapshot*/, const ViewOptions& /*view*/) const {
    return "";
  }
  virtual FigureScale figure_scale() const { return FigureScale::none; }
};

}  // namespace spinfold::render
