#include "engine/trail.h"

#include <cmath>

#include "engine/chart.h"

namespace spinfold {

namespace {

// Every other sample dropped, the spacing doubled: k·s with k even is (k/2)·(2s) in floating
// point too (scaling by 2 is exact), so the kept samples are the ones a coarser trail takes.
void halve(Trail& trail) {
  std::vector<TrailPoint> kept;
  kept.reserve(trail.points.size() / 2 + 1);
  for (TrailPoint p : trail.points)
    if (p.k % 2 == 0) {
      p.k /= 2;
      kept.push_back(p);
    }
  trail.points = std::move(kept);
  trail.spacing *= 2.0;
}

std::int64_t next_index(const Trail& trail) {
  return trail.points.empty() ? 0 : trail.points.back().k + 1;
}

}  // namespace

double next_sample_time(const Trail& trail) {
  return static_cast<double>(next_index(trail)) * trail.spacing;
}

void sample_trail_if_due(Trail& trail, const Simulation& run) {
  if (trail.companions.size() != run.companions.size()) {
    Trail fresh;
    fresh.spacing = trail.spacing;
    fresh.max_points = trail.max_points;
    trail.companions.assign(run.companions.size(), fresh);
  }
  for (std::size_t i = 0; i < run.companions.size(); ++i)
    sample_trail_if_due(trail.companions[i], run.companions[i]);
  if (run.state.t != next_sample_time(trail)) return;
  trail.points.push_back({next_index(trail), run.state.t, global_embedding(run.scene, run.state).X});
  if (trail.points.size() > trail.max_points) halve(trail);
}

bool advance_sampling_trail(Simulation& run, Trail& trail, double t_end, std::uint64_t max_attempts) {
  sample_trail_if_due(trail, run);
  for (double ts = next_sample_time(trail); ts <= t_end; ts = next_sample_time(trail)) {
    const bool done = advance_within(run, ts, max_attempts);
    if (!done || run.state.status != Status::ok || run.state.t != ts) return done;
    sample_trail_if_due(trail, run);
  }
  return advance_within(run, t_end, max_attempts);
}

std::vector<Vec3> trail_positions(const Trail& trail, double t, double span) {
  std::vector<Vec3> out;
  out.reserve(trail.points.size());
  for (const TrailPoint& p : trail.points)
    if (p.t <= t && (span < 0.0 || p.t >= t - span)) out.push_back(p.X);
  return out;
}

namespace {

void carry(Trail& trail, const Surface& before, const Surface& after) {
  for (TrailPoint& p : trail.points) p.X = carried_position(before, after, p.X);
  for (Trail& companion : trail.companions) carry(companion, before, after);
}

}  // namespace

void retune_carrying_trail(Simulation& run, Trail& trail, const Scene& next) {
  const Surface before = run.scene.surface;
  retune(run, next);
  carry(trail, before, next.surface);
}

}  // namespace spinfold
