#include "bench/companions_bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "bench/timing.h"
#include "codec/presets.h"
#include "codec/scene_json.h"
#include "engine/trail.h"

namespace spinfold::bench {

namespace {

// The spin fan preset widened to 8 companions (spins 0.25 … 2), with every body on `integrator`.
Scene fan_of_eight(const std::string& integrator) {
  nlohmann::json document = nlohmann::json::parse(find_preset("spin_fan_sphere")->json);
  document["vary"]["values"] = {0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0};
  document["integrator"]["name"] = integrator;
  return *parse_scene(document).scene;
}

}  // namespace

int run_companions_bench(int repeats, double until) {
  std::printf(
      "| integrator | what | main body alone ms | the 9 bodies alone, summed ms | main + 8 companions ms | "
      "ratio to the sum |\n");
  std::printf("| --- | --- | --- | --- | --- | --- |\n");
  for (const char* integrator : {"exact", "dop853"}) {
    const Scene eight = fan_of_eight(integrator);
    Scene one = eight;
    one.companions.clear();
    one.companions_source.clear();
    for (const bool trail : {false, true}) {
      const auto run = [&](const Scene& scene) {
        return median_ms(repeats, [&] {
          Simulation sim = start_simulation(scene);
          Trail t;
          if (trail)
            advance_sampling_trail(sim, t, until);
          else
            advance_to(sim, until);
        });
      };
      const double a = run(one), b = run(eight);
      double sum = a;
      for (std::size_t i = 0; i < eight.companions.size(); ++i) sum += run(companion_scene(eight, i));
      std::printf("| %s | advance to t = %g%s | %.2f | %.2f | %.2f | %.2f |\n", integrator, until,
                  trail ? " with the trail" : "", a, sum, b, b / sum);
    }
  }
  return 0;
}

}  // namespace spinfold::bench
