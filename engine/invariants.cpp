#include "engine/invariants.h"

#include <cmath>
#include <limits>

#include "engine/chart.h"
#include "engine/dynamics.h"
#include "engine/embedded_dynamics.h"
#include "engine/embedded_run.h"
#include "engine/inertia.h"
#include "engine/potentials.h"
#include "engine/revolution.h"

namespace spinfold {

GlobalBody global_body(const Scene& scene, const State& state) {
  const Surface& surface = scene.surface;
  const Chart& chart = state.chart;
  const BodyKinematics body = chart_kinematics(scene, state.y);
  GlobalBody g;
  g.X = chart.A * body.X + chart.b;
  g.V = chart.A * body.V;
  g.spin = body.spin;
  const PolarCoordinates pc = polar_coordinates(surface, g.X);
  g.r = pc.r;
  g.phi = pc.phi;
  g.S = pc.rho;
  g.C = offers(surface, Offer::zero_curvature) ? 1.0 : g.X.z() / surface.radius;
  g.at_pole = pc.rho <= 1e-12 * surface.radius;
  g.L = body.L;
  g.M = body.M;
  if (g.at_pole) return g;

  // The paper's E₁ at the body, in chart coordinates: away from the global pole O. Pulling O back
  // (one row of A⁻¹, no cancellation) and projecting keeps full precision far out on H².
  Vec3 E1 = body.F1;
  if (!chart.global) {
    const Mat3 A_inv = inverse_linear(surface, chart.A);
    const Vec3 O_global =
        offers(surface, Offer::zero_curvature) ? Vec3::Zero() : Vec3(0.0, 0.0, surface.radius);
    const Vec3 towards = tangential(surface, body.X, A_inv * (O_global - chart.b) - body.X);
    E1 = -towards / std::sqrt(dot(surface, towards, towards));
  }
  const Vec3 E2 = rotate_quarter(surface, body.X, E1);
  const Mat2 U = rotation2(std::atan2(dot(surface, body.F1, E2), dot(surface, body.F1, E1)));
  g.L = U * body.L;
  g.M = U * body.M;
  g.r_dot = dot(surface, body.V, E1);
  g.phi_dot = dot(surface, body.V, E2) / g.S;
  return g;
}

double energy(const Scene& scene, const State& state) {
  if (chart_free(scene.surface)) {
    const EnergyParts e = embedded_energy_parts(EmbeddedScene(scene), state.y);
    return e.kinetic + e.potential;
  }
  return hamiltonian(scene, state.chart, state.y);
}

double orbital_energy(const Scene& scene, const State& state) {
  if (chart_free(scene.surface)) return embedded_energy_split(EmbeddedScene(scene), state.y).orbital;
  const double m = scene.body.mass, r = state.y[coord::r];
  const double S = polar_S(scene.surface, r), C = polar_C(scene.surface, r);
  const double Pi = state.y[coord::p_phi] - C * spin_of(scene, state.y);
  const double p_r = state.y[coord::p_r];
  return p_r * p_r / (2.0 * m) + Pi * Pi / (2.0 * m * S * S) +
         orbit_potential(scene, state.chart, r, state.y[coord::phi]).value;
}

double deformation_energy(const Scene& scene, const State& state) {
  if (chart_free(scene.surface)) return embedded_energy_split(EmbeddedScene(scene), state.y).deformation;
  const Inertia inertia = inertia_of(scene.body);
  const InternalState in = internal_state(scene, state.y);
  // ½ tr(M J Mᵀ) (physics.md §13); the rigid body is the isotropic one with J = tr(J)/2.
  double E = inertia.isotropic || scene.body.model == BodyModel::rigid
                 ? 0.5 * inertia.J * in.M.squaredNorm()
                 : 0.5 * (in.M * inertia.matrix).cwiseProduct(in.M).sum();
  if (scene.body.model != BodyModel::rigid) {
    const DeformationInvariants inv = deformation_invariants(in.L);
    E += deformation_potential(scene.potential.deformation, inv.a, inv.b).value;
  }
  return E;
}

double spin(const Scene& scene, const State& state) {
  if (chart_free(scene.surface)) return embedded_spin_of(EmbeddedScene(scene), state.y);
  return spin_of(scene, state.y);
}

double vorticity(const Scene& scene, const State& state) {
  const InternalState in = internal_state(scene, state.y);
  return vorticity_from_rate(inertia_of(scene.body), in.L, in.M);
}

ChartMomentum chart_momentum(const Scene& scene, const State& state) {
  const Surface& surface = scene.surface;
  const BodyKinematics body = chart_kinematics(scene, state.y);
  ChartMomentum out;
  out.local = scene.body.mass * body.X.cross(body.V) +
              curvature(surface) * surface.radius * body.spin * raise(surface, body.X);
  const Mat3& A = state.chart.A;
  // (AX) × (AV) = det(A) A^{-T}(X × V), A^{-T} = ηAη for a Lorentz transform or a rotation, and
  // η(AX) = ηAη(ηX).
  Mat3 B = A;
  if (offers(surface, Offer::negative_curvature)) {
    const Eigen::DiagonalMatrix<double, 3> eta(1.0, 1.0, -1.0);
    B = eta * A * eta;
  }
  // det A = ±1, but far out on H² (‖A‖ ~ e^{r/R}) the 3×3 determinant cancels to noise (measured:
  // −3.1 for a proper chart at r = 13R, which flipped the orbital part of p_φ). An isometry of the
  // upper sheet keeps time (A₃₃ ≥ 1) and is R₁·boost·R₂, so its orientation is that of the spatial
  // 2×2 block, whose determinant is cosh β ≥ 1 times ±1 and has no cancellation.
  const double det = (offers(surface, Offer::negative_curvature) ? A.topLeftCorner<2, 2>().determinant()
                                                                 : A.determinant()) < 0.0
                         ? -1.0
                         : 1.0;
  const Vec3 orbital = scene.body.mass * body.X.cross(body.V);
  const Vec3 spin_part = out.local - orbital;
  out.global = det * (B * orbital) + B * spin_part;
  constexpr double kEps = 2.220446049250313e-16;
  out.rounding = 8.0 * kEps * (B.cwiseAbs() * (orbital.cwiseAbs() + spin_part.cwiseAbs()));
  // ηAη is A^{-T} only while A keeps its Lorentz structure: AᵀηA = η holds to ~ε‖A‖² (absolute),
  // which far out (‖A‖ ~ e^{r/R}) leaves M with no digits at all. Measured: p_φ right to 1e-14 up
  // to r = 15R (‖A‖ ≈ 6e5), O(1) wrong at 20R (‖A‖ ≈ 9e7).
  const double size = A.cwiseAbs().maxCoeff();
  if (!(kEps * size * size <= 1e-4)) out.rounding.setConstant(std::numeric_limits<double>::infinity());
  return out;
}

bool well_conditioned(double rounding, double scale) {
  return rounding <= 1e-8 * scale;
}

double angular_momentum(const Scene& scene, const State& state) {
  if (chart_free(scene.surface)) return embedded_p_phi(EmbeddedScene(scene), state.y);
  if (state.chart.global) return state.y[coord::p_phi];
  if (!offers(scene.surface, Offer::zero_curvature)) return chart_momentum(scene, state).global.z();  // M₃
  const GlobalBody g = global_body(scene, state);
  const double orbital = scene.body.mass * (g.X.x() * g.V.y() - g.X.y() * g.V.x());
  return orbital + g.C * g.spin;  // M₃ = mS²φ̇ + Cs
}

double angular_momentum_rounding(const Scene& scene, const State& state) {
  if (state.chart.global || offers(scene.surface, Offer::zero_curvature)) return 0.0;
  return chart_momentum(scene, state).rounding.z();
}

namespace {

// L and M (the rates relative to parallel transport, W_A) in a right-handed orthonormal tangent frame
// (E, n × E) at the body, E along e₁: a, b and their rates' a, b are invariant under the frame's
// rotation (physics-surfaces.md §4: the internal motion is the flat one in a transported frame).
InternalState embedded_internal_state(const Scene& scene, const State& state) {
  const EmbeddedScene model(scene);
  const EmbeddedBody b = embedded_body(model, state.y);
  const Vec3 n = embedded_normal(*model.surface->implicit, b.X);
  const Vec3 E1 = (b.e[0] - b.e[0].dot(n) * n).normalized(), E2 = n.cross(E1);
  InternalState in;
  for (int A = 0; A < 2; ++A) {
    in.L(0, A) = E1.dot(b.e[A]), in.L(1, A) = E2.dot(b.e[A]);
    in.M(0, A) = E1.dot(b.W[A]), in.M(1, A) = E2.dot(b.W[A]);
  }
  return in;
}

}  // namespace

std::optional<SeparatedEnergies> separated_energies(const Scene& scene, const State& state) {
  // C_x and C_y separate only for isotropic J (physics.md §13), and not under det L = c (§15).
  if (scene.body.model != BodyModel::affine || !isotropic_inertia(scene.body)) return std::nullopt;
  AbcPotential abc;
  if (const auto* p = std::get_if<AbcPotential>(&scene.potential.deformation))
    abc = *p;
  else if (has_deformation_potential(scene.potential))
    return std::nullopt;
  const double J = inertia_of(scene.body).J;
  const InternalState in =
      chart_free(scene.surface) ? embedded_internal_state(scene, state) : internal_state(scene, state.y);
  const DeformationInvariants inv = deformation_invariants(in.L);
  const DeformationInvariants rate = deformation_invariants(in.M);  // 2(u_M² + v_M²), 2(p_M² + q_M²)
  SeparatedEnergies e{0.5 * J * rate.a, 0.5 * J * rate.b};
  if (abc.A != 0.0) e.C_x += abc.A / inv.a;
  if (abc.B != 0.0) e.C_y += abc.B / inv.b;
  e.C_x += abc.C * inv.a;
  e.C_y += abc.C * inv.b;
  return e;
}

std::optional<Vec3> momentum_map(const Scene& scene, const State& state) {
  if (scene.potential.radial || chart_free(scene.surface)) return std::nullopt;  // no SO(3)/SO(2,1)
  const Surface& surface = scene.surface;
  if (!offers(surface, Offer::zero_curvature)) return chart_momentum(scene, state).global;
  const GlobalBody g = global_body(scene, state);
  const double m = scene.body.mass;
  return Vec3(m * g.V.x(), m * g.V.y(), m * (g.X.x() * g.V.y() - g.X.y() * g.V.x()) + g.spin);
}

double casimir(const Surface& surface, const Vec3& M) {
  return dot(surface, M, M);
}

}  // namespace spinfold
