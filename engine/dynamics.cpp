#include "engine/dynamics.h"

#include <cmath>

#include "engine/body_forces.h"
#include "engine/inertia.h"
#include "engine/potentials.h"

namespace spinfold {

Mat2 epsilon() {
  Mat2 e;
  e << 0.0, -1.0, 1.0, 0.0;
  return e;
}

namespace {

Mat2 block(const Coords& y, int first) {
  Mat2 m;
  m << y[first], y[first + 1], y[first + 2], y[first + 3];
  return m;
}

// εX for a 2x2 X without multiplications: rows (−X₂₁, −X₂₂), (X₁₁, X₁₂).
Mat2 eps_times(const Mat2& X) {
  Mat2 r;
  r << -X(1, 0), -X(1, 1), X(0, 0), X(0, 1);
  return r;
}

double rigid_scale(const Scene& scene) {
  return scene.initial.lambda;
}

}  // namespace

double spin_of(const Scene& scene, const Coords& y) {
  if (scene.body.model == BodyModel::rigid) return y[coord::spin];
  const Mat2 L = block(y, coord::L), P = block(y, coord::P);
  return eps_times(L).cwiseProduct(P).sum();
}

InternalState internal_state(const Scene& scene, const Coords& y) {
  if (scene.body.model == BodyModel::rigid) {
    const double l0 = rigid_scale(scene), th = y[coord::theta];
    Mat2 L;
    L << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
    L *= l0;
    const double omega = y[coord::spin] / (2.0 * rigid_inertia(inertia_of(scene.body)) * l0 * l0);
    return {L, omega * eps_times(L)};
  }
  return {block(y, coord::L), rate_from_momentum(inertia_of(scene.body), block(y, coord::P))};
}

OrbitPotential orbit_potential(const Scene& scene, const Chart& chart, double r, double phi) {
  OrbitPotential t;
  const Surface& surface = scene.surface;
  const bool height = !std::holds_alternative<std::monostate>(scene.potential.height);
  if (scene.potential.radial) {
    const RadialPotential& radial = *scene.potential.radial;
    if (chart.global) {
      // V_r = Γ/S², V_r′ = −2ΓC/S³ (physics.md §5).
      const double S = polar_S(surface, r), C = polar_C(surface, r), G = radial_strength(surface, radial);
      t.value = G / (S * S);
      t.d_dr = -2.0 * G * C / (S * S * S);
    } else {
      const ChartPoint p = chart_point(surface, r, phi);
      const Vec3 X = chart.A * p.X + chart.b;
      const Vec3 grad = radial_potential_gradient(surface, radial, X);
      t.value = radial_potential(surface, radial, X);
      t.d_dr = grad.dot(chart.A * p.E1);                          // ∂X/∂r = E₁
      t.d_dphi = grad.dot(chart.A * p.E2) * polar_S(surface, r);  // ∂X/∂φ = S E₂
    }
  }
  if (height) {
    // V_h(z), z the global point's height: ∂V_h/∂r = V_h′ ∂z/∂r, ∂z/∂r = (A E₁)_z, ∂z/∂φ = S (A E₂)_z.
    const ChartPoint p = chart_point(surface, r, phi);
    const double z = (chart.A * p.X + chart.b).z(), m = scene.body.mass;
    const double slope = height_slope(scene.potential.height, m, z);
    t.value += height_energy(scene.potential.height, m, z);
    t.d_dr += slope * (chart.A * p.E1).z();
    t.d_dphi += slope * (chart.A * p.E2).z() * polar_S(surface, r);
  }
  return t;
}

EnergyParts energy_parts(const Scene& scene, const Chart& chart, const Coords& y) {
  const Inertia inertia = inertia_of(scene.body);
  const double m = scene.body.mass, J = rigid_inertia(inertia);
  const double r = y[coord::r], S = polar_S(scene.surface, r), C = polar_C(scene.surface, r);
  const double s = spin_of(scene, y);
  const double Pi = y[coord::p_phi] - C * s;
  EnergyParts e;
  e.kinetic = y[coord::p_r] * y[coord::p_r] / (2.0 * m) + Pi * Pi / (2.0 * m * S * S);
  e.potential = orbit_potential(scene, chart, r, y[coord::phi]).value;
  if (scene.body.model == BodyModel::rigid) {
    const double l0 = rigid_scale(scene);
    e.kinetic += s * s / (4.0 * J * l0 * l0);
    return e;
  }
  const Mat2 L = block(y, coord::L), P = block(y, coord::P);
  const DeformationInvariants inv = deformation_invariants(L);
  e.kinetic += internal_kinetic_energy(inertia, P);  // ½ tr(P J⁻¹ Pᵀ) (physics.md §13)
  e.potential += deformation_potential(scene.potential.deformation, inv.a, inv.b).value;
  return e;
}

double hamiltonian(const Scene& scene, const Chart& chart, const Coords& y) {
  const EnergyParts e = energy_parts(scene, chart, y);
  return e.kinetic + e.potential;
}

void vector_field(const Scene& scene, const Chart& chart, const Coords& y, Coords& dydt) {
  const Inertia inertia = inertia_of(scene.body);
  const double m = scene.body.mass, J = rigid_inertia(inertia), K = curvature(scene.surface);
  const double r = y[coord::r], S = polar_S(scene.surface, r), C = polar_C(scene.surface, r);
  const double s = spin_of(scene, y);
  const double Pi = y[coord::p_phi] - C * s;
  const double phi_dot = Pi / (m * S * S);
  const OrbitPotential potential = orbit_potential(scene, chart, r, y[coord::phi]);

  dydt.resize(y.size());
  dydt[coord::r] = y[coord::p_r] / m;
  dydt[coord::phi] = phi_dot;
  dydt[coord::p_r] = (C * Pi * Pi / (S * S) - K * s * Pi) / (m * S) - potential.d_dr;
  dydt[coord::p_phi] = -potential.d_dphi;
  const double drive = C * phi_dot;  // Cφ̇: rotation rate of the chart frame against parallel transport
  // Rayleigh friction (physics-surfaces.md §13): −γ_t times the velocity's covector, and −γ_i M on P.
  const Friction friction = scene.friction.value_or(Friction{});
  if (friction.translational != 0.0) {
    dydt[coord::p_r] -= friction.translational * y[coord::p_r] / m;
    dydt[coord::p_phi] -= friction.translational * S * S * phi_dot;
  }

  if (scene.body.model == BodyModel::rigid) {
    const double l0 = rigid_scale(scene);
    dydt[coord::theta] = s / (2.0 * J * l0 * l0) - drive;
    dydt[coord::spin] = 0.0;
    if (friction.internal != 0.0) {  // tr((εL)ᵀM) = 2ωλ₀² = s/J
      dydt[coord::spin] = -friction.internal * s / J;
      dydt[coord::p_phi] -= friction.internal * C * s / J;
    }
    return;
  }
  const Mat2 L = block(y, coord::L), P = block(y, coord::P);
  const Mat2 M = rate_from_momentum(inertia, P);
  const Mat2 L_dot = M - drive * eps_times(L);  // PJ⁻¹ − Cφ̇εL (§13)
  Mat2 P_dot = -drive * eps_times(P);
  if (has_deformation_potential(scene.potential)) {
    const DeformationInvariants inv = deformation_invariants(L);
    P_dot -= deformation_gradient(deformation_potential(scene.potential.deformation, inv.a, inv.b), L);
  }
  if (friction.internal != 0.0) {
    P_dot -= friction.internal * M;
    dydt[coord::p_phi] -= friction.internal * C * eps_times(L).cwiseProduct(M).sum();
  }
  dydt.segment<4>(coord::L) << L_dot(0, 0), L_dot(0, 1), L_dot(1, 0), L_dot(1, 1);
  dydt.segment<4>(coord::P) << P_dot(0, 0), P_dot(0, 1), P_dot(1, 0), P_dot(1, 1);
}

}  // namespace spinfold
