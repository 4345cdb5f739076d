#include "engine/embedded_dynamics.h"

#include "engine/potentials.h"

namespace spinfold {
namespace {

struct Local {
  ImplicitPoint p;
  double nu2 = 1.0;  // |∇F|²
  Vec3 n;
  Mat3 Pi;  // I − n nᵀ
};

Local local_at(const ImplicitSurface& surface, const Vec3& X) {
  Local l;
  l.p = surface.at(X);
  l.nu2 = l.p.gradient.squaredNorm();
  l.n = l.p.gradient / std::sqrt(l.nu2);
  l.Pi = Mat3::Identity() - l.n * l.n.transpose();
  return l;
}

// The deformation invariants a = x², b = y² of the frame (§5): (|e₁|² + |e₂|²)/2 ∓ det[e₁, e₂, n].
DeformationEnergy frame_energy(const DeformationPotential& potential, const Vec3& e1, const Vec3& e2,
                               const Vec3& n) {
  const double half = 0.5 * (e1.squaredNorm() + e2.squaredNorm());
  const double det = e1.cross(e2).dot(n);
  return deformation_potential(potential, half - det, half + det);
}

}  // namespace

Vec3 embedded_normal(const ImplicitSurface& surface, const Vec3& X) {
  return surface.at(X).gradient.normalized();
}

void embedded_vector_field(const EmbeddedModel& model, const Embedded& Y, Embedded& dYdt) {
  const SurfaceBody& body = model.body;
  const Vec3 X = Y.segment<3>(embedded::X), V = Y.segment<3>(embedded::V);
  const Vec3 e[2] = {Y.segment<3>(embedded::e1), Y.segment<3>(embedded::e2)};
  const Vec3 W[2] = {Y.segment<3>(embedded::W1), Y.segment<3>(embedded::W2)};
  const Local l = local_at(model.surface, X);
  const Mat3& H = l.p.hessian;
  const Vec3& g = l.p.gradient;
  const double nu = std::sqrt(l.nu2);
  const Mat3 Dn = l.Pi * H / nu;  // the derivative of the unit normal field
  const Mat3 DnT = Dn.transpose();
  const Vec3 DnV = Dn * V;
  const Mat2& J = body.inertia.matrix;
  const Mat2& Jinv = body.inertia.inverse;

  // The spin–curvature force, the bracket of §7 (never needs K or s, nor the sign of n).
  Vec3 force = Vec3::Zero();
  for (int A = 0; A < 2; ++A)
    for (int B = 0; B < 2; ++B) force += J(A, B) * (DnT * W[A] * e[B].dot(DnV) - DnT * e[A] * W[B].dot(DnV));
  force -= height_slope(body.height, body.mass, X.z()) * Vec3::UnitZ();
  force -= body.friction.translational * V;

  dYdt.segment<3>(embedded::X) = V;
  dYdt.segment<3>(embedded::V) = l.Pi * force / body.mass - (V.dot(H * V) / l.nu2) * g;

  // ∂V_def/∂e₁ = V_a(e₁ − e₂ × n) + V_b(e₁ + e₂ × n), ∂V_def/∂e₂ = V_a(e₂ − n × e₁) + V_b(e₂ + n × e₁).
  Vec3 pull[2] = {body.friction.internal * W[0], body.friction.internal * W[1]};
  if (!std::holds_alternative<std::monostate>(body.deformation)) {
    const DeformationEnergy d = frame_energy(body.deformation, e[0], e[1], l.n);
    const Vec3 e2xn = e[1].cross(l.n), nxe1 = l.n.cross(e[0]);
    pull[0] += d.dV_da * (e[0] - e2xn) + d.dV_db * (e[0] + e2xn);
    pull[1] += d.dV_da * (e[1] - nxe1) + d.dV_db * (e[1] + nxe1);
  }
  const Vec3 HV = H * V;
  for (int A = 0; A < 2; ++A) {
    dYdt.segment<3>(embedded::e1 + 3 * A) = W[A] - (e[A].dot(HV) / l.nu2) * g;
    dYdt.segment<3>(embedded::W1 + 3 * A) =
        -l.Pi * (Jinv(A, 0) * pull[0] + Jinv(A, 1) * pull[1]) - (W[A].dot(HV) / l.nu2) * g;
  }
}

namespace {

// dV/dt of a body of constant spin s (§7 with §4's force K s n × V, K from the bordered Hessian).
Vec3 orbit_acceleration(const SurfaceBody& body, const Local& l, const Vec3& X, const Vec3& V, const Vec3& HV,
                        double s) {
  const double K = bordered_hessian_curvature(l.p);
  const Vec3 push =
      height_slope(body.height, body.mass, X.z()) * Vec3::UnitZ() + body.friction.translational * V;
  return (K * s * l.n.cross(V) - l.Pi * push) / body.mass - (V.dot(HV) / l.nu2) * l.p.gradient;
}

}  // namespace

void embedded_rigid_vector_field(const EmbeddedModel& model, const EmbeddedRigid& Y, EmbeddedRigid& dYdt) {
  const SurfaceBody& body = model.body;
  const Vec3 X = Y.segment<3>(embedded::X), V = Y.segment<3>(embedded::V), e1 = Y.segment<3>(embedded::e1);
  const double s = Y(embedded::spin);
  const Local l = local_at(model.surface, X);
  const Vec3 HV = l.p.hessian * V;
  const double lambda2 = e1.squaredNorm();
  const double I = lambda2 * body.inertia.matrix.trace();
  dYdt.segment<3>(embedded::X) = V;
  dYdt.segment<3>(embedded::V) = orbit_acceleration(body, l, X, V, HV, s);
  dYdt.segment<3>(embedded::e1) = (s / I) * l.n.cross(e1) - (e1.dot(HV) / l.nu2) * l.p.gradient;
  dYdt(embedded::spin) = -2.0 * body.friction.internal * lambda2 / I * s;
}

void embedded_orbit_vector_field(const EmbeddedModel& model, double s, const EmbeddedOrbit& Y,
                                 EmbeddedOrbit& dYdt) {
  const Vec3 X = Y.segment<3>(embedded_orbit::X), V = Y.segment<3>(embedded_orbit::V);
  const Vec3 E = Y.segment<3>(embedded_orbit::E);
  const Local l = local_at(model.surface, X);
  const Vec3 HV = l.p.hessian * V;
  dYdt.segment<3>(embedded_orbit::X) = V;
  dYdt.segment<3>(embedded_orbit::V) = orbit_acceleration(model.body, l, X, V, HV, s);
  dYdt.segment<3>(embedded_orbit::E) = -(E.dot(HV) / l.nu2) * l.p.gradient;
  dYdt(embedded_orbit::tau) = 1.0;
}

double embedded_spin(const EmbeddedModel& model, const Embedded& Y) {
  const Vec3 n = embedded_normal(model.surface, Y.segment<3>(embedded::X));
  const Mat2& J = model.body.inertia.matrix;
  double s = 0.0;
  for (int A = 0; A < 2; ++A)
    for (int B = 0; B < 2; ++B)
      s += J(A, B) * Y.segment<3>(embedded::e1 + 3 * A).cross(Y.segment<3>(embedded::W1 + 3 * B)).dot(n);
  return s;
}

double embedded_det_L(const EmbeddedModel& model, const Embedded& Y) {
  const Vec3 n = embedded_normal(model.surface, Y.segment<3>(embedded::X));
  return Y.segment<3>(embedded::e1).cross(Y.segment<3>(embedded::e2)).dot(n);
}

EmbeddedEnergy embedded_energy(const EmbeddedModel& model, const Embedded& Y) {
  const SurfaceBody& body = model.body;
  const Vec3 X = Y.segment<3>(embedded::X);
  const Vec3 e1 = Y.segment<3>(embedded::e1), e2 = Y.segment<3>(embedded::e2);
  const Vec3 W[2] = {Y.segment<3>(embedded::W1), Y.segment<3>(embedded::W2)};
  const Mat2& J = body.inertia.matrix;
  EmbeddedEnergy E;
  E.orbital = 0.5 * body.mass * Y.segment<3>(embedded::V).squaredNorm() +
              height_energy(body.height, body.mass, X.z());
  double kinetic = 0.0;
  for (int A = 0; A < 2; ++A)
    for (int B = 0; B < 2; ++B) kinetic += J(A, B) * W[A].dot(W[B]);
  E.deformation = 0.5 * kinetic;
  if (!std::holds_alternative<std::monostate>(body.deformation))
    E.deformation += frame_energy(body.deformation, e1, e2, embedded_normal(model.surface, X)).value;
  return E;
}

double embedded_rigid_energy(const EmbeddedModel& model, const EmbeddedRigid& Y) {
  const SurfaceBody& body = model.body;
  const double I = Y.segment<3>(embedded::e1).squaredNorm() * body.inertia.matrix.trace();
  const double s = Y(embedded::spin);
  return 0.5 * body.mass * Y.segment<3>(embedded::V).squaredNorm() + s * s / (2.0 * I) +
         height_energy(body.height, body.mass, Y(embedded::X + 2));
}

double embedded_axial_momentum(const EmbeddedModel& model, const Embedded& Y) {
  const Vec3 X = Y.segment<3>(embedded::X), V = Y.segment<3>(embedded::V);
  return model.body.mass * X.cross(V).z() + embedded_spin(model, Y) * embedded_normal(model.surface, X).z();
}

double embedded_rayleigh(const EmbeddedModel& model, const Embedded& Y) {
  const Friction& f = model.body.friction;
  return 0.5 * f.translational * Y.segment<3>(embedded::V).squaredNorm() +
         0.5 * f.internal *
             (Y.segment<3>(embedded::W1).squaredNorm() + Y.segment<3>(embedded::W2).squaredNorm());
}

}  // namespace spinfold
