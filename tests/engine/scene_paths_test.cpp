// The scene's dotted paths, walked through the tables: every leaf once, with its range or names.
#include "engine/scene_paths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace spinfold {
namespace {

TEST(ScenePaths, EveryLeafOnceWithItsRangeOrNames) {
  std::set<std::string> seen;
  for (const ScenePath& p : scene_paths()) EXPECT_TRUE(seen.insert(p.path).second) << p.path;
  const ScenePath* r = find_scene_path("initial.r");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->leaf, ScenePath::Leaf::number);
  EXPECT_TRUE(r->range.has_min());
  const ScenePath* kind = find_scene_path("surface.kind");
  ASSERT_NE(kind, nullptr);
  EXPECT_EQ(kind->names, (std::vector<std::string>{"sphere", "pseudosphere", "plane", "torus", "spheroid",
                                                   "bump", "catenoid", "implicit", "graph"}));
  // A leaf knows the surfaces it belongs to: r the constant-curvature ones, u the surfaces of
  // revolution, F the implicit surface.
  EXPECT_EQ(r->surfaces, surfaces_offering(Offer::polar_chart));
  ASSERT_NE(find_scene_path("initial.u"), nullptr);
  EXPECT_EQ(find_scene_path("initial.u")->surfaces, surfaces_offering(Offer::profile_chart));
  ASSERT_NE(find_scene_path("surface.F"), nullptr);
  EXPECT_EQ(find_scene_path("surface.F")->surfaces, surface_bit(SurfaceKind::implicit));
  // A formula's parameter is a number leaf of its own name, once, on the formula surfaces.
  const ScenePath* a = find_scene_path("surface.parameters.a");
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->leaf, ScenePath::Leaf::number);
  EXPECT_EQ(a->surfaces, surfaces_offering(Offer::formula));
  EXPECT_EQ(find_scene_path("surface.parameters.a"), a);
  EXPECT_EQ(find_scene_path("surface.parameters.pi"), nullptr);  // not a parameter's name
  EXPECT_EQ(find_scene_path("surface.parameters."), nullptr);
  ASSERT_NE(find_scene_path("potential.height.g"), nullptr);
  EXPECT_EQ(find_scene_path("potential.height.g")->surfaces,
            surfaces_offering(Offer::implicit_equation) | surface_bit(SurfaceKind::sphere));
  EXPECT_EQ(find_scene_path("friction.internal")->surfaces, ~0u);
  EXPECT_EQ(find_scene_path("surface.tube_radius")->surfaces, surface_bit(SurfaceKind::torus));
  EXPECT_EQ(find_scene_path("body.mass")->surfaces, ~0u);
  const ScenePath* integrator = find_scene_path("integrator.name");
  ASSERT_NE(integrator, nullptr);
  EXPECT_NE(std::find(integrator->names.begin(), integrator->names.end(), "dop853"), integrator->names.end());
  // The deformation's kind comes before its coefficients, and shared coefficients once.
  const auto at = [](std::string_view path) {
    const auto& all = scene_paths();
    return std::find_if(all.begin(), all.end(), [&](const ScenePath& p) { return p.path == path; }) -
           all.begin();
  };
  ASSERT_NE(find_scene_path("potential.deformation.kind"), nullptr);
  EXPECT_LT(at("potential.deformation.kind"), at("potential.deformation.A"));
  EXPECT_EQ(find_scene_path("initial.nope"), nullptr);
}

TEST(ScenePaths, TheWalkReachesEveryPathThroughItsPlace) {
  std::size_t leaves = 0;
  for_each_scene_field([&](const std::string& path, std::string_view, const auto&, auto place) {
    Scene scene;
    (void)place(scene);  // present after the call: the optional section, the deformation's kind
    EXPECT_NE(find_scene_path(path), nullptr) << path;
    ++leaves;
  });
  EXPECT_GE(leaves, scene_paths().size() - 2);  // all but the synthetic kinds (deformation, height)
}

}  // namespace
}  // namespace spinfold
