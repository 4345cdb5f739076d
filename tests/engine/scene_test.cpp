// A companion as a scene of its own (engine/scene.h): what it shares with the main body's scene,
// what is its own, and its legend label.
#include "engine/scene.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace spinfold {
namespace {

Scene scene_with_two_companions() {
  Scene s;
  s.name = "pair";
  s.surface = {SurfaceKind::pseudosphere, 2.5};
  s.potential.radial = RadialPotential{0.4};
  s.potential.deformation = AbcPotential{0.1, 0.2, 0.3};
  s.on_degenerate = OnDegenerate::stop;
  Companion first;
  first.body.mass = 3.0;
  first.deformation = PolarPotential{0.05, 0.1, PolarForm::literal};
  first.initial.r = 0.7;
  first.integrator = {"rk4", 0.002, 1e-8};
  s.companions.push_back(first);
  Companion second;
  second.label = "probe";
  s.companions.push_back(second);
  return s;
}

// The surface, the radial potential and the rule at a degenerate frame are the scene's; body,
// deformation potential, start and integrator are the companion's.
TEST(Scene, CompanionSceneTakesTheSharedFieldsFromTheMainScene) {
  const Scene s = scene_with_two_companions();
  const Scene c = companion_scene(s, 0);
  EXPECT_EQ(c.name, "pair");
  EXPECT_EQ(c.surface.kind, SurfaceKind::pseudosphere);
  EXPECT_EQ(c.surface.radius, 2.5);
  ASSERT_TRUE(c.potential.radial);
  EXPECT_EQ(c.potential.radial->gamma, 0.4);
  EXPECT_EQ(c.on_degenerate, OnDegenerate::stop);
  EXPECT_EQ(c.body.mass, 3.0);
  ASSERT_TRUE(std::holds_alternative<PolarPotential>(c.potential.deformation));
  EXPECT_EQ(std::get<PolarPotential>(c.potential.deformation).form, PolarForm::literal);
  EXPECT_EQ(c.initial.r, 0.7);
  EXPECT_EQ(c.integrator.name, "rk4");
  EXPECT_EQ(c.integrator.dt, 0.002);
  EXPECT_TRUE(c.companions.empty());  // a companion has no companions of its own
}

// A companion without a label is "body N", N counting the main body as 1.
TEST(Scene, CompanionLabelDefaultsToItsNumber) {
  const Scene s = scene_with_two_companions();
  EXPECT_EQ(companion_label(s, 0), "body 2");
  EXPECT_EQ(companion_label(s, 1), "probe");
  EXPECT_THROW(companion_label(s, 2), std::out_of_range);
  EXPECT_THROW(companion_scene(s, 2), std::out_of_range);
}

}  // namespace
}  // namespace spinfold
