#include "engine/actions.h"

#include <cmath>
#include <numbers>

#include "engine/dynamics.h"
#include "engine/inertia.h"
#include "engine/invariants.h"
#include "engine/potentials.h"

namespace spinfold {

namespace {

constexpr double pi = std::numbers::pi;

// k = 8π²mΓ, the radial barrier's share of J_r (0 without a radial potential).
double barrier_term(const Scene& scene) {
  if (!scene.potential.radial) return 0.0;
  return 8.0 * pi * pi * scene.body.mass * radial_strength(scene.surface, *scene.potential.radial);
}

// ½√(k + (J_φ+J_α)²) and ½√(k + (J_φ−J_α)²).
std::pair<double, double> half_roots(double k, double J_phi, double J_alpha) {
  return {0.5 * std::sqrt(k + (J_phi + J_alpha) * (J_phi + J_alpha)),
          0.5 * std::sqrt(k + (J_phi - J_alpha) * (J_phi - J_alpha))};
}

// The abc potential, if the scene's deformation potential is one.
std::optional<AbcPotential> abc_of(const Scene& scene) {
  if (const auto* abc = std::get_if<AbcPotential>(&scene.potential.deformation)) return *abc;
  return std::nullopt;
}

// π√(J/2C): the period of x² and y² under C(x² + y²), C > 0 (physics.md §8.3).
double deformation_period(double J, double C) {
  return pi * std::sqrt(J / (2.0 * C));
}

}  // namespace

std::optional<std::string> actions_unsupported_reason(const Scene& scene) {
  if (chart_free(scene.surface))
    return "action variables are computed where the curvature is constant (physics.md §8); here the orbit "
           "does not separate";
  if (scene.friction && scene.friction->any())
    return "with friction nothing is conserved to make action variables of (physics-surfaces.md §13)";
  if (!std::holds_alternative<std::monostate>(scene.potential.height))
    return "the height potential: its action variables (physics-surfaces.md §5) are not computed here";
  if (offers(scene.surface, Offer::zero_curvature))
    return "the flat limit has no action formulas here (physics.md §8.9, §8.10 are for S² and H²)";
  if (has_deformation_potential(scene.potential) && !abc_of(scene))
    return "the polar deformation potential: its actions (physics.md §8.10) are not computed here";
  if (scene.body.model == BodyModel::affine && !isotropic_inertia(scene.body))
    return "with anisotropic inertia the motion does not separate (physics.md §13)";
  if (scene.body.model == BodyModel::incompressible)
    return "the incompressible body's internal motion (det L fixed) does not separate into x and y "
           "(physics.md §15)";
  return std::nullopt;
}

ActionVariables action_variables(const Scene& scene, const State& state) {
  ActionVariables a;
  const double m = scene.body.mass, R = scene.surface.radius;
  const double J_phi = 2.0 * pi * angular_momentum(scene, state);
  const double J_alpha = 2.0 * pi * spin(scene, state);
  const double E_orb = orbital_energy(scene, state);
  const double k = barrier_term(scene);
  const auto [half_plus, half_minus] = half_roots(k, J_phi, J_alpha);
  const double radial = 8.0 * pi * pi * m * R * R * E_orb;  // 8π²mR²E′
  a.J_phi = J_phi;
  a.J_alpha = J_alpha;
  if (half_plus == 0.0 || half_minus == 0.0)
    a.undefined.push_back(
        {"nu_phi", "the orbit passes through a pole (no barrier, p_phi = +-s): phi jumps there"});
  if (offers(scene.surface, Offer::positive_curvature)) {
    const double root = std::sqrt(radial + J_alpha * J_alpha);
    a.J_r = root - half_plus - half_minus;
    a.nu_r = root / (4.0 * pi * pi * m * R * R);
    // E′ = (Q² − J_α²)/(8π²mR²), Q = J_r + h₊ + h₋, ∂h±/∂J_φ = (J_φ ± J_α)/(4h±).
    if (half_plus > 0.0 && half_minus > 0.0)
      a.nu_phi = 2.0 * root *
                 ((J_phi + J_alpha) / (4.0 * half_plus) + (J_phi - J_alpha) / (4.0 * half_minus)) /
                 (8.0 * pi * pi * m * R * R);
  } else {
    const double q = J_alpha * J_alpha - radial;  // ∝ Λ of physics.md §8.2: > 0 iff u = cosh(r/R) oscillates
    if (q > 0.0) {
      const double root = std::sqrt(q);
      a.J_r = -root + half_plus - half_minus;
      a.nu_r = root / (4.0 * pi * pi * m * R * R);
      // E′ = (J_α² − Q²)/(8π²mR²), Q = h₊ − h₋ − J_r.
      if (half_plus > 0.0 && half_minus > 0.0)
        a.nu_phi = -2.0 * root *
                   ((J_phi + J_alpha) / (4.0 * half_plus) - (J_phi - J_alpha) / (4.0 * half_minus)) /
                   (8.0 * pi * pi * m * R * R);
    } else {
      const std::string why = q == 0.0
                                  ? "a separatrix on H² (s² = 2mR²E_orb): r(t) never returns"
                                  : "the orbit is unbounded on H² (s² < 2mR²E_orb): r(t) does not oscillate";
      a.undefined.push_back({"J_r", why});
      a.undefined.push_back({"nu_r", why});
      a.undefined.push_back({"nu_phi", why});
    }
  }

  if (scene.body.model == BodyModel::rigid) {
    for (const char* f : {"J_beta", "J_x", "J_y", "nu_x", "nu_y"})
      a.undefined.push_back({f, "a rigid body has no deformation degrees of freedom"});
    return a;
  }
  const double J = inertia_of(scene.body).J;
  a.J_beta = 2.0 * pi * vorticity(scene, state);
  const std::optional<AbcPotential> abc = abc_of(scene);
  if (!abc || !(abc->C > 0.0)) {
    const std::string why = !abc ? "no deformation potential: x² and y² are not bounded (they grow like t²)"
                                 : "the abc potential's C <= 0 does not bound x² and y²";
    for (const char* f : {"J_x", "J_y", "nu_x", "nu_y"}) a.undefined.push_back({f, why});
    return a;
  }
  const std::optional<SeparatedEnergies> e = separated_energies(scene, state);
  // p_γ = 2J(u v_M − v u_M), p_δ = 2J(p q_M − q p_M): cancellation-free near x = 0 (physics.md §3).
  const InternalState in = internal_state(scene, state.y);
  const Mat2 &L = in.L, &M = in.M;
  const double u = 0.5 * (L(0, 0) - L(1, 1)), v = 0.5 * (L(0, 1) + L(1, 0));
  const double uM = 0.5 * (M(0, 0) - M(1, 1)), vM = 0.5 * (M(0, 1) + M(1, 0));
  const double p = 0.5 * (L(0, 0) + L(1, 1)), q = 0.5 * (L(1, 0) - L(0, 1));
  const double pM = 0.5 * (M(0, 0) + M(1, 1)), qM = 0.5 * (M(1, 0) - M(0, 1));
  const double p_gamma = 2.0 * J * (u * vM - v * uM), p_delta = 2.0 * J * (p * qM - q * pM);
  const double T = deformation_period(J, abc->C);
  a.J_x = e->C_x * T - pi * std::sqrt(2.0 * J * abc->A + p_gamma * p_gamma);  // πC_x√(J/2C) = C_x T
  a.J_y = e->C_y * T - pi * std::sqrt(2.0 * J * abc->B + p_delta * p_delta);
  a.nu_x = a.nu_y = 1.0 / T;
  return a;
}

std::optional<double> energy_from_actions(const Scene& scene, const ActionVariables& a) {
  if (!a.J_r || !a.J_phi || !a.J_alpha) return std::nullopt;
  const double m = scene.body.mass, R = scene.surface.radius;
  const auto [half_plus, half_minus] = half_roots(barrier_term(scene), *a.J_phi, *a.J_alpha);
  const double scale = 8.0 * pi * pi * m * R * R, Ja2 = *a.J_alpha * *a.J_alpha;
  double E = 0.0;
  if (offers(scene.surface, Offer::positive_curvature)) {
    const double Q = *a.J_r + half_plus + half_minus;  // √(8π²mR²E′ + J_α²)
    E = (Q * Q - Ja2) / scale;
  } else {
    const double Q = half_plus - half_minus - *a.J_r;  // √(J_α² − 8π²mR²E′)
    E = (Ja2 - Q * Q) / scale;
  }
  if (scene.body.model == BodyModel::rigid) {
    const double s = *a.J_alpha / (2.0 * pi), l0 = scene.initial.lambda;
    return E + s * s / (4.0 * inertia_of(scene.body).J * l0 * l0);
  }
  const std::optional<AbcPotential> abc = abc_of(scene);
  if (!a.J_x || !a.J_y || !a.J_beta || !abc) return std::nullopt;
  const double J = inertia_of(scene.body).J, T = deformation_period(J, abc->C);
  const double p_gamma = (*a.J_alpha + *a.J_beta) / (4.0 * pi),
               p_delta = (*a.J_alpha - *a.J_beta) / (4.0 * pi);
  const double C_x = (*a.J_x + pi * std::sqrt(2.0 * J * abc->A + p_gamma * p_gamma)) / T;
  const double C_y = (*a.J_y + pi * std::sqrt(2.0 * J * abc->B + p_delta * p_delta)) / T;
  return E + C_x + C_y;
}

}  // namespace spinfold
