// Height potentials and friction (engine/body_forces.h, physics-surfaces.md §5, §13).
#include "engine/body_forces.h"

#include <gtest/gtest.h>

namespace spinfold {
namespace {

TEST(BodyForces, HeightPotentialsAndTheirSlopes) {
  const HeightPotential gravity = GravityPotential{9.8};
  const HeightPotential spring = SpringPotential{0.7};
  EXPECT_DOUBLE_EQ(height_energy(gravity, 2.0, 0.5), 2.0 * 9.8 * 0.5);  // m g z
  EXPECT_DOUBLE_EQ(height_energy(spring, 2.0, 0.5), 0.5 * 0.7 * 0.25);  // k z²/2, whatever m
  EXPECT_EQ(height_energy(HeightPotential{}, 2.0, 0.5), 0.0);
  // The slope is the energy's derivative in z (central differences).
  for (const HeightPotential& h : {gravity, spring})
    for (const double z : {-1.3, 0.0, 0.4}) {
      const double d = 1e-6;
      EXPECT_NEAR(height_slope(h, 2.0, z),
                  (height_energy(h, 2.0, z + d) - height_energy(h, 2.0, z - d)) / (2 * d), 1e-8);
    }
}

TEST(BodyForces, FrictionIsAbsentUnlessACoefficientIsSet) {
  EXPECT_FALSE(Friction{}.any());
  EXPECT_TRUE((Friction{0.1, 0.0}.any()));
  EXPECT_TRUE((Friction{0.0, 0.05}.any()));
}

}  // namespace
}  // namespace spinfold
