// Helpers shared by the engine tests: scene builders, running, exact isometry flows.
#pragma once

#include <cmath>
#include <cstring>

#include "engine/chart.h"
#include "engine/invariants.h"
#include "engine/scene.h"
#include "engine/simulation.h"
#include "engine/worked_examples.h"

namespace spinfold::test {

// The 2×2 matrix [[a, b], [c, d]].
inline Mat2 matrix(double a, double b, double c, double d) {
  Mat2 m;
  m << a, b, c, d;
  return m;
}

inline Scene rigid_scene(SurfaceKind kind, double R, double m, double J, double lambda0) {
  Scene s;
  s.surface = {kind, R};
  s.body = {m, J, BodyModel::rigid};
  s.initial.lambda = s.initial.mu = lambda0;
  s.integrator = {"dop853", 0.01, 1e-13};
  return s;
}

// Sets the initial velocity to speed v along the angle `heading` from E₁ (0: outwards) and the
// spin to s, for a rigid body (θ̇ from s = 2Jλ₀²(θ̇ + Cφ̇)).
inline void set_rigid_motion(Scene& s, double v, double heading, double spin) {
  const double S = polar_S(s.surface, s.initial.r), C = polar_C(s.surface, s.initial.r);
  s.initial.r_dot = v * std::cos(heading);
  s.initial.phi_dot = v * std::sin(heading) / S;
  const double l0 = s.initial.lambda;
  s.initial.alpha_dot = spin / (2.0 * s.body.inertia * l0 * l0) - C * s.initial.phi_dot;
  s.initial.beta_dot = 0.0;
}

// A free affine body whose covariant rate is M = diag(0, −0.6): relative to parallel transport
// det L = 0.3 − 0.6t, so the frame is squashed to a segment at t = 0.5 (physics.md §2).
inline Scene degenerate_crossing_scene() {
  Scene s;
  s.surface = {SurfaceKind::sphere, 1.0};
  s.body = {1.0, 0.1, BodyModel::affine};
  s.initial.r = 1.2;
  s.initial.lambda = 1.0;
  s.initial.mu = 0.3;
  s.initial.phi_dot = 0.4;
  s.initial.mu_dot = -0.6;
  s.initial.alpha_dot = -std::cos(1.2) * 0.4;  // cancels the chart frame's rotation Cφ̇
  return s;
}

using spinfold::w5_scene;  // engine/worked_examples.h

// Two states with the same time, chart, coordinates (bit for bit) and status.
inline bool same_bits(const State& a, const State& b) {
  return a.t == b.t && a.y.size() == b.y.size() &&
         std::memcmp(a.y.data(), b.y.data(), sizeof(double) * a.y.size()) == 0 && a.chart.A == b.chart.A &&
         a.chart.b == b.chart.b && a.status == b.status;
}

inline Simulation run_to(const Scene& scene, double t) {
  Simulation run = start_simulation(scene);
  advance_to(run, t);
  return run;
}

// exp(tA) with A w = η((ηM) × w)/(mR²): the orbital isometry flow of a body with V_r = 0
// (physics.md §8.6). Uses A³ = −cA.
inline Mat3 isometry_flow(const Surface& surface, const Vec3& M, double m, double t) {
  const double R = surface.radius;
  const Vec3 etaM = raise(surface, M);
  Mat3 A;
  for (int i = 0; i < 3; ++i) A.col(i) = raise(surface, etaM.cross(Vec3::Unit(i))) / (m * R * R);
  const double c = -(A * A).trace() / 2.0;
  const Mat3 I = Mat3::Identity();
  if (c > 0.0) {
    const double k = std::sqrt(c);
    return I + (std::sin(k * t) / k) * A + ((1.0 - std::cos(k * t)) / c) * A * A;
  }
  if (c < 0.0) {
    const double k = std::sqrt(-c);
    return I + (std::sinh(k * t) / k) * A + ((std::cosh(k * t) - 1.0) / (-c)) * A * A;
  }
  return I + t * A + 0.5 * t * t * A * A;
}

}  // namespace spinfold::test
