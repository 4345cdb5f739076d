// Which way a path on the surface bends, as a class sees it drawn: the signed geodesic curvature
// κ_g of a sampled path (the spinning body's is K s/(m v) with no other force, physics-surfaces.md
// §5: it changes sign with K on the torus), positive where the path turns left seen from the side
// the surface's normal points to (outside a closed surface, above a graph and the plane).
#pragma once

#include <span>
#include <vector>

#include "engine/surface_model.h"

namespace spinfold {

// The unit normal at X on the surface [1]: ∇F/|∇F| where the model has an F, X/R on S² and H² (the
// Minkowski normal), ẑ on the plane.
Vec3 surface_normal(const SurfaceModel& surface, const Vec3& X);

// K at X [1/length²]: σ/R² where it is constant, else from F's bordered Hessian.
double curvature_at(const SurfaceModel& surface, const Vec3& X);

// κ_g [1/length] at each point of the path (embedding coordinates, consecutive samples): at an
// interior point the tangential part of the curvature of the circle through it and its neighbours,
// 2 det[n, a, b] / (|a| |b| |a + b|) with a, b the chords before and after it and n the unit normal
// there (the normal part of a chord drops out of the determinant); the ends take their neighbour's.
// Lengths are the surface's (Minkowski on H²). A repeated point (a paused trail) gives 0 there. Its
// error is O(κ' |a|) for a smooth path: a sample per tenth of the feature length reads κ_g to ~1 %.
std::vector<double> geodesic_curvatures(const SurfaceModel& surface, std::span<const Vec3> path);

}  // namespace spinfold
