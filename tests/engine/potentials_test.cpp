// The potential energies (engine/potentials.h, physics.md §5): the closed forms written out here,
// and every derivative against a central difference of the value.
#include "engine/potentials.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/engine/test_support.h"

namespace spinfold {
namespace {

using test::matrix;

// Γ = g R² on S², g on H² and the plane.
TEST(Potentials, RadialStrengthPerSurface) {
  const RadialPotential radial{0.3};
  EXPECT_DOUBLE_EQ(radial_strength({SurfaceKind::sphere, 2.0}, radial), 1.2);
  EXPECT_EQ(radial_strength({SurfaceKind::pseudosphere, 2.0}, radial), 0.3);
  EXPECT_EQ(radial_strength({SurfaceKind::plane, 2.0}, radial), 0.3);
}

// V_r = Γ/S(r)² at the chart point (r, φ), on S² g R²/(R sin(r/R))² = g/sin²(r/R).
TEST(Potentials, RadialPotentialIsStrengthOverRhoSquared) {
  const RadialPotential radial{0.3};
  const Surface sphere{SurfaceKind::sphere, 2.0}, h2{SurfaceKind::pseudosphere, 2.0};
  const double r = 1.1;
  EXPECT_NEAR(radial_potential(sphere, radial, chart_point(sphere, r, 0.4).X),
              0.3 / std::pow(std::sin(r / 2.0), 2), 1e-14);
  EXPECT_NEAR(radial_potential(h2, radial, chart_point(h2, r, 0.4).X),
              0.3 / std::pow(2.0 * std::sinh(r / 2.0), 2), 1e-14);
  EXPECT_DOUBLE_EQ(radial_potential({SurfaceKind::plane, 1.0}, radial, {3.0, 4.0, 0.0}), 0.3 / 25.0);
}

// ∂V_r/∂X by central differences in each ambient direction.
TEST(Potentials, RadialGradientMatchesDifferences) {
  const RadialPotential radial{0.7};
  const Surface s{SurfaceKind::sphere, 1.5};
  const Vec3 X{0.4, -0.9, 0.3};
  const Vec3 gradient = radial_potential_gradient(s, radial, X);
  const double h = 1e-6;
  for (int i = 0; i < 3; ++i) {
    Vec3 step = Vec3::Zero();
    step[i] = h;
    const double numeric =
        (radial_potential(s, radial, X + step) - radial_potential(s, radial, X - step)) / (2 * h);
    EXPECT_NEAR(gradient[i], numeric, 1e-7) << i;
  }
  EXPECT_EQ(gradient.z(), 0.0);
}

// a = ‖L‖²/2 − det L, b = ‖L‖²/2 + det L; a similarity (λI) has a = 0 exactly, no round-off.
TEST(Potentials, DeformationInvariantsAreXSquaredAndYSquared) {
  const Mat2 L = matrix(1.5, 0.2, -0.1, 0.5);
  const DeformationInvariants ab = deformation_invariants(L);
  EXPECT_NEAR(ab.a, L.squaredNorm() / 2 - L.determinant(), 1e-15);
  EXPECT_NEAR(ab.b, L.squaredNorm() / 2 + L.determinant(), 1e-15);
  const DeformationInvariants similarity = deformation_invariants(matrix(0.7, 0.0, 0.0, 0.7) * 1e8);
  EXPECT_EQ(similarity.a, 0.0);
  EXPECT_EQ(deformation_invariants(matrix(0.6, 0.8, 0.8, -0.6)).b, 0.0);  // a reflection: y = 0
}

// V = A/a + B/b + C(a + b) with its partials; no potential is zero everywhere.
TEST(Potentials, AbcEnergyAndPartials) {
  const AbcPotential abc{0.02, 0.4, 0.3};
  const double a = 0.7, b = 1.9;
  const DeformationEnergy e = deformation_potential(abc, a, b);
  EXPECT_NEAR(e.value, 0.02 / a + 0.4 / b + 0.3 * (a + b), 1e-15);
  EXPECT_NEAR(e.dV_da, -0.02 / (a * a) + 0.3, 1e-15);
  EXPECT_NEAR(e.dV_db, -0.4 / (b * b) + 0.3, 1e-15);
  const DeformationEnergy none = deformation_potential(std::monostate{}, a, b);
  EXPECT_EQ(none.value, 0.0);
  EXPECT_EQ(none.dV_da, 0.0);
  EXPECT_EQ(none.dV_db, 0.0);
}

// Each kind's partials and ∂V/∂L against differences of V(a(L), b(L)).
TEST(Potentials, DeformationDerivativesMatchDifferences) {
  const Mat2 L = matrix(1.3, 0.25, -0.15, 0.6);
  const double h = 1e-6;
  for (const DeformationPotential& potential :
       {DeformationPotential{AbcPotential{0.02, 0.4, 0.3}},
        DeformationPotential{PolarPotential{0.05, 0.1, PolarForm::cot2}},
        DeformationPotential{PolarPotential{0.05, 0.1, PolarForm::literal}}}) {
    const auto V = [&](const Mat2& M) {
      const DeformationInvariants ab = deformation_invariants(M);
      return deformation_potential(potential, ab.a, ab.b).value;
    };
    const DeformationInvariants ab = deformation_invariants(L);
    const DeformationEnergy e = deformation_potential(potential, ab.a, ab.b);
    EXPECT_NEAR(e.dV_da,
                (deformation_potential(potential, ab.a + h, ab.b).value -
                 deformation_potential(potential, ab.a - h, ab.b).value) /
                    (2 * h),
                1e-6 * (1 + std::abs(e.dV_da)))
        << potential.index();
    EXPECT_NEAR(e.dV_db,
                (deformation_potential(potential, ab.a, ab.b + h).value -
                 deformation_potential(potential, ab.a, ab.b - h).value) /
                    (2 * h),
                1e-6 * (1 + std::abs(e.dV_db)))
        << potential.index();
    const Mat2 gradient = deformation_gradient(e, L);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        Mat2 step = Mat2::Zero();
        step(i, j) = h;
        EXPECT_NEAR(gradient(i, j), (V(L + step) - V(L - step)) / (2 * h),
                    1e-6 * (1 + std::abs(gradient(i, j))))
            << potential.index() << " " << i << j;
      }
  }
}

TEST(Potentials, HasDeformationPotentialOnlyWhenOneIsGiven) {
  Potentials p;
  EXPECT_FALSE(has_deformation_potential(p));
  p.deformation = AbcPotential{0.0, 0.0, 1.0};
  EXPECT_TRUE(has_deformation_potential(p));
  p.radial = RadialPotential{1.0};
  p.deformation = std::monostate{};
  EXPECT_FALSE(has_deformation_potential(p));
}

}  // namespace
}  // namespace spinfold
