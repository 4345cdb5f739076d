// What acts on a body on a surface whose curvature varies (physics-surfaces.md §5, §13): its mass and
// inertia, a height potential, the deformation potential and Rayleigh friction. Plain data shared by
// the chart (revolution_chart.h) and the chart-free equations (embedded_dynamics.h).
#pragma once

#include "engine/inertia.h"
#include "engine/scene.h"

namespace spinfold {

// V_h as a function of the embedded height z (§5): gravity m g z, spring k z²/2 (towards z = 0).
struct HeightPotential {
  enum class Kind { none, gravity, spring };
  Kind kind = Kind::none;
  double g = 0.0;  // [length/time²] (gravity)
  double k = 0.0;  // [energy/length²] (spring)
};

// V_h(z) [energy] and dV_h/dz [energy/length] for a body of mass m.
double height_energy(const HeightPotential& height, double mass, double z);
double height_slope(const HeightPotential& height, double mass, double z);

// Rayleigh's R = γ_t/2 |V|² + γ_i/2 Σ_A |W_A|² (W_A = De_A/Dt: damping relative to parallel
// transport, §13). Zero: no friction, and the flow is Hamiltonian.
struct Friction {
  double translational = 0.0;  // γ_t [mass/time]
  double internal = 0.0;       // γ_i [mass·length²/time]
  bool any() const { return translational != 0.0 || internal != 0.0; }
};

struct SurfaceBody {
  double mass = 1.0;  // m [mass]
  Inertia inertia;    // J^{AB}
  HeightPotential height;
  DeformationPotential deformation;  // abc or polar (physics.md §5), rotation invariant
  Friction friction;
};

}  // namespace spinfold
