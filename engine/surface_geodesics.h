// Points and geodesics on an implicit surface F(X) = 0, from F, ∇F and Hess F only (like the
// chart-free equations, embedded_dynamics.h): what drawing a body on a surface whose curvature varies
// needs (its ellipse is exp_X of a circle of frame vectors; a trail's chords are pushed back onto it).
#pragma once

#include "engine/revolution.h"

namespace spinfold {

// A point of the surface near X: Newton's steps along the gradient, X ← X − F ∇F/|∇F|², until the
// step is below 1e-15 of |X| + 1 (at most 16 steps) [length]. For X within a fraction of the
// curvature radius of the surface it lands within rounding of the nearest point's level.
Vec3 project_onto_surface(const ImplicitSurface& surface, const Vec3& X);

// The tangent part of v at X: v − ⟨v, n⟩n with n = ∇F/|∇F|.
Vec3 tangent_part(const ImplicitSurface& surface, const Vec3& X, const Vec3& v);

// exp_X(v) [length]: the geodesic from X (on the surface) with initial velocity v (tangent),
// followed for unit time. The geodesic equation in the embedding, Ẍ = −(VᵀHV/|∇F|²)∇F (§7 with no
// body), by classical RK4 in `steps` equal steps, X projected back onto the surface and V onto its
// tangent plane after each. Its error is O((|v|·κ/steps)⁴) relative (κ: the largest principal
// curvature along the way): 8 steps draw a body's ellipse to within a pixel.
Vec3 implicit_exponential_map(const ImplicitSurface& surface, const Vec3& X, const Vec3& v, int steps = 8);

}  // namespace spinfold
