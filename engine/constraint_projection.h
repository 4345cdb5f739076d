// The chart-free state brought back onto its constraint manifold after an accepted step
// (physics-anysurface.md §3, §8): X onto F = 0 by Newton along ∇F, then V, e_A and W_A onto the tangent
// plane at the new X (the rigid body's e₁ also back to its length λ₀). The flow keeps these
// constraints exactly; a step keeps them to its tolerance, and the drift grows linearly. Never inside
// a step: it would spoil the error estimate. For any ImplicitSurface: nothing here asks what it is.
#pragma once

#include "engine/embedded_dynamics.h"

namespace spinfold {

// How far a state is off its constraints: the distance from the surface |F|/|∇F| [length], and the
// largest normal part max |⟨u, n⟩| of u = V, e₁, e₂, W₁, W₂ (the rigid body: V, e₁) [their units].
struct ConstraintResidual {
  double distance = 0.0;
  double tangency = 0.0;
};
ConstraintResidual constraint_residual(const ImplicitSurface& surface, const Embedded& Y);
ConstraintResidual constraint_residual(const ImplicitSurface& surface, const EmbeddedRigid& Y);

// Two Newton steps X ← X − F∇F/|∇F|² (from a drift of the tolerance's size, the second leaves
// round-off), then u ← Πu with Π = I − n nᵀ at the new X for every vector of the state.
void project_onto_constraints(const ImplicitSurface& surface, Embedded& Y);
// The same for the rigid body, and e₁ rescaled to |e₁| = λ₀ (the spin s is not constrained).
void project_onto_constraints(const ImplicitSurface& surface, EmbeddedRigid& Y, double lambda0);

}  // namespace spinfold
