// What both pictures of a surface of revolution share (render/views/profile_drawing.cpp), against
// the surfaces' closed forms: where K changes sign, which parallels are drawn, the largest |K|.
#include "render/views/profile_drawing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace spinfold::render {
namespace {

constexpr double kPi = std::numbers::pi;

ProfileShape shape(SurfaceKind kind) {
  Surface s;
  s.kind = kind;
  return profile_shape(s);
}

TEST(ProfileDrawing, KChangesSignOnTheTorussTopAndBottomCirclesAndAtTheBumpsWidth) {
  const std::vector<double> torus = zero_curvature_parallels(shape(SurfaceKind::torus));
  ASSERT_EQ(torus.size(), 2u);
  EXPECT_NEAR(torus[0], -kPi / 2, 1e-12);  // K = cos u/(a ρ)
  EXPECT_NEAR(torus[1], kPi / 2, 1e-12);
  // z = h exp(−ρ²/(2w²)): z'' = 0, so K = 0, at ρ = w (w = 1 by default).
  const std::vector<double> bump = zero_curvature_parallels(shape(SurfaceKind::bump));
  ASSERT_EQ(bump.size(), 1u);
  EXPECT_NEAR(bump[0], 1.0, 1e-12);
  EXPECT_TRUE(zero_curvature_parallels(shape(SurfaceKind::spheroid)).empty());  // K > 0 everywhere
  EXPECT_TRUE(zero_curvature_parallels(shape(SurfaceKind::catenoid)).empty());  // K < 0 everywhere
}

TEST(ProfileDrawing, TheGridsParallelsAreTheRowsStepsLeavingOutTheAxisPoints) {
  const std::vector<double> spheroid = grid_parallels(shape(SurfaceKind::spheroid));
  ASSERT_EQ(spheroid.size(), 11u);  // every 15° of polar angle, the poles left out
  EXPECT_NEAR(spheroid.front(), kPi / 12, 1e-12);
  EXPECT_NEAR(spheroid.back(), 11 * kPi / 12, 1e-12);
  const std::vector<double> torus = grid_parallels(shape(SurfaceKind::torus));
  EXPECT_EQ(torus.size(), 13u);  // −π … π every 30°, both ends the inner equator
  const std::vector<double> bump = grid_parallels(shape(SurfaceKind::bump));
  ASSERT_EQ(bump.size(), 8u);  // w/2 … 4w, the top left out
  EXPECT_NEAR(bump.front(), 0.5, 1e-12);
}

TEST(ProfileDrawing, TheLargestCurvatureIsTheTorussInnerEquators) {
  Surface torus;
  torus.kind = SurfaceKind::torus;
  torus.tube_radius = 1.0;
  torus.center_radius = 2.5;
  // K = cos u/(a(c + a cos u)) is most negative at u = π: −1/(a(c − a)).
  EXPECT_NEAR(largest_curvature(profile_shape(torus), 48), 1.0 / 1.5, 1e-12);
}

}  // namespace
}  // namespace spinfold::render
