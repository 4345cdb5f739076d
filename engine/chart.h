// Charts and the embedding: building a state, re-centring its chart, reading it back in any
// coordinates (physics.md §7, "Conversions").
#pragma once

#include "engine/scene.h"
#include "engine/state.h"

namespace spinfold {

// A body described by vectors in one coordinate system (a chart's embedding or the global one).
struct BodyKinematics {
  Vec3 X;       // position [length]
  Vec3 V;       // velocity dX/dt [length/time]
  Vec3 F1;      // unit tangent vector that, with F₂ = jF₁, is the frame L and M refer to
  Mat2 L;       // internal matrix: e_A = F_B L_BA
  Mat2 M;       // covariant rate: De_A/Dt = F_B M_BA [1/time]
  double spin;  // s [angular momentum]; frame-independent
};

// The body in the coordinates of its own chart (the chart must not be at its pole).
BodyKinematics chart_kinematics(const Scene& scene, const Coords& y);

// Canonical coordinates of a body given in a chart's embedding coordinates (the body must not be
// at that chart's pole).
Coords chart_coords(const Scene& scene, const BodyKinematics& body);

// The body in the scene's coordinates, from the initial values of physics.md §2 (valid at a pole).
BodyKinematics initial_kinematics(const Scene& scene);

// The state at t = 0, in a chart where the body is far from the chart's pole.
State initial_state(const Scene& scene);

// A body given in the scene's polar frame: at (r, φ), velocity v_r E₁ + v_φ E₂, L and M in (E₁, E₂).
struct PlacedBody {
  double r, phi;      // [length], [rad]
  double v_r, v_phi;  // [length/time]
  Mat2 L, M;          // internal matrix, covariant rate [1/time]
  double spin;        // s [angular momentum]
};
// Its state (t = 0, status ok) in a well-conditioned chart, built without the global embedding far
// out on H² (valid for any r the scene allows).
State place_body(const Scene& scene, const PlacedBody& body);

// True while the chart coordinate r keeps the polar chart accurate: away from its pole(s) and,
// on H², not so far out that φ loses precision. A chart is left when this turns false.
bool chart_well_conditioned(const Surface& surface, double r);
// A narrower band: a moved chart returns to the scene's chart once the body is this well inside
// it (the gap between the two bands keeps the chart from flip-flopping).
bool chart_comfortable(const Surface& surface, double r);

// After a step: leaves an ill-conditioned chart, and returns to the scene's chart when it is
// comfortable, where p_φ is a coordinate and kept exactly by every integrator. True if it moved.
bool maintain_chart(const Scene& scene, State& state);

// Moves the chart so that the body sits at a well-conditioned distance from the new pole, with
// the new pole placed off the body's path. The physical state is unchanged.
void recentre(const Scene& scene, const BodyKinematics& body_in_chart, Chart& chart, Coords& y);
void recentre(const Scene& scene, State& state);

// The body in the scene's embedding coordinates (physics.md §7 state (X, V, e_A, W_A)), valid
// everywhere including the poles: what a renderer draws.
struct EmbeddedBody {
  Vec3 X, V;  // position [length], velocity [length/time]
  Vec3 e[2];  // deformed frame e_A [length]
  Vec3 W[2];  // covariant rates De_A/Dt [length/time]
};
EmbeddedBody global_embedding(const Scene& scene, const State& state);

// How far two states of a scene are apart, chart-free: the largest component difference of their
// embedded X, V, e_A and W_A, each relative to max(1, |b's vector|) [1]; infinity if not finite.
// The benchmarks' error where no oracle is at hand.
double embedded_state_error(const Scene& scene, const State& a, const State& b);

// Inverse of the chart isometry's linear part: ηAᵀη (Lorentz or rotation).
Mat3 inverse_linear(const Surface& surface, const Mat3& A);

// U(ψ) = [[cos ψ, −sin ψ], [sin ψ, cos ψ]].
Mat2 rotation2(double psi);

}  // namespace spinfold
