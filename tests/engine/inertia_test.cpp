// The body's inertia J^{AB} (engine/inertia.h, physics.md §13): each quantity against the trace
// formula written out here, the momentum map inverted, and the isotropic case as the number.
#include "engine/inertia.h"

#include <gtest/gtest.h>

#include "engine/dynamics.h"
#include "tests/engine/test_support.h"

namespace spinfold {
namespace {

using test::matrix;

Body anisotropic_body() {
  Body body;
  body.inertia_matrix = InertiaMatrix{0.3, 0.05, 0.05, 0.1};
  return body;
}

TEST(Inertia, NumberIsIsotropic) {
  Body body;
  body.inertia = 0.25;
  const Inertia j = inertia_of(body);
  EXPECT_TRUE(j.isotropic);
  EXPECT_TRUE(isotropic_inertia(body));
  EXPECT_EQ(j.J, 0.25);
  EXPECT_EQ(rigid_inertia(j), 0.25);
}

// A multiple of the identity given as a matrix is the number J₁₁ (so its runs are bit-identical).
TEST(Inertia, IsotropicMatrixIsTheNumber) {
  Body body;
  body.inertia = 7.0;  // unused when the matrix is set
  body.inertia_matrix = InertiaMatrix{0.4, 0.0, 0.0, 0.4};
  EXPECT_TRUE(isotropic_inertia(body));
  const Inertia j = inertia_of(body);
  EXPECT_TRUE(j.isotropic);
  EXPECT_EQ(j.J, 0.4);
}

// An anisotropic matrix: J is tr(J)/2 and the inverse is the matrix's.
TEST(Inertia, MatrixKeepsItsInverseAndHalfTrace) {
  const Body body = anisotropic_body();
  EXPECT_FALSE(isotropic_inertia(body));
  const Inertia j = inertia_of(body);
  EXPECT_FALSE(j.isotropic);
  EXPECT_DOUBLE_EQ(j.J, 0.2);
  EXPECT_DOUBLE_EQ(rigid_inertia(j), 0.2);
  EXPECT_EQ(j.matrix, matrix(0.3, 0.05, 0.05, 0.1));
  EXPECT_LT((j.matrix * j.inverse - Mat2::Identity()).norm(), 1e-15);
}

// P = M J and M = P J⁻¹ invert each other; T = ½ tr(P J⁻¹ Pᵀ) = ½ tr(M J Mᵀ).
TEST(Inertia, MomentumAndRateAndEnergy) {
  const Mat2 M = matrix(0.3, -0.7, 1.1, 0.2);
  for (const Body& body : {Body{}, anisotropic_body()}) {
    const Inertia j = inertia_of(body);
    const Mat2 J = j.isotropic ? Mat2(j.J * Mat2::Identity()) : j.matrix;
    const Mat2 P = momentum_from_rate(j, M);
    EXPECT_LT((P - M * J).norm(), 1e-15);
    EXPECT_LT((rate_from_momentum(j, P) - M).norm(), 1e-14);
    EXPECT_NEAR(internal_kinetic_energy(j, P), 0.5 * (M * J * M.transpose()).trace(), 1e-14) << j.isotropic;
  }
}

// s = tr((εL)ᵀ M J) and p_β = −tr((Lε)ᵀ M J), written out with ε = [[0, −1], [1, 0]].
TEST(Inertia, SpinAndVorticityAreTheTraceFormulas) {
  const Mat2 L = matrix(1.5, 0.2, -0.1, 0.5), M = matrix(0.3, -0.7, 1.1, 0.2);
  const Mat2 eps = matrix(0.0, -1.0, 1.0, 0.0);
  EXPECT_EQ(epsilon(), eps);
  for (const Body& body : {Body{}, anisotropic_body()}) {
    const Inertia j = inertia_of(body);
    const Mat2 J = j.isotropic ? Mat2(j.J * Mat2::Identity()) : j.matrix;
    EXPECT_NEAR(spin_from_rate(j, L, M), ((eps * L).transpose() * M * J).trace(), 1e-15);
    EXPECT_NEAR(vorticity_from_rate(j, L, M), -((L * eps).transpose() * M * J).trace(), 1e-15);
  }
}

// The rigid rotation L = λ₀U(θ), M = ωεL: its kinetic energy ½ω²λ₀² tr J is the isotropic body's
// with J = rigid_inertia.
TEST(Inertia, RigidMomentGivesTheRigidRotationsEnergy) {
  const Inertia j = inertia_of(anisotropic_body());
  const double lambda0 = 1.2, omega = 0.8, theta = 0.3;
  const Mat2 L = lambda0 * matrix(std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta));
  const Mat2 M = omega * epsilon() * L;
  const double T = internal_kinetic_energy(j, momentum_from_rate(j, M));
  EXPECT_NEAR(T, 0.5 * omega * omega * lambda0 * lambda0 * j.matrix.trace(), 1e-14);
  EXPECT_NEAR(T, omega * omega * lambda0 * lambda0 * rigid_inertia(j), 1e-14);
}

}  // namespace
}  // namespace spinfold
