// Formula surfaces as the tests write them (engine, render and codec tests): a scene's Surface given
// by F or by a graph's z, and Joachimsthal's integral of the triaxial ellipsoid, the claim the
// ellipsoid's tests check.
#pragma once

#include <cmath>
#include <string>

#include "engine/surface.h"

namespace spinfold::test {

inline Surface implicit_surface(const std::string& F, SurfaceParameters parameters = {}) {
  Surface s;
  s.kind = SurfaceKind::implicit;
  s.F = F;
  s.parameters = std::move(parameters);
  return s;
}

inline Surface graph_surface(const std::string& z, SurfaceParameters parameters = {}) {
  Surface s;
  s.kind = SurfaceKind::graph;
  s.z = z;
  s.parameters = std::move(parameters);
  return s;
}

// Joachimsthal's integral p·D on x²/a² + y²/b² + z²/c² = 1 at X moving along V: p the distance from
// the centre to the tangent plane, D the semi-diameter parallel to V. Constant along a geodesic.
inline double joachimsthal_integral(const Vec3& X, const Vec3& V, double a, double b, double c) {
  const Vec3 t = V.normalized();
  const double p = 1.0 / std::sqrt(X.x() * X.x() / std::pow(a, 4) + X.y() * X.y() / std::pow(b, 4) +
                                   X.z() * X.z() / std::pow(c, 4));
  const double D =
      1.0 / std::sqrt(t.x() * t.x() / (a * a) + t.y() * t.y() / (b * b) + t.z() * t.z() / (c * c));
  return p * D;
}

}  // namespace spinfold::test
