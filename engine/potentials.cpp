#include "engine/potentials.h"

#include <cmath>

namespace spinfold {

double radial_strength(const Surface& surface, const RadialPotential& radial) {
  const double R = surface.radius;
  return offers(surface, Offer::positive_curvature) ? radial.gamma * R * R : radial.gamma;
}

double radial_potential(const Surface& surface, const RadialPotential& radial, const Vec3& X) {
  const double rho2 = X.x() * X.x() + X.y() * X.y();
  return radial_strength(surface, radial) / rho2;
}

Vec3 radial_potential_gradient(const Surface& surface, const RadialPotential& radial, const Vec3& X) {
  const double rho2 = X.x() * X.x() + X.y() * X.y();
  const double factor = -2.0 * radial_strength(surface, radial) / (rho2 * rho2);
  return {factor * X.x(), factor * X.y(), 0.0};
}

DeformationInvariants deformation_invariants(const Mat2& L) {
  const double u = 0.5 * (L(0, 0) - L(1, 1)), v = 0.5 * (L(0, 1) + L(1, 0));
  const double p = 0.5 * (L(0, 0) + L(1, 1)), q = 0.5 * (L(1, 0) - L(0, 1));
  return {2.0 * (u * u + v * v), 2.0 * (p * p + q * q)};
}

namespace {

DeformationEnergy abc_energy(const AbcPotential& abc, double a, double b) {
  DeformationEnergy e;
  // A term with a zero coefficient is absent, not 0/0 (physics.md §11 pitfalls).
  if (abc.A != 0.0) {
    e.value += abc.A / a;
    e.dV_da -= abc.A / (a * a);
  }
  if (abc.B != 0.0) {
    e.value += abc.B / b;
    e.dV_db -= abc.B / (b * b);
  }
  if (abc.C != 0.0) {
    e.value += abc.C * (a + b);
    e.dV_da += abc.C;
    e.dV_db += abc.C;
  }
  return e;
}

DeformationEnergy polar_energy(const PolarPotential& polar, double a, double b) {
  DeformationEnergy e;
  const double s = a + b;  // ς²
  if (polar.gtilde != 0.0) {
    e.value += polar.gtilde / std::sqrt(s);
    const double d = -polar.gtilde / (2.0 * s * std::sqrt(s));
    e.dV_da += d;
    e.dV_db += d;
  }
  if (polar.ghat != 0.0) {
    const double g = polar.ghat, w = b - a;
    if (polar.form == PolarForm::literal) {
      // V = ĝ(b − a)²/(4a²b)
      e.value += g * w * w / (4.0 * a * a * b);
      e.dV_da += -g * w / (2.0 * a * a * a);
      e.dV_db += g * (b * b - a * a) / (4.0 * a * a * b * b);
    } else {
      // Q = ĝ(b − a)²/(4ab(a + b)); derivatives expanded so that b = a is regular.
      const double den = a * b * s;
      e.value += g * w * w / (4.0 * den);
      e.dV_da += 0.25 * g * (-2.0 * w / den - w * w / (a * den) - w * w / (s * den));
      e.dV_db += 0.25 * g * (2.0 * w / den - w * w / (b * den) - w * w / (s * den));
    }
  }
  return e;
}

}  // namespace

DeformationEnergy deformation_potential(const DeformationPotential& potential, double a, double b) {
  if (const auto* abc = std::get_if<AbcPotential>(&potential)) return abc_energy(*abc, a, b);
  if (const auto* polar = std::get_if<PolarPotential>(&potential)) return polar_energy(*polar, a, b);
  return {};
}

Mat2 deformation_gradient(const DeformationEnergy& energy, const Mat2& L) {
  Mat2 cof;
  cof << L(1, 1), -L(1, 0), -L(0, 1), L(0, 0);
  return energy.dV_da * (L - cof) + energy.dV_db * (L + cof);
}

bool has_deformation_potential(const Potentials& potentials) {
  return !std::holds_alternative<std::monostate>(potentials.deformation);
}

}  // namespace spinfold
