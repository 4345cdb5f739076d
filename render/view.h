// What a frame shows and how: the view, the layers and the camera. Plain data, no GL.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "engine/surface.h"

namespace spinfold::render {

enum class ViewKind {
  sphere,       // the 3-D sphere, orbiting camera
  hyperboloid,  // the upper sheet of the hyperboloid model of H², orbiting camera
  disk,         // Poincaré disk (H²) or stereographic plane (S²), 2-D
  plane,        // the flat plane, 2-D
  klein,        // Beltrami–Klein disk (H²): geodesics are straight chords, 2-D
  halfplane,    // Poincaré upper half-plane (H²), 2-D, following the body
  tractricoid,  // Beltrami's pseudosphere in ℝ³ (a horocyclic strip of H² wrapped round its axis)
  conformal,    // every surface: stereographic (S²), identity (plane), Poincaré (H²), continuous in K, 2-D
  revolution,   // a surface of revolution whose curvature varies (torus, spheroid, bump, catenoid) in ℝ³
  chart,        // the same surfaces' chart (u, φ) unrolled flat, K as the background's colour, 2-D
  formula,      // a surface given by a formula (implicit F = 0 or a graph z = f(x, y)) in ℝ³
};

// The one table of views: the name the API, the CLI and the UI use, the surfaces each shows, and
// how the UI titles and explains it.
struct ViewInfo {
  std::string_view name;
  ViewKind kind;
  bool three_d;                  // an orbiting camera (else orthographic, 2-D)
  unsigned needs;                // what a surface must offer one of to be shown (offer_bit, engine/surface.h)
  std::string_view title;        // a short label for a menu
  std::string_view description;  // one line for a reader
};
std::span<const ViewInfo> views();
// The views' names in the table's order joined by `separator` ("sphere | disk | …" for a help text).
std::string joined_view_names(std::string_view separator);
const ViewInfo& view_info(ViewKind view);

// Layers, each on or off per frame; an unselected layer costs nothing.
enum Layer : unsigned {
  kSurface = 1u << 0,     // shaded surface
  kGrid = 1u << 1,        // geodesic grid
  kBody = 1u << 2,        // the deformed-frame ellipse
  kFrame = 1u << 3,       // the frame arrows e₁, e₂
  kTrail = 1u << 4,       // the path on the surface
  kHud = 1u << 5,         // text overlay (Dear ImGui)
  kActions = 1u << 6,     // the action variables and frequencies, added to the text overlay
  kCurvature = 1u << 7,   // the Gaussian curvature K as the surface's colour (warm > 0, cool < 0)
  kBending = 1u << 8,     // the main body's trail coloured by which way it bends (render/scene_builder.h)
  kDrift = 1u << 9,       // an arrow of a fast spinner's guiding-centre drift (engine/guiding_centre.h)
  kPlain = 1u << 10,      // the text overlay in plain words for a class (Snapshot::plain_lines)
  kDefaultLayers = 831u,  // every layer but the action variables, the curvature and plain words
};

// The length that the display scale (ViewOptions::scale, "body size") is given in: R, so that a
// body looks the same on any sphere; lengths in the conformal view, whose picture must not change
// with K (the dial) — a sphere of R = 1e6 would otherwise draw a body the size of a continent.
double body_scale_length(ViewKind view, const Surface& surface);

// The layer names ("surface", "grid", …, "actions") in the order of the one table of layers,
// kLayerTable (render/view_parameters.h, which defines these two).
std::span<const std::string_view> layer_names();

struct ViewOptions {
  ViewKind kind = ViewKind::sphere;
  int width = 640;   // [pixels]
  int height = 480;  // [pixels]
  // The width the picture is shown at [pixels]; 0: as drawn. A paced live picture is drawn smaller
  // and scaled up by the page: its overlay is sized for the shown size (hud_text_scale).
  int shown_width = 0;
  unsigned layers = kDefaultLayers;
  double yaw = 0.7;       // camera azimuth [rad] (3-D views)
  double pitch = 0.45;    // camera elevation [rad] (3-D views)
  double distance = 3.4;  // camera distance [surface radii] (3-D views)
  double scale = 0.25;    // display scale: the ellipse is the image of scale·(unit circle) under e_A
  // The point the 3-D camera orbits and the plane and conformal views centre on [world units], set
  // by aim_camera_at_body; nullopt: the view's own (the sphere's centre, a point above the
  // hyperboloid's vertex, the plane's origin). The disk view ignores it.
  std::optional<std::array<double, 3>> target;
  // The 2-D close-up: the view's own window shrunk this many times about target (a power of two),
  // set by aiming where the bodies would be specks (near the Poincaré disk's rim); 1: the view's own.
  double zoom = 1.0;
};

inline constexpr int kMaxImageSide = 4096;

// Whether a view can show a surface kind.
bool shows(const ViewInfo& view, SurfaceKind surface);
// The view a surface is shown in by default: sphere → sphere, pseudosphere → disk, plane → plane,
// the surfaces of revolution → revolution, the formula surfaces → formula.
ViewKind default_view(SurfaceKind surface);
// Why a view cannot show a surface, or nullopt.
std::optional<std::string> view_unsupported_reason(ViewKind view, SurfaceKind surface);

std::optional<ViewKind> parse_view(std::string_view name);
std::string_view view_name(ViewKind view);
// "surface,grid,body" → bitmask; nullopt names the first unknown layer in `unknown`.
std::optional<unsigned> parse_layers(std::string_view list, std::string* unknown = nullptr);

}  // namespace spinfold::render
