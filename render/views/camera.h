// The cameras the views share and the search that aims them: an orbiting perspective camera (the
// 3-D views), an orthographic window (the 2-D views), and what a camera must show of the bodies
// and how badly a candidate shows it (aim_camera_at_body).
#pragma once

#include <functional>
#include <initializer_list>
#include <limits>
#include <vector>

#include "render/scene_builder.h"
#include "render/views/view_model.h"

namespace spinfold::render {

// The 3-D views' vertical field of view [degrees].
inline constexpr double kFovY = 35.0;

// Perspective, orbiting view.target (else `default_target`) at view.distance from the direction
// (yaw, pitch), z up [world units].
glm::mat4 orbit_camera(const ViewOptions& view, const glm::dvec3& default_target);

// The window centred on `centre` whose shorter side spans 2·half [world units], the longer one
// stretched to the frame's aspect ratio.
Window2d window_around(const ViewOptions& view, const glm::dvec2& centre, double half);
// view.target's (x, y), or `otherwise` when the view has none.
glm::dvec2 target_or(const ViewOptions& view, const glm::dvec2& otherwise);
// Where a perspective camera is: the point its projection sends to w = 0 [world units].
glm::dvec3 eye_of(const glm::mat4& view_projection);
// The orthographic projection of a window (z from −1 to 1).
glm::mat4 window_camera(const Window2d& w);

// What a camera must show [world units] and how much each counts: the main body's centre above
// all (1000), each companion's (50), each body's outline (5 a point) and its trail (10 in all).
struct Sight {
  glm::dvec3 at;
  double weight;
};
// The sights of a snapshot in a view, the main body's first when the view draws it; with
// `recent_only`, only each trail's last stretch (within 3 radii, intrinsic, of its body).
std::vector<Sight> sights(const ViewModel& model, const Snapshot& snapshot, const ViewOptions& view,
                          bool recent_only);
// The HUD's and legend's boxes a frame of this snapshot will have (as build_scene lays them out).
HudLayout hud_boxes(const Snapshot& snapshot, const ViewOptions& view);
// Whether the camera shows the main body's centre in the frame, clear of the HUD's and legend's
// boxes and in sight (what aiming weighs most); true where the view does not draw it. With
// `behind_too`, a centre behind the surface counts as shown where the view draws it through.
bool shows_main_body(const ViewOptions& view, const Snapshot& snapshot, bool behind_too = false);
// The ghosts of a view that shows through (ViewModel::shows_through): each body behind the surface
// and every trail, at kGhostAlpha, into scene.ghost_fills and ghost_lines (drawn under the rest,
// without the depth test: the stretches in sight are drawn over their ghosts).
inline constexpr float kGhostAlpha = 0.45f;
void add_ghosts(FrameScene& scene, const ViewModel& model, const Snapshot& snapshot, const ViewOptions& view);
// How badly a camera shows the sights: the weight of those hidden (ViewModel::hidden) or behind
// the camera, out of the frame (less a margin) or under the HUD's or legend's box (grown by the
// margin). The sum stops once it reaches `enough` (a camera search's best so far: a camera that bad
// cannot win), so the ray casts of the rest are not paid for.
double badness(const ViewModel& model, const Surface& surface, const ViewOptions& view,
               const std::vector<Sight>& points, const HudLayout& hud,
               double enough = std::numeric_limits<double>::infinity());
// Tries the camera turned by each of a fixed list of (Δyaw, Δpitch) and drawn back by each factor
// of `pulls`, in this order, and keeps the first that shows the sights best; returns its badness.
double clear_the_boxes(const ViewModel& model, const Surface& surface, ViewOptions& view,
                       const std::vector<Sight>& points, const HudLayout& hud,
                       std::initializer_list<double> pulls);

// When turning and drawing back leave the sights boxed (a small frame whose HUD covers its
// centre, where an orbit puts its target): slides the target across the screen plane by a
// quarter or a third of the frame each way, the first of the list of offsets that shows the
// sights best; the camera's direction and distance stay. Returns the badness it ends with.
double slide_clear_of_boxes(const ViewModel& model, const Surface& surface, ViewOptions& view,
                            const std::vector<Sight>& points, const HudLayout& hud);

// The orbit of a surface that stretches out of a unit ball (hyperboloid, tractricoid): orbit the
// centre of the bounding box of the bodies and their recent trails, at the distance at which a
// ball round all of them (at least `min_radius` [world units]) fills 85% of the narrower field of
// view, at `pitch` [rad], from the side of the axis turned by `yaw_turn` [rad] from the centre's,
// then clear the boxes.
void aim_orbit(const ViewModel& model, ViewOptions& view, const Snapshot& snapshot, const HudLayout& hud,
               double min_radius, double pitch, double yaw_turn);
// A window centred on the bounding box of the bodies' positions (plane, conformal).
void aim_at_bodies_centre(const ViewModel& model, ViewOptions& view, const Snapshot& snapshot);

// A 2-D view's window: its own (shorter half-side `half`) about view.target, else `home`, view.zoom
// times smaller (a close-up) or larger (drawn back).
Window2d zoomed_window(const ViewOptions& view, const glm::dvec2& home, double half);
// The disk views' own window: the unit disk and a margin (the shorter half-side [world units]).
inline constexpr double kDiskWindowHalf = 1.08;
// The largest close-up considered [times the view's own window].
inline constexpr double kMaxCloseUp = 256.0;
// The disks' rims are polygons of this many sides (and their grid circles of half as many): in the
// largest close-up of a 757 px high frame a side strays from the circle by π²/2n² of the radius,
// ~0.4 pixel (~1.7 on the grid's). More sides cost every frame whose background is not cached.
inline constexpr int kRimSlices = 1024;
// Aims a 2-D view's window (shorter half-side `half`, about view.target or the origin):
// - a close-up where the map draws the main body less than a third of its size at the pole (near
//   the Poincaré disk's rim it shrinks lengths like e^{−r/R}): view.zoom becomes the largest power
//   of two up to that shrink's inverse (and kMaxCloseUp) whose window, about the centre of the
//   bodies and their recent trails (view.target), shows them all within the middle 60% of the
//   frame and clear of the boxes; the HUD then says the zoom (readout_lines), one line more than
//   `hud` holds;
// - otherwise the view's own window (view.zoom = 1), unless a sight is out of it or under a box:
//   then slid away from the boxes and drawn back (view.zoom < 1) until they are clear.
void aim_2d_window(const ViewModel& model, ViewOptions& view, const Snapshot& snapshot, const HudLayout& hud,
                   double half);

// The aiming of a view of a surface in space (revolution, formula): orbiting the centre of the bodies
// and their recent trails on the drawn piece at the distance that frames them (at least `radius`),
// from the best of: the main body's normal, and every 30° round z at five elevations, drawn back as
// far as 1.6×. The cost of a camera is its badness (a hidden or boxed main body 1000, each trail 10 in
// all) plus up to 4 for drawing back, up to 1.5 for looking at the main body obliquely and a little
// for an elevation far from 0.5 rad (a surface is read best from a little above): a near camera facing
// the body that shows most of its path wins over a far one that shows all of it edge-on. No camera
// is lower than the view's lowest_pitch. A closed piece (SpaceAim::whole) is framed whole.
// The lowest elevation a camera on a surface drawn upright takes [rad] (~9°, ViewModel::lowest_pitch):
// never from under it (a teacher's torus seen from below lost the class), so a body on the underside
// is drawn through the surface (ViewModel::shows_through).
inline constexpr double kLowestSpacePitch = 0.15;
struct SpaceAim {
  glm::dvec3 normal{0.0, 0.0, 1.0};                 // the surface's unit normal at the main body
  double radius = 1.0;                              // the least framing radius [world units]
  std::function<bool(const glm::dvec3&)> on_piece;  // whether a world point is on the drawn piece
  // A closed piece (a torus, a spheroid, an ellipsoid): the radius of the ball about the world
  // origin (the piece's centre) that holds it [world units], which the lesson's camera frames whole,
  // so that, steady, it rarely has to move; 0 where the piece is not closed.
  double whole = 0.0;
};
void aim_in_space(const ViewModel& model, ViewOptions& view, const Snapshot& snapshot, const HudLayout& hud,
                  const SpaceAim& aim);

}  // namespace spinfold::render
