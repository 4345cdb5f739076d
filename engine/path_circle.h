// The circle a spinning body runs on (physics.md §8.5) as a student checks it: the radius measured
// from the path drawn, next to the one the theory predicts from the state, and, where there is no
// circle, why. The HUD (render/snapshot.cpp) and the session's samples (server) both use this.
#pragma once

#include <optional>
#include <span>
#include <string>

#include "engine/simulation.h"
#include "engine/trail.h"

namespace spinfold {

// The geodesic radius [length] the theory predicts for the run's state (physics.md §8.5: constant
// curvature, no radial potential, no friction): on S², R·atan2(m v R, |s|), the smaller of the
// circle's two radii (a great circle, πR/2, at s = 0); on H² with |s| > m v R, R·artanh(m v R/|s|).
// None elsewhere, with the reason in `why_none` ("a straight line: no curvature (K = 0)", "a
// geodesic: no spin (s = 0)" on H², "a hypercycle: |s| < m v R", …).
struct PredictedCircle {
  std::optional<double> radius;
  double period = 0.0;  // [time] of one lap: its circumference 2πS(ρ) over v
  std::string why_none;
};
PredictedCircle predicted_circle(const Scene& scene, double spin, double speed);

// The geodesic radius [length] of the circle through points on S² or H² (embedding coordinates):
// the plane of their best fit (least squares) cuts the surface in it. On S², the smaller of its two
// radii; on H², none where the plane's section is not a circle (a horocycle or hypercycle). `off`
// gets the points' rms distance from the plane [length] (0 on a circle, to round-off).
std::optional<double> circle_through(const Surface& surface, std::span<const Vec3> points,
                                     double* off = nullptr);

// Both for a run and its trail: measured through the trail's points of the last lap (since the
// last parameter change), once they span at least an eighth of it; none before, or where none is
// predicted (the path is no circle then, and a fit would name a radius it does not have).
struct CircleReadout {
  PredictedCircle predicted;
  std::optional<double> measured;
};
CircleReadout circle_readout(const Simulation& run, const Trail& trail);

// The HUD's and the readout's line: "circle radius = 0.4636 (predicted 0.4636)", "circle radius:
// predicted 0.4636 (measuring)", "no circle: a straight line (K = 0)"; "" where the scene is not
// one of constant curvature (the torus, …: no circle to speak of).
std::string circle_line(const Scene& scene, const CircleReadout& circle);

}  // namespace spinfold
