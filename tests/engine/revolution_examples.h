// physics-surfaces.md §11's WS1 as the surface tests build it (revolution_chart_test,
// embedded_dynamics_test): torus a = 1, c = 3; m = 2, J = [[0.6, 0.1], [0.1, 0.4]], gravity 0.5,
// abc (0.01, 0.02, 0.2); the generalised state u = 0.7, φ = 0.3, L, u̇, φ̇, L̇.
#pragma once

#include <Eigen/SVD>
#include <cmath>
#include <string>
#include <utility>

#include "engine/revolution_chart.h"
#include "engine/scene.h"
#include "tests/engine/test_support.h"

namespace spinfold::test {

// The symmetric J^{AB} = [[J11, J12], [J12, J22]] as the dynamics use it.
inline Inertia inertia_matrix(double J11, double J12, double J22) {
  Body body;
  body.inertia_matrix = InertiaMatrix{J11, J12, J12, J22};
  return inertia_of(body);
}

inline RevolutionModel ws1_model() {
  return {.surface = {.kind = SurfaceKind::torus, .tube_radius = 1.0, .center_radius = 3.0},
          .body = {.mass = 2.0,
                   .inertia = inertia_matrix(0.6, 0.1, 0.4),
                   .height = GravityPotential{0.5},
                   .deformation = AbcPotential{0.01, 0.02, 0.2},
                   .friction = {}}};
}

// A surface of the given kind with every kind's parameters set off their defaults (each kind reads its
// own): the tests that loop over revolution_catalog().
inline RevolutionSurface off_default_surface(SurfaceKind kind) {
  return {.kind = kind,
          .tube_radius = 0.8,
          .center_radius = 2.0,
          .equatorial_radius = 1.5,
          .polar_radius = 0.9,
          .height = 1.2,
          .width = 0.8,
          .neck_radius = 0.7};
}

// §11's WS2: oblate spheroid a = 2, b = 1; rigid m = 1, J = diag(0.5, 0.5), spring k = 0.7.
inline RevolutionModel ws2_model() {
  return {.surface = {.kind = SurfaceKind::spheroid, .equatorial_radius = 2.0, .polar_radius = 1.0},
          .body = {.mass = 1.0,
                   .inertia = inertia_matrix(0.5, 0.0, 0.5),
                   .height = SpringPotential{0.7},
                   .deformation = {},
                   .friction = {}}};
}

inline RevolutionRates ws1_rates() {
  RevolutionRates r;
  r.u = 0.7;
  r.phi = 0.3;
  r.L = matrix(1.2, 0.1, -0.2, 0.9);
  r.u_dot = 0.4;
  r.phi_dot = -0.2;
  r.L_dot = matrix(0.05, 0.3, -0.1, 0.2);
  return r;
}

// WS1's chart-free state Y = [X, V, e₁, e₂, W₁, W₂] (the reference's 30-digit values, rounded).
inline Embedded ws1_state() {
  Embedded Y;
  Y << 3.5966911173123304, 1.1125869412336418, -0.644217687237691, -0.02366047717658104, -0.7954899610894152,
      -0.3059368749137954, -0.6794295549376602, -0.41952251070596835, -0.9178106247413862,
      -0.32751265235103294, 0.8407649058063081, -0.07648421872844885, -0.06277046859916074,
      0.037748273508739924, -0.05795110396399363, -0.17617856648064523, 0.16833862120799897,
      -0.1407621804863851;
  return Y;
}

// L = U(α) diag(λ, μ) U(β)ᵀ and its rates from L and L̇ (physics.md §2), by Eigen's SVD: with
// D = U(α)ᵀ L̇ U(β) = [[λ̇, λβ̇ − μα̇], [λα̇ − μβ̇, μ̇]].
inline void set_internal(InitialState& q, const Mat2& L, const Mat2& L_dot) {
  Eigen::JacobiSVD<Mat2> svd(L, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat2 U = svd.matrixU(), V = svd.matrixV();
  Eigen::Vector2d s = svd.singularValues();
  if (U.determinant() < 0) {  // both rotations: move the sign into μ
    U.col(1) *= -1.0;
    s(1) *= -1.0;
  }
  if (V.determinant() < 0) {
    V.col(1) *= -1.0;
    s(1) *= -1.0;
  }
  q.alpha = std::atan2(U(1, 0), U(0, 0));
  q.beta = std::atan2(V(1, 0), V(0, 0));
  q.lambda = s(0);
  q.mu = s(1);
  const Mat2 D = U.transpose() * L_dot * V;
  q.lambda_dot = D(0, 0);
  q.mu_dot = D(1, 1);
  // [−μ λ; λ −μ] [α̇; β̇] = [D₀₁; D₁₀]
  Mat2 A;
  A << -q.mu, q.lambda, q.lambda, -q.mu;
  const Eigen::Vector2d rates = A.lu().solve(Eigen::Vector2d(D(0, 1), D(1, 0)));
  q.alpha_dot = rates(0);
  q.beta_dot = rates(1);
}

// physics-surfaces.md §11's WS1 as a scene: the torus a = 1, c = 3, m = 2, anisotropic J, gravity 0.5
// and the abc potential, at u = 0.7, φ = 0.3.
inline Scene ws1_scene(std::string integrator = "dop853") {
  Scene s;
  s.surface.kind = SurfaceKind::torus;
  s.surface.tube_radius = 1.0;
  s.surface.center_radius = 3.0;
  s.body.mass = 2.0;
  s.body.inertia_matrix = InertiaMatrix{0.6, 0.1, 0.1, 0.4};
  s.potential.height = GravityPotential{0.5};
  s.potential.deformation = AbcPotential{0.01, 0.02, 0.2};
  const RevolutionRates r = ws1_rates();
  s.initial.u = r.u;
  s.initial.phi = r.phi;
  s.initial.u_dot = r.u_dot;
  s.initial.phi_dot = r.phi_dot;
  set_internal(s.initial, r.L, r.L_dot);
  s.integrator = {std::move(integrator), 0.01, 1e-13};
  return s;
}

}  // namespace spinfold::test
