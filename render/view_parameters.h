// The picture's vocabulary, named once: every parameter of a frame (its size, view, layers, the
// body's display scale, the camera, the trail's span) with its unit, allowed range, default and
// help, and the table of layers. The frame query parameters (server/frames.cpp), the recording
// body (server/routes_recordings.cpp), the CLI's render and record options (cli/view_options.cpp),
// the OpenAPI document and GET /api/v1/view-parameters all iterate these tables, so that a name,
// a range or a default is written here only. Plain data, no JSON.
//
// A row points at the member of ViewRequest it sets; the default is ViewRequest's own in-class
// default (as engine/scene_fields.h takes a scene field's from its struct), and the member's type
// says the parameter's: int a whole number, double a number, std::optional<double> a number with no
// default (its absence means something: "aimed at the body"), std::optional<ViewKind> one of the
// views, unsigned a list of layers.
#pragma once

#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "engine/number_rule.h"  // Range, NumberRule
#include "engine/surface.h"
#include "render/view.h"

namespace spinfold::render {

// How a sequence's 3-D camera (the live view, a recording: render/camera_follow.h) moves while the
// run plays. steady, the lesson's camera: it stays put while the main body is in the frame, clear of
// the boxes and in sight, and only then glides to the aim, all the way (the scene does not move
// under the student). follow: it glides toward the aim at every frame, keeping the body centred.
enum class CameraMotion { steady, follow };
inline constexpr std::string_view kCameraMotionNames[] = {"steady", "follow"};
std::optional<CameraMotion> parse_camera_motion(std::string_view name);

// What the view parameters ask for, before the surface is known.
struct ViewRequest {
  int width = 640;                   // [pixels]
  int height = 480;                  // [pixels]
  std::optional<ViewKind> view{};    // absent: the surface's own (default_view)
  unsigned layers = kDefaultLayers;  // Layer bits
  // [surface radii; lengths in the conformal view (body_scale_length)] the body's ellipse is the
  // image of scale·(unit circle) under e_A
  double scale = 0.25;
  std::optional<double> yaw{};       // [rad] camera azimuth (3-D views); absent: aimed at the body
  std::optional<double> pitch{};     // [rad] camera elevation (3-D views); absent: aimed at the body
  std::optional<double> distance{};  // [surface radii] (3-D views); absent: aimed at the body
  std::optional<double> trail{};     // [time] the trail's span before now; absent: the whole run
  CameraMotion motion = CameraMotion::steady;  // a sequence's camera while the run plays
  std::optional<double> shown_width{};         // [pixels] the width shown at; absent: as drawn
};

// The kinds of value a parameter holds (from the member's type).
enum class ParameterType {
  integer,      // a whole number
  number,       // a finite number
  enumeration,  // one of choices()
  list,         // comma-separated items, each one of choices() (empty items are ignored)
};

using ViewMember = std::variant<int ViewRequest::*, double ViewRequest::*,
                                std::optional<double> ViewRequest::*, std::optional<ViewKind> ViewRequest::*,
                                unsigned ViewRequest::*, CameraMotion ViewRequest::*>;

struct ViewParameter {
  std::string_view name;  // the query parameter, the recording body's key, the CLI's --NAME
  ViewMember member;      // what it sets (its type and default)
  std::string_view unit;  // numbers: "pixels", "rad", "radii" (surface radii), "time"; "" for none
                          // (scale: surface radii, or lengths in the conformal view, as its help says)
  Range range;            // numbers: the allowed values (a side's maximum: also Limits::max_image_side)
  std::string_view help;  // one line: what it does, and what its absence means
};

// ---- the tables --------------------------------------------------------------------------------

inline constexpr Range kImageSide{.min = 16.0, .max = kMaxImageSide};

inline constexpr ViewParameter kViewParameters[] = {
    {"width", &ViewRequest::width, "pixels", kImageSide, "image width"},
    {"height", &ViewRequest::height, "pixels", kImageSide, "image height"},
    {"view",
     &ViewRequest::view,
     "",
     {},
     "the picture (GET /api/v1/views lists each with the surfaces it shows); default: the surface's own"},
    {"layers",
     &ViewRequest::layers,
     "",
     {},
     "what is drawn: the shaded surface, its geodesic grid, the body's ellipse, the frame arrows, the "
     "trail, the text overlay, and (not by default) the action variables and frequencies in the text "
     "overlay"},
    {"scale",
     &ViewRequest::scale,
     "",
     {.min = 0.0, .min_open = true, .max = 10.0},
     "the body's ellipse: the image of this many surface radii (lengths in the conformal view) of the "
     "unit circle under e_A"},
    {"yaw",
     &ViewRequest::yaw,
     "rad",
     {.min = -100.0, .max = 100.0},
     "camera azimuth (3-D views); default: aimed at the body"},
    {"pitch",
     &ViewRequest::pitch,
     "rad",
     {.min = -1.55, .max = 1.55},
     "camera elevation (3-D views); default: aimed at the body"},
    {"distance",
     &ViewRequest::distance,
     "radii",
     {.min = 1.2, .max = 100.0},
     "camera distance from the centre in surface radii (3-D views); default: aimed at the body"},
    {"trail", &ViewRequest::trail, "time", kNonNegative,
     "the trail's span: the path over this much simulated time before now; default: the whole run "
     "(sampled every 0.01, the spacing doubling past 8192 samples)"},
    {"motion",
     &ViewRequest::motion,
     "",
     {},
     "how the live view's and a recording's 3-D camera moves while the run plays: steady stays put while "
     "the main body is in the frame and in sight, then glides to it; follow keeps the body centred"},
    {"shown", &ViewRequest::shown_width, "pixels", kImageSide,
     "the width the picture is shown at (a live picture drawn smaller for speed and scaled up): the text "
     "overlay is sized for it, the same on the screen as at full size, or the compact overlay where text "
     "that small cannot be drawn; default: the image width"},
};

struct LayerInfo {
  std::string_view name;  // as in the layers list
  Layer bit;
  bool on_by_default;     // in kDefaultLayers
  std::string_view help;  // one line
};

// The one table of layers, in the order the lists name them.
inline constexpr LayerInfo kLayerTable[] = {
    {"surface", kSurface, true, "the shaded surface"},
    {"grid", kGrid, true, "the geodesic grid"},
    {"body", kBody, true, "the body's deformed-frame ellipse (and each companion's)"},
    {"frame", kFrame, true, "the frame arrows e₁, e₂"},
    {"trail", kTrail, true, "the path on the surface"},
    {"hud", kHud, true, "the text overlay: scene, time, energy, invariants"},
    {"actions", kActions, false, "the action variables and frequencies, added to the text overlay"},
    {"curvature", kCurvature, false,
     "the Gaussian curvature K as the surface's colour: warm where K > 0, cool where K < 0, white where K = "
     "0"},
    {"bending", kBending, true,
     "the main body's trail coloured by which way it bends: orange where it turns left, green where it turns "
     "right (seen from outside the surface), grey where it runs straight; deeper the more it bends"},
    {"drift", kDrift, true,
     "where a fast spinner gyrates on a surface of revolution, an arrow at each body along the parallel its "
     "guiding centre drifts along (the grad-B drift of B = K s), reversed with the spin"},
    {"plain", kPlain, false,
     "the text overlay in plain words for a class: the time, the surface (and its curvature at the body) "
     "and the spin, without the energy error, integrator, inertia and det L"},
};

constexpr unsigned default_layers() {
  unsigned mask = 0;
  for (const LayerInfo& l : kLayerTable)
    if (l.on_by_default) mask |= l.bit;
  return mask;
}
static_assert(default_layers() == kDefaultLayers, "kDefaultLayers is the table's layers on by default");

// ---- reading the tables --------------------------------------------------------------------------

std::span<const ViewParameter> view_parameters();
// The row named `name`; std::logic_error when there is none (a programming error).
const ViewParameter& view_parameter(std::string_view name);
ParameterType parameter_type(const ViewParameter& p);
// enumeration: the view names (the view table's order) or the camera's motions; list: the layer
// names; else empty.
std::vector<std::string_view> choices(const ViewParameter& p);
// The allowed values of a number, a side at most `max_image_side`.
Range allowed_range(const ViewParameter& p, int max_image_side = kMaxImageSide);
// A number's rule (engine/number_rule.h): whole or not, its allowed range, its unit.
NumberRule number_rule(const ViewParameter& p, int max_image_side = kMaxImageSide);
// The default as the API writes it: a number (integer, number), a text (the default layers,
// "surface,grid,body,frame,trail,hud"), or none (its absence means what the help says).
std::optional<std::variant<double, std::string>> default_value(const ViewParameter& p);
// The layers on by default, joined by commas.
std::string default_layer_list();

// Why a value is refused, in the words of every reader (query, body, CLI): "must be a whole number
// from 16 to 4096 [pixels]", "must be a number in (0, 10]", "must be sphere, disk,
// … or conformal", "'sparkles' is not one of surface, grid, …, actions".
std::string expectation(const ViewParameter& p, int max_image_side = kMaxImageSide);

// A value as given: a number (JSON), or a text (a query value, a CLI option, a JSON string).
using GivenValue = std::variant<double, std::string>;

// Sets `p` in `request` from a value; nullopt when set, else the reason it is refused (the caller
// names the field and the value). A text for a number is read as one (all of it, finite).
std::optional<std::string> set_parameter(ViewRequest& request, const ViewParameter& p,
                                         const GivenValue& value, int max_image_side = kMaxImageSide);

// The request's value of `p` as the API writes it (the inverse of set_parameter; nullopt when absent).
std::optional<GivenValue> parameter_value(const ViewRequest& request, const ViewParameter& p);

// The layer list of a mask ("surface,grid,body"), in the table's order.
std::string layer_list(unsigned layers);

// ---- resolving a request: the one place -------------------------------------------------------
// A picture request becomes a ViewOptions here and nowhere else: the server's frames and figures,
// its recordings (record/clip.cpp), the CLI's render and record, the CLI's figures and Python's
// render. The view is the request's (the surface's own when none); the body's scale is given in
// the view's length (body_scale_length); the camera is aimed at the bodies and each part the request
// gives (yaw, pitch, distance) replaces the aimed one — all three given replace all three, the point
// the camera orbits staying the one it was aimed at.

struct Snapshot;

// The view cannot show the surface: the parameter ("view"), its value and the reason.
struct ViewRefused : std::invalid_argument {
  ViewRefused(std::string name, std::string given, const std::string& reason)
      : std::invalid_argument(reason), parameter(std::move(name)), value(std::move(given)) {}
  std::string parameter, value;
};

// Why the request's view cannot show the surface, or nullopt.
std::optional<std::string> view_refusal(const ViewRequest& request, SurfaceKind surface);

// Everything the request sets but the camera: the view, the size, the layers, the body's scale [the
// view's length]. ViewRefused when the view cannot show the surface.
ViewOptions view_options(const ViewRequest& request, const Surface& surface);

// What the picture is: a raster frame (the camera keeps the bodies clear of the HUD box) or a vector
// figure (its caption is below the picture: no HUD box to keep clear of).
enum class Picture { frame, figure };

// The camera: aimed at the snapshot's bodies, then the parts the request gives replace the aimed ones;
// a camera they put on the surface's dark side (ViewModel::on_lit_side) is tilted up until it is not,
// or, where no tilt does it, is the aimed one.
void place_camera(ViewOptions& view, const ViewRequest& request, const Snapshot& snapshot,
                  Picture picture = Picture::frame);

// Both: the picture the request asks for of the snapshot (view_options, then place_camera).
ViewOptions resolve_view(const ViewRequest& request, const Snapshot& snapshot,
                         Picture picture = Picture::frame);

}  // namespace spinfold::render
