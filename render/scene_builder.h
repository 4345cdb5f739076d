// build_scene: a snapshot and a view in, plain draw lists out. No GL: everything here is testable
// without a context (physics of the drawing, not pixels).
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/snapshot.h"
#include "render/view.h"

namespace spinfold::render {

struct Vertex {
  glm::vec3 position;  // world coordinates (embedding / R, see world_position)
  glm::vec4 color;     // RGBA in [0, 1]
};

struct LitVertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec3 tint{1.0f};  // the curvature layer's colour at the vertex (curvature_color of K there)
};

// Geometry that depends only on the surface kind and the view: built once and reused.
// An edge of the surface mesh with the normals of the faces on either side (one for the mesh's
// boundary): what silhouette() needs.
struct SurfaceEdge {
  std::uint32_t a = 0, b = 0;  // indices into StaticGeometry::surface
  glm::vec3 face[2]{};         // the faces' normals (unnormalised)
  int faces = 0;               // 1 on the boundary, 2 inside
};

struct StaticGeometry {
  std::vector<LitVertex> surface;  // triangles, lit
  std::vector<Vertex> grid;        // line segments
  std::vector<SurfaceEdge> edges;  // each edge of the surface once (degenerate faces left out)
  std::uint64_t id = 0;            // unique among all ever built (the GL renderer's key for its buffers)
};
// The unit surface of a constant-curvature kind in a view: built once, kept for the process's life.
const StaticGeometry& static_geometry(SurfaceKind surface, ViewKind view);
// Any surface's: a constant kind's as above; a surface whose curvature varies has its own shape
// (its parameters), so the last kStaticGeometryCache of those are kept and older ones freed once no
// frame holds them (a slider dragged through a thousand tube radii keeps eight meshes).
inline constexpr std::size_t kStaticGeometryCache = 8;
// And at most this many bytes of them (a formula surface's mesh is ~4 MB; the newest is kept whatever
// its size), the patches' four included.
inline constexpr std::size_t kStaticGeometryBytes = std::size_t{64} << 20;
std::shared_ptr<const StaticGeometry> static_geometry(const Surface& surface, ViewKind view);
// Where a view's patch of the surface is (ViewModel::patch_at): the revolution view's (u, φ, 0), the
// formula view's box centre [length].
using PatchPlace = std::array<double, 3>;
// The same with the view's patch at `at` added (ViewModel::patch_at; the last four are kept).
std::shared_ptr<const StaticGeometry> static_geometry(const Surface& surface, ViewKind view, PatchPlace at);

// The curvature layer's diverging colour of K·ℓ² (ℓ: the surface's length, so that the colour is
// the same for any size): white at 0, warm (orange-red) for K > 0, cool (blue) for K < 0, saturated
// at |K|·ℓ² = `full`.
glm::vec3 curvature_color(double K_times_length_squared, double full);

// Line widths of a frame [pixels]. The outline, trail and arrows are 1.5 px at 640×480 and grow
// with the frame's shorter side measured in 4:3 terms (min(width·3/4, height)/480), so that a frame
// shown larger on a projector keeps the same weight; the grid, behind them, is two thirds as wide.
// Neither is ever thinner than 1 px (thumbnails: 160×120 gets 1 px lines, anti-aliased).
struct LineWidths {
  float lines = 1.0f;  // outline, trail, arrows [pixels]
  float grid = 1.0f;   // the surface's grid [pixels]
};
LineWidths line_widths(int width, int height);

// The plane view: the grid's spacing and the half-height of the frame [world units, radii].
inline constexpr double kPlaneGridSpacing = 0.5, kPlaneHalfHeight = 3.0;

// A frame narrower or lower than this [pixels] (a phone's picture, a thumbnail, the smallest paced
// picture) has a compact overlay: the HUD says the time and what the picture itself needs said
// (hud_lines), and there is no legend. With the full overlay at 320×240 and 390×290 a body was
// under the HUD, the legend or out of the frame in 81 of the 2444 framings of
// Camera.EveryPresetInEveryViewItOffersShowsItsBodiesClearOfTheBoxes (all at those two sizes);
// compact, in none.
inline constexpr int kFullOverlayWidth = 480, kFullOverlayHeight = 300;

// The overlay's text scales (of the built-in 13 px font, one font made per scale): 0.625 and 0.75
// for a paced picture (drawn at 0.5-0.8 of its shown size: the page scales it up, the text to the
// full picture's size), 1, the projector floor 1.25, then half steps up to 4× (larger frames draw
// the text at 4×).
inline constexpr std::array<double, 10> kHudScales{0.625, 0.75, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0};
// The text scale a frame drawn width×height and shown shown_width pixels wide (0: as drawn) wants,
// in the drawn picture's pixels: hud_layout's rule for the shown size, times width/shown_width (a
// paced picture drawn at half its shown size wants half the scale). Below 1 no font is that small.
double hud_text_scale(int width, int height, int shown_width = 0);

// Compact: a frame small as shown (a paced picture by the size it is shown at), or one shown so
// much larger than drawn that no font is small enough for its text to be the full picture's size
// on the screen.
inline bool compact_overlay(const ViewOptions& view) {
  const double shown = view.shown_width > 0 ? view.shown_width : view.width;
  const double enlarged = shown / view.width;
  return shown < kFullOverlayWidth || view.height * enlarged < kFullOverlayHeight ||
         hud_text_scale(view.width, view.height, view.shown_width) < kHudScales.front() - 0.0625;
}

// One line of the in-frame legend: a body's swatch (its trail, dashed for the geodesic companion,
// and its fill) and label.
struct LegendEntry {
  std::string label;
  glm::vec4 color;        // the body's fill, opaque
  glm::vec4 trail_color;  // its trail's
  bool dashed = false;    // the geodesic companion's trail
  bool dot = true;        // the fill's dot on the swatch (none: a colour of a trail, not a body)
  // A two-colour key in one row ("path bends left / right"): the swatch's right half in this colour,
  // in the label's order.
  std::optional<glm::vec4> right_half;
};

// The bending layer (kBending): the main body's trail coloured by its geodesic curvature κ_g
// (engine/path_bending.h), orange where it turns left, bluish green where it turns right (Okabe–Ito's
// colours, told apart in every common colour blindness, and apart from the companions' blue and the
// curvature layer's), grey where |κ_g| ℓ < kStraightBending; from 40 % of
// the colour at that floor to all of it at |κ_g| ℓ = kFullBending, ℓ the surface's feature length (a
// torus's tube, R), so that one bend reads the same from frame to frame (the torus preset's κ_g ℓ
// runs from −0.67 to +0.29: both bands in full colour). The geodesic companion keeps its dashes.
inline constexpr glm::vec4 kBendsLeftColor{0.835f, 0.369f, 0.0f, 1.0f};
inline constexpr glm::vec4 kBendsRightColor{0.0f, 0.62f, 0.451f, 1.0f};
inline constexpr glm::vec4 kStraightColor{0.55f, 0.55f, 0.58f, 1.0f};
inline constexpr double kStraightBending = 0.02, kFullBending = 0.25;
glm::vec4 bending_color(double kappa_length);
// Whether the layer colours the main body's trail (not: the layer off, no trail of three points, the
// geodesic companion as the main body).
bool main_trail_bends(const Snapshot& snapshot, const ViewOptions& view);
// κ_g ℓ at each point of the main body's trail where the layer colours it; empty where it does not.
std::vector<double> main_trail_bending(const Snapshot& snapshot, const ViewOptions& view);
// The in-frame legend: each body where there is more than one to tell apart, then the bending
// layer's one row "path bends left / right" where it colours the main trail (the main body's own
// swatch then grey, as its trail is where it runs straight); none in a compact_overlay frame.
// build_scene draws it and the camera keeps clear of its box.
std::vector<LegendEntry> legend_entries(const Snapshot& snapshot, const ViewOptions& view);

// A rectangle of the frame [pixels, x right, y down from the top-left corner]; empty when w = 0.
struct PixelBox {
  double x = 0.0, y = 0.0, w = 0.0, h = 0.0;
  bool contains(const glm::dvec2& p) const {
    return w > 0.0 && p.x >= x && p.x < x + w && p.y >= y && p.y < y + h;
  }
};

// Where the HUD (top-left) and the legend (top-right) go and how large their text is. The text is
// Dear ImGui's built-in font (ProggyClean: 13 px, 7 px advance, ASCII) at `scale` times its size;
// the scale grows with the frame's shorter side in 4:3 terms, min(width·3/4, height)/540, in half
// steps and never below 1: unchanged up to 640×480 (and in thumbnails), 1.5× at 1280×720, 2× at
// 1920×1080, so that a frame shown on a projector stays legible; and at least 1.25× (16 px) from
// kHudProjectorSide up (the ~795×515 picture of a 1366×900 page). Plain arithmetic, no ImGui: the
// overlay draws exactly these boxes, and the cameras keep the bodies out of them.
inline constexpr double kHudProjectorSide = 500.0;  // [pixels, the shorter side in 4:3 terms]
struct HudLayout {
  double scale = 1.0;     // of the font and of every length below
  double font_size = 13;  // [pixels]
  double advance = 7;     // of a glyph [pixels]
  double line = 15;       // from one line of text to the next [pixels]
  double padding = 5;     // inside a box [pixels]
  double swatch = 30;     // the legend's swatch width [pixels]
  PixelBox hud, legend;   // empty when not drawn
};
// shown_width: the width the frame is shown at (0: as drawn); the scale is the nearest of kHudScales
// to hud_text_scale's (1 below it: a compact overlay's).
HudLayout hud_layout(const std::vector<std::string>& lines, const std::vector<std::string>& legend_labels,
                     int width, int height, int shown_width = 0);

struct FrameScene {
  std::shared_ptr<const StaticGeometry> statics;  // null when neither surface nor grid is drawn
  bool draw_surface = false, draw_grid = false;
  bool tint_by_curvature = false;  // the curvature layer: the surface coloured by its vertices' tint
  std::vector<Vertex> fills;       // translucent triangles (the ellipse)
  std::vector<Vertex> lines;       // line segments (trail, outline, arrows)
  std::size_t trails_begin = 0, trails_end = 0;  // the trails' vertices in `lines`
  // Bodies behind the surface drawn faintly through it (the sphere view: a companion on the far
  // side, which no camera can show face-on with the main body): no depth test, drawn first.
  std::vector<Vertex> ghost_fills, ghost_lines;
  std::vector<std::string> hud_lines;  // empty when the HUD is off
  std::vector<LegendEntry> legend;     // one per body when there is more than one body to tell apart
                                       // and the frame is at least kLegendMinWidth wide
  HudLayout hud;                       // the boxes of hud_lines and legend
  // The plane view's grid, which follows its camera (lines every kPlaneGridSpacing across the
  // frame), and the conformal view's (that grid's image, and the ideal boundary of H²); drawn with
  // the background.
  std::vector<Vertex> grid_lines;
  // Opaque triangles drawn with the surface layer before the grid (the conformal view's Poincaré
  // disk when it does not cover the frame).
  std::vector<Vertex> backdrop;
  glm::mat4 view_projection{1.0f};
  bool depth_test = true;  // 3-D views hide what is behind the surface
  // Grid, fills and lines are drawn this fraction of the way towards the camera (same pixels,
  // nearer depth) so that the surface's faces hide none of a wide line's width.
  float depth_bias = 0.0f;
  glm::vec4 surface_color{0.78f, 0.83f, 0.90f, 1.0f};
  glm::vec4 clear_color{0.97f, 0.97f, 0.96f, 1.0f};
};

FrameScene build_scene(const Snapshot& snapshot, const ViewOptions& view);

// The direction the surface is lit from (lit.vert's light_direction): the camera's side in the 3-D
// views, straight on in the 2-D ones.
glm::vec3 headlight(const FrameScene& scene);

// lit.vert's colour of a surface vertex lit from `light` over an `ambient` floor: the surface's colour,
// or with the curvature layer the vertex's tint.
glm::vec4 lit_color(const FrameScene& scene, const LitVertex& v, const glm::vec3& light, float ambient);

// The surface's outline as seen by the scene's camera: the mesh's boundary edges and the edges
// between a face turned towards the camera and one turned away, as line segments in the shaded
// surface's colour at their ends. Drawn as anti-aliased lines over the surface they smooth its
// silhouette against the background without multisampling.
std::vector<Vertex> silhouette(const StaticGeometry& g, const FrameScene& scene);

// The camera placed to show the bodies and their trails, clear of the HUD's and legend's boxes:
// on the sphere, looking at the centre of everything drawn of the bodies, turned and tilted (a
// few candidates tried in a fixed order) until every body and as much of every trail as can be
// are in the frame and out of the boxes; on the hyperboloid, orbiting the centre of the bodies and
// their trails' last stretch (up to 3 radii from a body) from across the bowl, as far away as
// they need (the same search then clears the boxes); on the plane, centred on the bodies.
void aim_camera_at_body(ViewOptions& view, const Snapshot& snapshot);

// The scale a body is drawn at [length per frame unit]: `scale`, or less, so that its ellipse
// reaches no farther than kMaxDrawnExtent of the surface's curvature radius (R on S² and H², the
// feature where the curvature varies) from the body: the image of a larger one wraps round the
// sphere or runs far out on H², a torn polygon (λ = 26 painted the whole sphere). The plane draws
// any size. Its ratio to `scale` is below 1 for a body drawn smaller than it is (the HUD says so).
inline constexpr double kMaxDrawnExtent = 0.5;
double drawn_scale(const Surface& surface, const BodySnapshot& body, double scale);

// The read-out's lines for the HUD and a figure's caption: the snapshot's, the action variables'
// with that layer, the view's note when the main body is off what it draws (beyond the
// tractricoid's rim, the bump's or catenoid's piece), and the scale a too-large frame is drawn at.
std::vector<std::string> readout_lines(const Snapshot& snapshot, const ViewOptions& view);
// The in-frame HUD's lines: readout_lines, or in a compact_overlay frame its first (the time), the
// action variables where that layer is asked for, and the notes about the picture (off the view, a
// close-up, a body drawn smaller); lines wrapped to the frame's width (a compact one's half).
std::vector<std::string> hud_lines(const Snapshot& snapshot, const ViewOptions& view);

// Points of a body's ellipse on the surface: exp_X(scale·(cos θ e₁ + sin θ e₂)), embedding
// coordinates (exposed for tests).
std::vector<Vec3> ellipse_points(const Surface& surface, const BodySnapshot& body, double scale, int count);

// exp_X(v) on the surface for a tangent v at X of intrinsic length |v| (passed in: far out on H²
// it cannot be computed from v's embedded components).
Vec3 exponential_map(const Surface& surface, const Vec3& X, const Vec3& v, double length);

// Where an embedded point lands in the view's world coordinates.
//   klein:       (X₁, X₂)/X₃, the Beltrami–Klein disk (geodesics are chords);
//   halfplane:   the upper half-plane (half_plane_point);
//   tractricoid: the covering map of the horocyclic strip y' = kTractricoidDilation·y ≥ 1 of the
//                half-plane: θ = x', ρ = R/y', z = R(arcosh y' − √(1 − 1/y'²)), i.e. ρ = R sech u,
//                z = R(u − tanh u) with y' = cosh u; points with y' < 1 (off the surface, see
//                on_view) land in the rim's plane at ρ = R/y' and are not drawn;
//   conformal:   conformal_point, in lengths (not radii).
glm::dvec3 world_position(const Surface& surface, ViewKind view, const Vec3& X);

// ---- The conformal view: one flat map for every curvature K [1/length²], continuous in K.
// A point at geodesic polar coordinates (r, φ) about the pole goes to w = T_K(r)(cos φ, sin φ)
// [length], with T_K(r) = 2R tan(r/2R) for K = 1/R² > 0 (stereographic projection from the
// antipode, scaled to the sphere's size: the antipode goes to infinity), r for K = 0 and
// 2R tanh(r/2R) for K = −1/R² < 0 (the Poincaré disk |w| < 2R). Written with R = 1/√|K|, finite
// whenever K ≠ 0, nothing divides by a vanishing K; T_K(r) = r(1 + Kr²/12 + O(K²r⁴)).
// The pulled-back metric is ds² = |dw|²/(1 + K|w|²/4)²: a tangent vector of length ℓ at w is
// drawn with length ℓ·(1 + K|w|²/4), at its angle to the radial (E₁) and angular (E₂) directions.

// T_K(r) [length] for r ≥ 0 [length].
double conformal_radius(double curvature, double r);
// Its inverse: the distance r whose image lies at |w| = t; +∞ at and beyond H²'s boundary t ≥ 2R.
double conformal_distance(double curvature, double t);
// 1 + K|w|²/4: drawn length over intrinsic length at w (|dw|/ds).
double conformal_factor(double curvature, const glm::dvec2& w);
// w of an embedded point of the surface [length].
glm::dvec2 conformal_point(const Surface& surface, const Vec3& X);

// The Poincaré upper half-plane's (x, y) of a point of H² (the Cayley transform of the disk, the
// centre X = (0, 0, R) at (0, 1)): y = R/(X₃ − X₁), x = −X₂/(X₃ − X₁), computed as
// (X₃ + X₁)/(R² + X₂²) so that nothing cancels far out.
glm::dvec2 half_plane_point(const Surface& surface, const Vec3& X);

// The tractricoid shows the strip y ≥ 1/kTractricoidDilation of the half-plane, the centre at
// u = arcosh 2 above the rim; its θ = kTractricoidDilation·x wraps round every 2π/k in x.
inline constexpr double kTractricoidDilation = 2.0;

// Whether the view shows this point: false only for points of H² off the tractricoid's strip.
bool on_view(const Surface& surface, ViewKind view, const Vec3& X);

// Its pixel position (x right, y down) and whether it is in front of the camera.
std::optional<glm::dvec2> pixel_position(const FrameScene& scene, const ViewOptions& view,
                                         const glm::dvec3& world);

}  // namespace spinfold::render
