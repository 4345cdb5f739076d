// The body's path for drawing: positions sampled at t = k·spacing, so that it follows the true
// path and does not depend on how the run was advanced (one advance or many, play ticks, frames).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/simulation.h"

namespace spinfold {

struct TrailPoint {
  std::int64_t k = 0;  // sample index: t = k · spacing at the time it was taken
  double t = 0.0;      // [time]
  Vec3 X;              // position in the scene's embedding coordinates [length]
};

struct Trail {
  double spacing = 0.01;           // [time] between samples; doubles whenever max_points is passed
  std::size_t max_points = 8192;   // beyond this every other sample is dropped (the run's whole
                                   // path is kept, at half the resolution)
  std::vector<TrailPoint> points;  // oldest first; points[i].t = points[i].k · spacing
  std::vector<Trail> companions;   // the run's companions' trails, sampled at the same times
};

// The first sample time after the last one recorded (or 0) [time].
double next_sample_time(const Trail& trail);

// Samples the run's current position into the trail if it is at a sample time not yet taken, and
// each companion's likewise (a companion that stopped is sampled no more). ("Sample", not "record":
// a recording is a video file of the server's jobs, record/ and server/recordings.h.)
void sample_trail_if_due(Trail& trail, const Simulation& run);

// advance_to that takes the trail's samples on the way to t_end (each is the state advance_to
// gives at that time, so the trail is the same however the run was advanced).
bool advance_sampling_trail(Simulation& run, Trail& trail, double t_end,
                            std::uint64_t max_attempts = kNoStepLimit);

// retune (engine/simulation.h) that carries the trail along: after a curvature dial or a radius
// change each recorded point moves as the body does (the same (r, φ), or the same place in units
// of R), so the path drawn stays on the surface shown.
void retune_carrying_trail(Simulation& run, Trail& trail, const Scene& next);

// The points within the last `span` [time] before `t` (all of them for span < 0).
std::vector<Vec3> trail_positions(const Trail& trail, double t, double span);

}  // namespace spinfold
