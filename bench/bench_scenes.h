// Scenes shared by the benchmarks: each with a characteristic period and, where the exact solver
// covers it, a closed-form reference.
#pragma once

#include <string>
#include <vector>

#include "engine/scene.h"

namespace spinfold::bench {

struct BenchScene {
  std::string name;
  std::string summary;
  Scene scene;
};

std::vector<BenchScene> work_precision_scenes();

// The characteristic (orbital) period of a scene's motion [time]: 2πmR²/|M| on S²,
// 2πmR²/√(−MᵀηM) for a bounded orbit on H²; for scenes with a radial potential 2π/√Λ (physics.md §8.2).
double characteristic_period(const Scene& scene);

}  // namespace spinfold::bench
