#include "render/snapshot.h"

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/readout.h"

namespace spinfold::render {

Snapshot make_snapshot(const Simulation& run, std::vector<Vec3> trail) {
  const Scene& scene = run.scene;
  const EmbeddedBody body = global_embedding(scene, run.state);
  Snapshot s;
  s.surface = scene.surface;
  s.X = body.X;
  s.e[0] = body.e[0];
  s.e[1] = body.e[1];
  const Mat2 L = internal_state(scene, run.state.y).L;
  s.gram = L.transpose() * L;
  s.trail = std::move(trail);
  s.hud_lines = readout_lines(scene, readout(run));
  return s;
}

}  // namespace spinfold::render
