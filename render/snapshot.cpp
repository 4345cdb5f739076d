#include "render/snapshot.h"

#include <algorithm>
#include <stdexcept>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/guiding_centre.h"
#include "engine/orbit_bound.h"
#include "engine/readout.h"

namespace spinfold::render {

namespace {

// One body of the run (the main run or a companion's) with its trail's points in the span.
BodySnapshot body_snapshot(const Simulation& run, const Trail* trail, double span) {
  const Scene& scene = run.scene;
  const EmbeddedBody body = global_embedding(scene, run.state);
  BodySnapshot b;
  b.X = body.X;
  b.e[0] = body.e[0];
  b.e[1] = body.e[1];
  const Mat2 L = internal_state(scene, run.state.y).L;
  b.gram = L.transpose() * L;
  if (trail) {
    b.trail = trail_positions(*trail, run.state.t, span);
    if (!b.trail.empty() && b.trail.back() != b.X) b.trail.push_back(b.X);
  }
  return b;
}

}  // namespace

std::array<float, 3> companion_color(const Scene& scene, std::size_t i) {
  if (const auto& c = scene.companions.at(i).color)
    return {static_cast<float>((*c)[0]), static_cast<float>((*c)[1]), static_cast<float>((*c)[2])};
  return kCompanionPalette[i % kCompanionPalette.size()];
}

const SurfaceModel& surface_model(const Snapshot& snapshot) {
  if (!snapshot.model || !same_model(snapshot.model->surface, snapshot.surface))
    throw std::logic_error("Snapshot: its model is not its surface's");
  return *snapshot.model;
}

Snapshot make_snapshot(const Simulation& run, const Trail& trail, double span) {
  const Scene& scene = run.scene;
  Snapshot s;
  s.surface = scene.surface;
  s.model = run.surface;
  s.bodies.reserve(1 + run.companions.size());
  s.bodies.push_back(body_snapshot(run, &trail, span));
  s.bodies.front().label = main_body_label(scene);
  if (const auto d = guiding_drift(run)) s.bodies.front().drift = d->direction;
  const Readout main = readout(run);
  s.hud_lines = readout_lines(scene, main);
  const std::string held = orbit_bound_note(orbit_bound(run));
  s.hud_lines.back() += held;  // the spin's line: held by it, or not
  s.plain_lines = plain_readout_lines(scene, main);
  s.plain_lines.back() += held;
  s.plain_main_label = scene.main_label.empty() ? "the body" : scene.main_label;
  s.action_lines = action_lines(main);
  for (std::size_t i = 0; i < run.companions.size() && i < scene.companions.size(); ++i) {
    const Trail* own = i < trail.companions.size() ? &trail.companions[i] : nullptr;
    BodySnapshot b = body_snapshot(run.companions[i], own, span);
    b.color = b.trail_color = companion_color(scene, i);
    b.label = companion_label(scene, i);
    b.geodesic = scene.companions[i].geodesic;
    if (const auto d = guiding_drift(run.companions[i])) b.drift = d->direction;
    OrbitBound bound = orbit_bound(run.companions[i]);
    bound.critical_spin.reset();  // said once, on the main body's line: a companion's says the verdict
    const Readout companion = readout(run.companions[i]);
    s.hud_lines.push_back(companion_readout_line(b.label, companion) + orbit_bound_note(bound));
    if (companion.status != Status::ok) s.plain_lines.push_back(b.label + ": stopped");
    s.bodies.push_back(std::move(b));
  }
  return s;
}

Snapshot snapshot_at(const Scene& scene, double t, bool with_trail, std::optional<double> trail_span,
                     Simulation& run) {
  run = start_simulation(scene);
  Trail trail;  // every body's, companions' included
  const double span = std::min(t, trail_span.value_or(t));
  if (with_trail && span > 0.0) {
    // Recorded only when drawn, every body's at k·spacing from t = 0 (so that a short span late in
    // a long run does not stop the run millions of times).
    trail.spacing = std::max(span / 512, t / 65536);
    trail.max_points = 65536 + 2;
    advance_sampling_trail(run, trail, t);
  }
  advance_to(run, t);
  return make_snapshot(run, trail, span);
}

}  // namespace spinfold::render
