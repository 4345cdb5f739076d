// physics-surfaces.md §11's WS1 as the surface tests build it (revolution_chart_test,
// embedded_dynamics_test): torus a = 1, c = 3; m = 2, J = [[0.6, 0.1], [0.1, 0.4]], gravity 0.5,
// abc (0.01, 0.02, 0.2); the generalised state u = 0.7, φ = 0.3, L, u̇, φ̇, L̇.
#pragma once

#include "engine/revolution_chart.h"
#include "tests/engine/test_support.h"

namespace spinfold::test {

// The symmetric J^{AB} = [[J11, J12], [J12, J22]] as the dynamics use it.
inline Inertia inertia_matrix(double J11, double J12, double J22) {
  Body body;
  body.inertia_matrix = InertiaMatrix{J11, J12, J12, J22};
  return inertia_of(body);
}

inline RevolutionModel ws1_model() {
  RevolutionModel model;
  model.surface.kind = RevolutionKind::torus;
  model.surface.tube_radius = 1.0;
  model.surface.center_radius = 3.0;
  model.body.mass = 2.0;
  model.body.inertia = inertia_matrix(0.6, 0.1, 0.4);
  model.body.height = GravityPotential{0.5};
  model.body.deformation = AbcPotential{0.01, 0.02, 0.2};
  return model;
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

}  // namespace spinfold::test
