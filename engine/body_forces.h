// What acts on a body on a surface whose curvature varies (physics-surfaces.md §5, §13): its mass and
// inertia, a height potential, the deformation potential and Rayleigh friction. Plain data shared by
// the chart (revolution_chart.h) and the chart-free equations (embedded_dynamics.h).
#pragma once

#include "engine/inertia.h"
#include "engine/scene.h"

namespace spinfold {

// V_h(z) [energy] and dV_h/dz [energy/length] for a body of mass m.
double height_energy(const HeightPotential& height, double mass, double z);
double height_slope(const HeightPotential& height, double mass, double z);

struct SurfaceBody {
  double mass = 1.0;  // m [mass]
  Inertia inertia;    // J^{AB}
  HeightPotential height;
  DeformationPotential deformation;  // abc or polar (physics.md §5), rotation invariant
  Friction friction;
};

}  // namespace spinfold
