// The mutable state of a run: time, the chart it is expressed in, canonical coordinates, status.
#pragma once

#include <Eigen/Dense>
#include <string_view>

#include "engine/surface.h"

namespace spinfold {

// Canonical coordinates in a polar chart, at most 12 numbers, never heap-allocated:
//   affine: [r, φ, p_r, p_φ, L₁₁, L₁₂, L₂₁, L₂₂, P₁₁, P₁₂, P₂₁, P₂₂]   (physics.md §4, (L, P) form)
//   rigid:  [r, φ, p_r, p_φ, θ, s]                                    (physics.md §8.8)
// L is the internal matrix in the chart's frame (E₁, E₂), P = J(L̇ + Cφ̇εL) its momentum, s the spin.
// Room for 18: the chart-free state [X, V, e₁, e₂, W₁, W₂] on a surface whose curvature varies
// (engine/embedded_dynamics.h), which the same integrators step.
using Coords = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 18, 1>;

namespace coord {
inline constexpr int r = 0, phi = 1, p_r = 2, p_phi = 3;
inline constexpr int L = 4, P = 8;         // affine: first index of L and P (row-major 2x2)
inline constexpr int theta = 4, spin = 5;  // rigid
inline constexpr int affine_size = 12, rigid_size = 6;
}  // namespace coord

// A polar chart is the global one moved by an isometry: X_global = A X_chart + b, and tangent
// vectors map by A. Charts are re-centred so that the body never sits near a chart pole (where
// the polar coordinates are singular) nor far from it (where they lose precision on H²).
struct Chart {
  Mat3 A = Mat3::Identity();  // rotation (S², plane) or Lorentz transform (H²)
  Vec3 b = Vec3::Zero();      // translation (plane only)
  bool global = true;         // A = I, b = 0: the chart of the scene's coordinates
};

enum class Status {
  ok,                // running normally
  non_finite,        // a step produced a non-finite value; the state is the last good one
  step_failed,       // the step size underflowed; the state is the last good one
  degenerate_frame,  // det L reached 0 and the scene asked to stop there
  out_of_range,      // farther out on H² than the scene's global coordinates can express in double
                     // (r > kMaxHyperbolicDistance · R); the state is the last one within
  diverged,          // the energy error grew as large as the energy itself: the step is beyond the
                     // method's stability (or the tolerance too loose); the state is the last good one
  inconsistent,      // the closed form (exact) failed its independent check: its start or its conserved
                     // quantities disagree with the run's; the state is the last one that passed
  event_stop,        // a watched field crossed its level the number of times the run asked to stop at
                     // (engine/run_summary.h); the state is the crossing's
  event_unresolved,  // an event's levels are closer than double tells apart where its field is (period
                     // below kMinRelativePeriod of the field), or crossed more than 2⁵³ times; the
                     // state is the start of the step that met them
  too_many_events,   // det L crossed zero more than kMaxDegenerateEvents times (each is kept to be
                     // reported); the state is the last before the crossing past that
};

std::string_view status_name(Status status);
// One sentence for a person: what happened and what the state is.
std::string_view status_description(Status status);

struct State {
  double t = 0.0;  // [time]
  Chart chart;
  Coords y;
  Status status = Status::ok;
};

}  // namespace spinfold
