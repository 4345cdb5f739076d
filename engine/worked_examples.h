// physics.md §10's worked example W5 as a scene, and its incompressible variant (§13): the start that
// the engine tests, the benchmarks and the stress runs build on. Plain data; no integrator is chosen.
#pragma once

#include "engine/scene.h"

namespace spinfold {

// W5 (the preset separable_radial_abc): sphere R = 1.5 [length], m = 1 [mass], J = 0.4
// [mass·length²], radial potential k = 0.05 and abc (0.02, 0.4, 0.3) [energy], started at r = 1.2.
inline Scene w5_scene() {
  Scene s;
  s.surface = {SurfaceKind::sphere, 1.5};
  s.body = {1.0, 0.4, BodyModel::affine};
  s.potential.radial = RadialPotential{0.05};
  s.potential.deformation = AbcPotential{0.02, 0.4, 0.3};
  s.initial = {1.2, 0.0, 0.0, 0.0, 1.1, 0.6, 0.1, 0.4, 0.5, 0.2, 0.0, 0.05};
  return s;
}

// W5's potentials with an incompressible breathing ellipse: det L = 1.1·0.6 = 0.66 and
// λ̇μ + λμ̇ = 0 at the start (physics.md §13).
inline Scene incompressible_w5_scene() {
  Scene s = w5_scene();
  s.body.model = BodyModel::incompressible;
  s.initial.lambda_dot = 0.3;
  s.initial.mu_dot = -s.initial.lambda_dot * s.initial.mu / s.initial.lambda;
  return s;
}

}  // namespace spinfold
