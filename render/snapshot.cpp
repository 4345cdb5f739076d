#include "render/snapshot.h"

#include <cmath>
#include <cstdio>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/invariants.h"

namespace spinfold::render {

namespace {

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[160];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

}  // namespace

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
  const double H = energy(scene, run.state);
  const char* kind = scene.surface.kind == SurfaceKind::sphere         ? "sphere"
                     : scene.surface.kind == SurfaceKind::pseudosphere ? "pseudosphere"
                                                                       : "plane";
  s.hud_lines = {
      format("t = %.3f", run.state.t),
      format("energy error = %.2e",
             (H - run.initial_energy) / std::max(std::abs(run.initial_energy), 1e-300)),
      "integrator: " + std::string(run.info->name) + (run.state.status == Status::ok ? "" : "  [stopped]"),
      std::string(kind) + format("  R = %g", scene.surface.radius),
      format("m = %g  J = %g  ", scene.body.mass, scene.body.inertia) +
          (scene.body.model == BodyModel::rigid ? "rigid" : "affine"),
      format("spin = %.4f  det L = %.4f", spin(scene, run.state), det_L(scene, run.state)),
  };
  return s;
}

}  // namespace spinfold::render
