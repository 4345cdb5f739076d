// Direct manipulation of a frame (the page's drag handles, issue 34 item 4): where the main body
// and the tip of its velocity arrow are in a frame's pixels, and what a drop at a pixel sets of the
// scene's initial state. The pick inverts the view's own projection (world_position and camera) by
// a search over the surface's chart, so every view, 2-D or 3-D, answers alike without an inverse
// map of its own, and a drop lands where the frame drew that point (to a tenth of a pixel).
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/readout.h"
#include "render/snapshot.h"
#include "render/view.h"

namespace spinfold::render {

// Why a frame of this surface has no drag handles, or nullopt. Where the surface has a chart (the
// polar one, a surface of revolution's (u, φ)) the search runs over it; where it has none (a surface
// given by a formula) the pixel's ray is cast against F in a view whose map from space is affine.
std::optional<std::string> drag_unsupported_reason(const Surface& surface);
// Whether the surface has no chart to search (the drop sets initial.X: point_at_pixel).
bool drags_by_point(const Surface& surface);

// Where the main body is and how it moves, in the scene's chart (engine/readout.h).
struct BodyPlace {
  double q = 0.0;                 // r [length] on S², H² and the plane; u where the curvature varies
  double phi = 0.0;               // [rad]
  double speed = 0.0;             // v [length/time]
  std::optional<double> heading;  // from E₁ towards E₂ [rad]; none where undefined (v > 0 at a pole)
  Vec3 X = Vec3::Zero();          // the ambient point [length]: the place on a surface with no chart
};

// The main body's place and motion in a read-out (coordinates.r holds u where the curvature varies).
BodyPlace body_place(const Readout& readout);

// The arrow: from the body's centre kArrowBasePixels, then arrow_pixels_per_speed per unit of speed,
// so that a body at rest still has an arrow to take hold of.
inline constexpr double kArrowBasePixels = 16.0;
// A quarter of the frame's shorter side per R/time (R: the view's body_scale_length): the presets'
// speed of 0.5 R/time draws an arrow an eighth of the frame long [pixels per length/time].
double arrow_pixels_per_speed(const ViewOptions& view, const Surface& surface);

struct DragHandles {
  glm::dvec2 body;                  // the main body's centre [pixels from the frame's top left]
  std::optional<glm::dvec2> arrow;  // the tip of its velocity arrow; none where the heading is
                                    // undefined or the view draws the direction as a point
};
// The handles of the main body in the frame `view` (resolved: its camera placed as the frame's);
// nullopt when the frame does not show the body there (off the view, behind the camera, or in 3-D
// behind a nearer part of the surface, as the sphere view's faint ghost of a body on its far side).
std::optional<DragHandles> drag_handles(const Snapshot& snapshot, const ViewOptions& view,
                                        const BodyPlace& body);

// The place (q, φ) the frame draws at `pixel`: the point nearest the camera whose image is within
// 0.05 pixel of it (of several at one point, as the tractricoid wraps H², the one nearest `near`);
// nullopt off the surface drawn. `near` seeds the search (the main body's
// place: a drop is usually close to where the drag began). φ in (−π, π], q in the chart's range.
std::optional<std::pair<double, double>> place_at_pixel(const Snapshot& snapshot, const ViewOptions& view,
                                                        glm::dvec2 pixel, const BodyPlace& near);

// On a surface with no chart (drags_by_point): the point of F = 0 the frame draws at `pixel`, the
// nearest the camera along the pixel's ray within the drawn box or the patch round `near`, brought
// onto F = 0 by Newton; nullopt off the surface drawn or where the view's map is not affine.
std::optional<Vec3> point_at_pixel(const Snapshot& snapshot, const ViewOptions& view, glm::dvec2 pixel,
                                   const BodyPlace& near);

// The velocity (speed, heading) whose arrow from `body` ends at `tip`: the inverse of drag_handles'
// arrow. nullopt where the view draws the tangent plane as a line (the sphere's limb).
std::optional<std::pair<double, double>> velocity_at_pixel(const Snapshot& snapshot, const ViewOptions& view,
                                                           glm::dvec2 tip, const BodyPlace& body);

// The scene fields a drop sets, named as the scene format names them ("r" or "u", "phi"; "speed",
// "heading"; "spin"), in that order.
using InitialFields = std::vector<std::pair<std::string_view, double>>;
// The place's fields alone ("r" or "u", "phi").
InitialFields place_fields(const Surface& surface, double q, double phi);
// The body's place as the scene gives it: ("r" or "u", "phi"), or on a surface with no chart
// ("X.0", "X.1", "X.2").
InitialFields place_fields(const Surface& surface, const BodyPlace& body);

// What a drop keeps of the run's start however the scene gave it (φ̇ and α̇ would give another
// speed and spin at another place): its spin s, and, for a dropped body, its speed and heading.
struct StartMotion {
  double spin = 0.0;
  std::optional<double> speed, heading;  // none where the start's heading is undefined (at a pole)
};
StartMotion start_motion(const Readout& start);
// A dropped body: the run starts at (q, φ) with the start's speed, heading and spin.
InitialFields body_drop_fields(const Surface& surface, double q, double phi, const StartMotion& start);
// The same on a surface with no chart: at X ("X.0", "X.1", "X.2": the scene's initial.X).
InitialFields point_drop_fields(const Vec3& X, const StartMotion& start);
// What a drop of the body at `pixel` sets, searching the surface's chart (place_at_pixel) or, with
// none, its F (point_at_pixel); nullopt where the frame shows no part of the surface there.
std::optional<InitialFields> body_drop_at_pixel(const Snapshot& snapshot, const ViewOptions& view,
                                                glm::dvec2 pixel, const BodyPlace& near,
                                                const StartMotion& start);
// A dropped arrow: the run starts from the body's place now with the velocity drawn and the
// start's spin. At a pole or an axis point, where the engine takes only heading 0 or π with a
// speed (E₂ is undefined there), the heading is turned into φ, whose E₁ then points the velocity's way.
InitialFields arrow_drop_fields(const Surface& surface, const BodyPlace& body, double speed, double heading,
                                const StartMotion& start);

// What a drop changes, in the words of the label beside the pointer (4 significant digits): the
// place for a body ("r = 1.234, phi = 0.5"), the velocity for an arrow ("speed = 0.75, heading =
// 90.0°": degrees, as the physics panel shows the heading).
std::string drop_text(const InitialFields& fields, bool arrow);
// The same in plain words for a class (the `plain` layer, simple mode), no coordinate names: "start
// here, 1.23 from the pole" (only where the place is a distance r from the pole; elsewhere "start
// here"), "start at speed 0.75, 90° from outwards" (the heading measured from the way out).
std::string drop_plain_text(const InitialFields& fields, bool arrow);

}  // namespace spinfold::render
