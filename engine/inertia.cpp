#include "engine/inertia.h"

namespace spinfold {

bool isotropic_inertia(const Body& body) {
  if (!body.inertia_matrix) return true;
  const InertiaMatrix& m = *body.inertia_matrix;
  return m.J12 == 0.0 && m.J21 == 0.0 && m.J11 == m.J22;
}

Inertia inertia_of(const Body& body) {
  Inertia in;
  if (!body.inertia_matrix) {
    in.J = body.inertia;
  } else {
    const InertiaMatrix& m = *body.inertia_matrix;
    in.isotropic = isotropic_inertia(body);
    in.J = in.isotropic ? m.J11 : 0.5 * (m.J11 + m.J22);
    in.matrix << m.J11, m.J12, m.J21, m.J22;
  }
  if (in.isotropic) {
    in.matrix = in.J * Mat2::Identity();
    in.inverse = (1.0 / in.J) * Mat2::Identity();
    return in;
  }
  // J⁻¹ = adj J / det J, with det J = J11 J22 − J12² > 0 (validated).
  const double det = in.matrix(0, 0) * in.matrix(1, 1) - in.matrix(0, 1) * in.matrix(1, 0);
  in.inverse << in.matrix(1, 1) / det, -in.matrix(0, 1) / det, -in.matrix(1, 0) / det, in.matrix(0, 0) / det;
  return in;
}

Mat2 rate_from_momentum(const Inertia& inertia, const Mat2& P) {
  if (inertia.isotropic) return P / inertia.J;
  return P * inertia.inverse;
}

Mat2 momentum_from_rate(const Inertia& inertia, const Mat2& M) {
  if (inertia.isotropic) return inertia.J * M;
  return M * inertia.matrix;
}

double internal_kinetic_energy(const Inertia& inertia, const Mat2& P) {
  if (inertia.isotropic) return P.squaredNorm() / (2.0 * inertia.J);
  return 0.5 * (P * inertia.inverse).cwiseProduct(P).sum();  // ½ Σ (PJ⁻¹)_{BA} P_{BA}
}

namespace {

Mat2 epsilon2() {
  Mat2 e;
  e << 0.0, -1.0, 1.0, 0.0;
  return e;
}

// εX: rows (−X₂₁, −X₂₂), (X₁₁, X₁₂).
Mat2 eps_times(const Mat2& X) {
  Mat2 r;
  r << -X(1, 0), -X(1, 1), X(0, 0), X(0, 1);
  return r;
}

// Xε: columns (X₁₂, X₂₂), (−X₁₁, −X₂₁).
Mat2 times_eps(const Mat2& X) {
  Mat2 r;
  r << X(0, 1), -X(0, 0), X(1, 1), -X(1, 0);
  return r;
}

}  // namespace

double spin_from_rate(const Inertia& inertia, const Mat2& L, const Mat2& M) {
  if (inertia.isotropic) return inertia.J * (epsilon2() * L).cwiseProduct(M).sum();
  return eps_times(L).cwiseProduct(M * inertia.matrix).sum();
}

double vorticity_from_rate(const Inertia& inertia, const Mat2& L, const Mat2& M) {
  if (inertia.isotropic) return -inertia.J * (L * epsilon2()).cwiseProduct(M).sum();
  return -times_eps(L).cwiseProduct(M * inertia.matrix).sum();
}

double rigid_inertia(const Inertia& inertia) {
  return inertia.J;
}

}  // namespace spinfold
