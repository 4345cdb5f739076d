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
  model.body.height = {HeightPotential::Kind::gravity, 0.5, 0.0};
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

}  // namespace spinfold::test
