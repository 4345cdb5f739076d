// An immutable snapshot of what a frame shows: the body's embedded position and frame, its trail,
// and the numbers of the HUD. Built from a run; the renderer never sees the engine's state.
#pragma once

#include <string>
#include <vector>

#include "engine/simulation.h"
#include "engine/surface.h"

namespace spinfold::render {

struct Snapshot {
  Surface surface;
  Vec3 X;                              // body position, the scene's embedding coordinates [length]
  Vec3 e[2];                           // the deformed frame e_A at X [length]
  Mat2 gram = Mat2::Identity();        // ⟨e_A, e_B⟩ = (LᵀL)_AB, intrinsic: far out on H² the embedded
                                       // components of e_A are ~e^{r/R} and their η-products cancel
  std::vector<Vec3> trail;             // earlier positions, oldest first (empty: no trail)
  std::vector<std::string> hud_lines;  // readout_lines of the run (engine/readout.h)
};

// The snapshot of a run's current state; `trail` as recorded by the caller.
Snapshot make_snapshot(const Simulation& run, std::vector<Vec3> trail);

}  // namespace spinfold::render
