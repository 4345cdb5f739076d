// The example surfaces (engine/formula_examples.h): every one parses, its start has a foot on it, and a
// spinning body runs on it from there for a while with its energy kept and on its surface.
#include "engine/formula_examples.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "engine/embedded_run.h"
#include "engine/formula_surface.h"
#include "engine/readout.h"
#include "engine/simulation.h"

namespace spinfold {
namespace {

TEST(FormulaExamples, EveryExampleStartsAndRunsOnItsSurface) {
  std::set<std::string> names;
  for (const FormulaExample& example : formula_examples()) {
    const std::string name(example.name);
    EXPECT_TRUE(names.insert(name).second) << "two examples named " << name;
    const Surface surface = example_surface(example);
    ASSERT_TRUE(parse_scene_formula(surface).surface)
        << name << ": " << parse_scene_formula(surface).error.reason;
    const std::shared_ptr<const FormulaSurface> formula = formula_surface_of(surface);
    const SurfaceFoot foot = start_foot(*formula, example.start);
    ASSERT_TRUE(foot.X) << name << ": " << foot.refusal;
    EXPECT_LT((*foot.X - Vec3(example.start[0], example.start[1], example.start[2])).norm(), 0.5) << name;
    Scene scene;
    scene.surface = surface;
    scene.body.model = BodyModel::rigid;
    scene.initial.X = example.start;
    scene.initial.speed = 0.5;
    scene.initial.heading = 0.3;
    scene.initial.spin = 1.0;
    Simulation run = start_simulation(scene);
    advance_to(run, 5.0);
    EXPECT_EQ(run.state.status, Status::ok) << name;
    const Readout r = readout(run);
    EXPECT_LT(std::abs(r.energy_error), 1e-8) << name;
    ASSERT_TRUE(r.embedded) << name;
    EXPECT_LT(r.embedded->drift, 1e-12) << name;
  }
  EXPECT_EQ(names.size(), 5u);
}

}  // namespace
}  // namespace spinfold
