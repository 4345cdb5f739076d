// Scenes shared by the benchmarks: each with a characteristic period and, where the exact solver
// covers it, a closed-form reference.
#pragma once

#include <string>
#include <vector>

#include "engine/scene.h"
#include "engine/state.h"

namespace spinfold::bench {

struct BenchScene {
  std::string name;
  std::string summary;
  Scene scene;
};

std::vector<BenchScene> work_precision_scenes();

// Largest component difference of two states' embedded (X, V, e_A, W_A), each vector's difference
// relative to max(1, its length); infinity if either is not finite.
double state_error(const Scene& scene, const State& a, const State& b);

}  // namespace spinfold::bench
