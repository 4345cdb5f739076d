// An immutable snapshot of what a frame shows: every body's embedded position and frame, its trail,
// its colour and label, and the numbers of the HUD. Built from a run; the renderer never sees the
// engine's state.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/simulation.h"
#include "engine/surface.h"
#include "engine/surface_model.h"
#include "engine/trail.h"

namespace spinfold::render {

// Colours of the main body (today's colours, unchanged by companions) [sRGB in 0–1].
inline constexpr std::array<float, 3> kMainBodyColor{0.96f, 0.55f, 0.12f};
inline constexpr std::array<float, 3> kMainTrailColor{0.35f, 0.20f, 0.75f};

// The companions' palette, used in order when a companion gives no colour: saturated, mid-dark
// colours that stand apart from the main body's orange and purple, the frame arrows' red and
// green, the light blue-grey and grey-green surfaces and a projector's washed-out whites.
inline constexpr std::array<std::array<float, 3>, 8> kCompanionPalette{{
    {0.00f, 0.42f, 0.75f},  // blue
    {0.80f, 0.10f, 0.55f},  // magenta
    {0.00f, 0.55f, 0.50f},  // teal
    {0.55f, 0.33f, 0.05f},  // brown
    {0.20f, 0.20f, 0.22f},  // charcoal
    {0.55f, 0.55f, 0.00f},  // olive
    {0.85f, 0.30f, 0.30f},  // coral
    {0.35f, 0.35f, 0.90f},  // indigo
}};

struct BodySnapshot {
  Vec3 X;                        // position, the scene's embedding coordinates [length]
  Vec3 e[2];                     // the deformed frame e_A at X [length]
  Mat2 gram = Mat2::Identity();  // ⟨e_A, e_B⟩ = (LᵀL)_AB, intrinsic: far out on H² the embedded
                                 // components of e_A are ~e^{r/R} and their η-products cancel
  std::vector<Vec3> trail;       // earlier positions, oldest first, ending at X (empty: no trail)
  std::array<float, 3> color = kMainBodyColor;         // the body's fill [sRGB in 0–1]
  std::array<float, 3> trail_color = kMainTrailColor;  // its trail's [sRGB in 0–1]
  std::string label;      // legend text: main_body_label ("body 1") or companion_label
  bool geodesic = false;  // the point-particle companion: its trail is drawn dashed
  // Where its guiding centre drifts (engine/guiding_centre.h): the drift's unit direction at X.
  std::optional<Vec3> drift;
};

struct Snapshot {
  Surface surface;
  // The surface resolved (the run's, engine/surface_model.h): what a frame asks of it (its F, its
  // drawn piece) is asked of this. make_snapshot sets both; a snapshot built by hand sets it as
  // surface_model_of(surface).
  std::shared_ptr<const SurfaceModel> model;
  std::vector<BodySnapshot> bodies;    // the main body first, then the companions in scene order
  std::vector<std::string> hud_lines;  // readout_lines of the run, then one compact line per companion
  // plain_readout_lines of the run, then a line for each companion that stopped (the plain layer's);
  // the main body's legend label in plain words ("the body" unless the scene names it).
  std::vector<std::string> plain_lines;
  std::string plain_main_label;
  std::vector<std::string> action_lines;  // action_lines of the run (drawn with the actions layer)
};

// The snapshot's surface model, checked to be its surface's (std::logic_error for a snapshot built
// without one or whose surface was changed after it): what a frame asks of the surface.
const SurfaceModel& surface_model(const Snapshot& snapshot);

// The snapshot of a run's current state and of its companions'. Each body's trail holds its
// recorded positions within the last `span` [time] (all of them for span < 0) followed by its
// current position; an empty `trail` (no samples) gives bodies without trails.
Snapshot make_snapshot(const Simulation& run, const Trail& trail, double span);

// The snapshot of the scene's run at time t [time] as `spinfold render` draws it: the run advanced
// from 0, the trail (when `with_trail`) recorded at 512 samples over the last `trail_span` [time]
// (default: the whole run; fewer when the span is under 1/128 of the run, at most 2^16 samples).
// `run` gets the run (its status says whether it stopped before t). The CLI and the Python
// binding draw their stills from this, so their pixels are equal.
Snapshot snapshot_at(const Scene& scene, double t, bool with_trail, std::optional<double> trail_span,
                     Simulation& run);

// Companion i's colour: its own, else the palette's entry i (cycled).
std::array<float, 3> companion_color(const Scene& scene, std::size_t i);

}  // namespace spinfold::render
