#include "engine/constraint_projection.h"

#include <algorithm>
#include <cmath>

namespace spinfold {

namespace {

Vec3 newton_onto(const ImplicitSurface& surface, Vec3 X) {
  for (int i = 0; i < 2; ++i) {
    const ImplicitPoint p = surface.at(X);
    const double g2 = p.gradient.squaredNorm();
    if (!(g2 > 0.0) || !std::isfinite(p.F)) break;  // a singular or undefined point: the run's checks stop it
    X -= (p.F / g2) * p.gradient;
  }
  return X;
}

double distance_of(const ImplicitSurface& surface, const Vec3& X) {
  const ImplicitPoint p = surface.at(X);
  return std::abs(p.F) / p.gradient.norm();
}

}  // namespace

ConstraintResidual constraint_residual(const ImplicitSurface& surface, const Embedded& Y) {
  const Vec3 X = Y.segment<3>(embedded::X);
  const Vec3 n = embedded_normal(surface, X);
  ConstraintResidual r{distance_of(surface, X), 0.0};
  for (int at : {embedded::V, embedded::e1, embedded::e2, embedded::W1, embedded::W2})
    r.tangency = std::max(r.tangency, std::abs(n.dot(Y.segment<3>(at))));
  return r;
}

ConstraintResidual constraint_residual(const ImplicitSurface& surface, const EmbeddedRigid& Y) {
  const Vec3 X = Y.segment<3>(embedded::X);
  const Vec3 n = embedded_normal(surface, X);
  return {distance_of(surface, X),
          std::max(std::abs(n.dot(Y.segment<3>(embedded::V))), std::abs(n.dot(Y.segment<3>(embedded::e1))))};
}

void project_onto_constraints(const ImplicitSurface& surface, Embedded& Y) {
  const Vec3 X = newton_onto(surface, Y.segment<3>(embedded::X));
  Y.segment<3>(embedded::X) = X;
  const Vec3 n = embedded_normal(surface, X);
  for (int at : {embedded::V, embedded::e1, embedded::e2, embedded::W1, embedded::W2}) {
    const Vec3 u = Y.segment<3>(at);
    Y.segment<3>(at) = u - n.dot(u) * n;
  }
}

void project_onto_constraints(const ImplicitSurface& surface, EmbeddedRigid& Y, double lambda0) {
  const Vec3 X = newton_onto(surface, Y.segment<3>(embedded::X));
  Y.segment<3>(embedded::X) = X;
  const Vec3 n = embedded_normal(surface, X);
  const Vec3 V = Y.segment<3>(embedded::V), e = Y.segment<3>(embedded::e1);
  Y.segment<3>(embedded::V) = V - n.dot(V) * n;
  const Vec3 tangent = e - n.dot(e) * n;
  Y.segment<3>(embedded::e1) = (lambda0 / tangent.norm()) * tangent;
}

}  // namespace spinfold
