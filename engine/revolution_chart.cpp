#include "engine/revolution_chart.h"

#include <cmath>

#include "engine/dynamics.h"
#include "engine/potentials.h"

namespace spinfold {
namespace {

Mat2 block(const RevolutionCoords& w, int at) {
  Mat2 m;
  m << w(at), w(at + 1), w(at + 2), w(at + 3);
  return m;
}

void set_block(RevolutionCoords& w, int at, const Mat2& m) {
  w(at) = m(0, 0);
  w(at + 1) = m(0, 1);
  w(at + 2) = m(1, 0);
  w(at + 3) = m(1, 1);
}

struct ChartLocal {
  ProfilePoint p;
  ProfileMetric m;
};

ChartLocal chart_local(const RevolutionSurface& surface, double u) {
  ChartLocal c;
  c.p = revolution_entry(surface.kind).profile(surface, u);
  c.m = profile_metric(c.p);
  return c;
}

}  // namespace

double revolution_spin(const RevolutionCoords& w) {
  return (epsilon() * block(w, revolution_coord::L)).cwiseProduct(block(w, revolution_coord::P)).sum();
}

RevolutionCoords revolution_coords(const RevolutionModel& model, const RevolutionRates& rates) {
  const ChartLocal c = chart_local(model.surface, rates.u);
  const double m = model.body.mass;
  const Mat2 M = rates.L_dot + c.m.C * rates.phi_dot * epsilon() * rates.L;
  const Mat2 P = momentum_from_rate(model.body.inertia, M);
  RevolutionCoords w;
  w(revolution_coord::u) = rates.u;
  w(revolution_coord::phi) = rates.phi;
  set_block(w, revolution_coord::L, rates.L);
  set_block(w, revolution_coord::P, P);
  const double s = revolution_spin(w);
  w(revolution_coord::p_u) = m * c.m.f * c.m.f * rates.u_dot;
  w(revolution_coord::p_phi) = m * c.p.rho * c.p.rho * rates.phi_dot + c.m.C * s;
  return w;
}

EmbeddedEnergy revolution_energy(const RevolutionModel& model, const RevolutionCoords& w) {
  const SurfaceBody& body = model.body;
  const ChartLocal c = chart_local(model.surface, w(revolution_coord::u));
  const double m = body.mass, f = c.m.f, rho = c.p.rho;
  const double Pi = w(revolution_coord::p_phi) - c.m.C * revolution_spin(w);
  const double p_u = w(revolution_coord::p_u);
  EmbeddedEnergy E;
  E.orbital =
      p_u * p_u / (2.0 * m * f * f) + Pi * Pi / (2.0 * m * rho * rho) + height_energy(body.height, m, c.p.z);
  const Mat2 L = block(w, revolution_coord::L);
  E.deformation = internal_kinetic_energy(body.inertia, block(w, revolution_coord::P));
  if (!std::holds_alternative<std::monostate>(body.deformation)) {
    const DeformationInvariants d = deformation_invariants(L);
    E.deformation += deformation_potential(body.deformation, d.a, d.b).value;
  }
  return E;
}

void revolution_vector_field(const RevolutionModel& model, const RevolutionCoords& w,
                             RevolutionCoords& dwdt) {
  const SurfaceBody& body = model.body;
  const ChartLocal c = chart_local(model.surface, w(revolution_coord::u));
  const double m = body.mass, f = c.m.f, rho = c.p.rho, C = c.m.C;
  const Mat2 L = block(w, revolution_coord::L), P = block(w, revolution_coord::P);
  const Mat2 eps = epsilon();
  const double s = (eps * L).cwiseProduct(P).sum();
  const double p_u = w(revolution_coord::p_u);
  const double Pi = w(revolution_coord::p_phi) - C * s;
  const double u_dot = p_u / (m * f * f);
  const double phi_dot = Pi / (m * rho * rho);
  const Mat2 M = rate_from_momentum(body.inertia, P);

  Mat2 P_dot = -C * phi_dot * eps * P - body.friction.internal * M;
  if (!std::holds_alternative<std::monostate>(body.deformation)) {
    const DeformationInvariants d = deformation_invariants(L);
    P_dot -= deformation_gradient(deformation_potential(body.deformation, d.a, d.b), L);
  }
  dwdt(revolution_coord::u) = u_dot;
  dwdt(revolution_coord::phi) = phi_dot;
  set_block(dwdt, revolution_coord::L, M - C * phi_dot * eps * L);
  set_block(dwdt, revolution_coord::P, P_dot);
  dwdt(revolution_coord::p_u) =
      p_u * p_u * c.m.f_u / (m * f * f * f) + Pi * Pi * c.p.rho_u / (m * rho * rho * rho) +
      c.m.C_u * s * Pi / (m * rho * rho) - height_slope(body.height, m, c.p.z) * c.p.z_u -
      body.friction.translational * p_u / m;
  dwdt(revolution_coord::p_phi) = -body.friction.translational * rho * rho * phi_dot -
                                  body.friction.internal * C * (eps * L).cwiseProduct(M).sum();
}

void revolution_rigid_vector_field(const RevolutionModel& model, double lambda0,
                                   const RevolutionRigidCoords& w, RevolutionRigidCoords& dwdt) {
  const SurfaceBody& body = model.body;
  const ChartLocal c = chart_local(model.surface, w(revolution_coord::u));
  const double m = body.mass, f = c.m.f, rho = c.p.rho, C = c.m.C;
  const double I = lambda0 * lambda0 * body.inertia.matrix.trace();
  const double s = w(revolution_coord::spin), p_u = w(revolution_coord::rigid_p_u);
  const double Pi = w(revolution_coord::rigid_p_phi) - C * s;
  const double phi_dot = Pi / (m * rho * rho);
  const double s_dot = -2.0 * body.friction.internal * lambda0 * lambda0 / I * s;
  dwdt(revolution_coord::u) = p_u / (m * f * f);
  dwdt(revolution_coord::phi) = phi_dot;
  dwdt(revolution_coord::theta) = s / I - C * phi_dot;
  dwdt(revolution_coord::rigid_p_u) =
      p_u * p_u * c.m.f_u / (m * f * f * f) + Pi * Pi * c.p.rho_u / (m * rho * rho * rho) +
      c.m.C_u * s * Pi / (m * rho * rho) - height_slope(body.height, m, c.p.z) * c.p.z_u -
      body.friction.translational * p_u / m;
  dwdt(revolution_coord::rigid_p_phi) = -body.friction.translational * rho * rho * phi_dot + C * s_dot;
  dwdt(revolution_coord::spin) = s_dot;
}

Embedded embed(const RevolutionModel& model, const RevolutionCoords& w) {
  const double u = w(revolution_coord::u), phi = w(revolution_coord::phi);
  const ChartLocal c = chart_local(model.surface, u);
  const RevolutionFrame frame = revolution_frame(model.surface, u, phi);
  const double m = model.body.mass;
  const double Pi = w(revolution_coord::p_phi) - c.m.C * revolution_spin(w);
  const Mat2 L = block(w, revolution_coord::L);
  const Mat2 M = rate_from_momentum(model.body.inertia, block(w, revolution_coord::P));
  Embedded Y;
  Y.segment<3>(embedded::X) = frame.X;
  Y.segment<3>(embedded::V) =
      (w(revolution_coord::p_u) / (m * c.m.f)) * frame.E1 + (Pi / (m * c.p.rho)) * frame.E2;
  for (int A = 0; A < 2; ++A) {
    Y.segment<3>(embedded::e1 + 3 * A) = L(0, A) * frame.E1 + L(1, A) * frame.E2;
    Y.segment<3>(embedded::W1 + 3 * A) = M(0, A) * frame.E1 + M(1, A) * frame.E2;
  }
  return Y;
}

EmbeddedRigid embed_rigid(const RevolutionModel& model, double lambda0, const RevolutionRigidCoords& w) {
  const double u = w(revolution_coord::u), phi = w(revolution_coord::phi), theta = w(revolution_coord::theta);
  const ChartLocal c = chart_local(model.surface, u);
  const RevolutionFrame frame = revolution_frame(model.surface, u, phi);
  const double m = model.body.mass, s = w(revolution_coord::spin);
  const double Pi = w(revolution_coord::rigid_p_phi) - c.m.C * s;
  EmbeddedRigid Y;
  Y.segment<3>(embedded::X) = frame.X;
  Y.segment<3>(embedded::V) =
      (w(revolution_coord::rigid_p_u) / (m * c.m.f)) * frame.E1 + (Pi / (m * c.p.rho)) * frame.E2;
  Y.segment<3>(embedded::e1) = lambda0 * (std::cos(theta) * frame.E1 + std::sin(theta) * frame.E2);
  Y(embedded::spin) = s;
  return Y;
}

RevolutionCoords chart_of(const RevolutionModel& model, const Embedded& Y) {
  const Vec3 X = Y.segment<3>(embedded::X), V = Y.segment<3>(embedded::V);
  const double u = revolution_entry(model.surface.kind).u_of(model.surface, X);
  const double phi = std::atan2(X.y(), X.x());
  const ChartLocal c = chart_local(model.surface, u);
  const RevolutionFrame frame = revolution_frame(model.surface, u, phi);
  const Vec3 E[2] = {frame.E1, frame.E2};
  Mat2 L, M;
  for (int A = 0; A < 2; ++A)
    for (int B = 0; B < 2; ++B) {
      L(B, A) = E[B].dot(Y.segment<3>(embedded::e1 + 3 * A));
      M(B, A) = E[B].dot(Y.segment<3>(embedded::W1 + 3 * A));
    }
  RevolutionCoords w;
  w(revolution_coord::u) = u;
  w(revolution_coord::phi) = phi;
  set_block(w, revolution_coord::L, L);
  set_block(w, revolution_coord::P, momentum_from_rate(model.body.inertia, M));
  const double m = model.body.mass;
  w(revolution_coord::p_u) = m * c.m.f * V.dot(frame.E1);
  w(revolution_coord::p_phi) = m * c.p.rho * V.dot(frame.E2) + c.m.C * revolution_spin(w);
  return w;
}

}  // namespace spinfold
