// Closed-form solution of the separable scenes: no stepping, the state at any t costs the same.
// Covers the radial potential (or none) with the abc deformation potential (or none), for rigid
// and affine bodies on S², H² and the plane: physics.md §8.6 (chart-free, through the poles) when
// V_r = 0, §8.2 with §8.9 in the scene's chart when V_r > 0 (its barrier keeps the body off the
// poles), and §8.3/§8.4 for the internal motion.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "engine/chart.h"
#include "engine/scene.h"
#include "engine/state.h"

namespace spinfold {

// Exact motion of w ∈ ℝ² under the Lagrangian J|ẇ|² − A/(2|w|²) − 2C|w|²: one plane of the
// internal matrix ((u, v) with A, or (p, q) with B; physics.md §2, §8.3). |w|² is harmonic in time
// and the angle follows from ∫dt/|w|² in the closed forms of §8.4.
struct PlaneMotion {
  double J = 1.0, A = 0.0, C = 0.0;
  Eigen::Vector2d w0, w_dot0;
  // Derived at construction.
  double energy = 0.0;  // J|ẇ|² + A/(2s) + 2Cs
  double ell = 0.0;     // 2J(w × ẇ): ψ̇ = ℓ/(2Js)
  double s0 = 0.0, s_dot0 = 0.0, psi0 = 0.0;
};
PlaneMotion plane_motion(double J, double A, double C, const Eigen::Vector2d& w0,
                         const Eigen::Vector2d& w_dot0);
// w(t) and ẇ(t).
std::pair<Eigen::Vector2d, Eigen::Vector2d> plane_motion_at(const PlaneMotion& motion, double t);

// The internal motion at a fixed point without drive (physics.md §8.3: flat space, isotropic J) from
// (L₀, M₀ = L̇₀) under J‖M‖²/2 + V_abc: L(t) and L̇(t). Where the curvature varies it is the internal
// motion in a parallel-transported frame (physics-surfaces.md §4, decoupling).
std::pair<Mat2, Mat2> flat_internal_motion(double J, const AbcPotential& abc, const Mat2& L, const Mat2& M,
                                           double t);

// The exact flow for time t of the integrable part of H (physics.md §8.6): the orbit's isometry
// flow MᵀηM/(2mR²), the body-frame rotation −σs²/(2mR²) and the internal motion at a fixed point
// under J‖M‖²/2 + V_abc (`internal`; zero for a free body). `start` may be in any chart's embedding
// coordinates (the flow commutes with isometries); the result is in the same coordinates.
BodyKinematics integrable_flow(const Scene& scene, const AbcPotential& internal, const BodyKinematics& start,
                               double t);

// The orbit under a radial potential in the scene's chart (physics.md §8.2; §8.9 on the plane):
// u = C(r) is harmonic in time, φ and the frame's drive angle D follow from ∫dt/(1 ∓ u).
struct RadialOrbit {
  double r0 = 0.0, phi0 = 0.0, r_dot0 = 0.0;
  double p_phi = 0.0, spin = 0.0, energy = 0.0;  // conserved: p_φ, s, E_orb
  double strength = 0.0;                         // Γ = V_r S² (physics.md §5)
  double Lambda = 0.0, u_c = 0.0;                // ü = −Λu + K²p_φ s/m², u_c its centre
};

struct ExactSolution {
  Scene scene;
  BodyKinematics initial;  // in the scene's embedding coordinates
  // The initial state's chart and the body in its coordinates. Without a radial potential the
  // state at t is this local body in the chart moved by the orbit's isometry G(t): the e^{r/R}
  // growth far out on H² stays in the chart and never cancels in the body's coordinates.
  Chart chart0;
  BodyKinematics local0;
  double theta0 = 0.0;                // rigid body: the frame angle θ at the start in the scene's chart
  AbcPotential internal;              // the scene's abc potential, or zero
  std::optional<RadialOrbit> radial;  // set when the scene has a radial potential with g > 0
};

// The reason a scene has no closed form here, or nullopt when it has one.
std::optional<std::string> exact_unsupported_reason(const Scene& scene);

// Prepares the closed form from the scene's initial state (the scene must be supported).
ExactSolution make_exact_solution(const Scene& scene);

// The same from a state of a run under this scene's parameters (after a change of them): t = 0
// of the solution is that state's moment. The body must not be at the scene's pole when the
// scene has a radial potential (its barrier keeps it off).
ExactSolution make_exact_solution(const Scene& scene, const State& start);

// The state at time t [time], in a well-conditioned chart.
State exact_state(const ExactSolution& solution, double t);

// The times τ in (t0, t1] [time, the solution's own] at which det L changes sign, oldest first:
// the roots of det L(τ) = |w_pq(τ)|² − |w_uv(τ)|², a trigonometric, hyperbolic or quadratic
// function of τ (physics.md §8.3; L + τM for a free anisotropic body), solved in closed form, so the
// crossings do not depend on where the run is sampled. None for the rigid body. At most `max_count`
// of them, the oldest (a breathing body crosses twice a period: a jump of 10⁹ would list ~10⁹).
std::vector<double> degenerate_times(const ExactSolution& solution, double t0, double t1,
                                     std::size_t max_count = std::numeric_limits<std::size_t>::max());

}  // namespace spinfold
