#include "bench/oracle_sweep.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include "oracle/differential.h"

namespace spinfold::bench {

int run_oracle_sweep(const OracleSweepOptions& o) {
  using namespace spinfold::oracle;
  struct Cell {
    int runs = 0, refused = 0, beyond = 0;
    double worst = 0;
    unsigned long long worst_seed = 0;
  };
  std::map<std::pair<std::string, std::string>, Cell> table;  // (integrator, regime)
  std::vector<IntegratorCase> cases;
  for (const IntegratorCase& c : integrator_cases())
    if (o.integrator.empty() || c.name == o.integrator) cases.push_back(c);
  int oracle_failures = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (const std::string& regime : regimes()) {
    if (!o.regime.empty() && regime != o.regime) continue;
    for (int i = 0; i < o.scenes; ++i) {
      const unsigned long long seed = o.seed + static_cast<unsigned long long>(i);
      const std::string text = random_scene(regime, seed);
      const OracleScene scene = read_scene(text);
      const OracleRun ref = run_oracle(scene, o.t_end);
      if (!ref.ok) {
        ++oracle_failures;
        std::printf("oracle failed (%s) on %s seed %llu\n", ref.error.c_str(), regime.c_str(), seed);
        continue;
      }
      for (const IntegratorCase& c : cases) {
        const Verdict v = check(text, c, o.t_end, scene, ref);
        Cell& cell = table[{c.name, regime}];
        if (v.refused) {
          ++cell.refused;
          if (!v.pass) ++cell.beyond;
          continue;
        }
        ++cell.runs;
        if (!v.pass) ++cell.beyond;
        if (!(v.error <= cell.worst)) cell.worst = v.error, cell.worst_seed = seed;
        if (!v.pass && o.verbose)
          std::printf(
              "--- %s %s seed %llu: error %.3g (position %.3g, velocity %.3g, frame %.3g, energy %.3g) "
              "%s\n%s\n",
              c.name.c_str(), regime.c_str(), seed, v.error, v.diff.position, v.diff.velocity, v.diff.frame,
              v.diff.energy, v.message.c_str(), v.scene_json.c_str());
      }
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("| integrator | bound | regime | runs | refused | beyond bound | worst error | worst seed |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const IntegratorCase& c : cases)
    for (const std::string& regime : regimes()) {
      const auto it = table.find({c.name, regime});
      if (it == table.end()) continue;
      const Cell& cell = it->second;
      std::printf("| %s | %.0e | %s | %d | %d | %d | %.2g | %llu |\n", c.name.c_str(), c.bound,
                  regime.c_str(), cell.runs, cell.refused, cell.beyond, cell.worst, cell.worst_seed);
    }
  std::printf("\n%d oracle failures; %.1f s; T = %g; seeds %llu..%llu per regime\n", oracle_failures, seconds,
              o.t_end, o.seed, o.seed + static_cast<unsigned long long>(o.scenes) - 1);
  int beyond = 0;
  for (const auto& [key, cell] : table) beyond += cell.beyond;
  return beyond == 0 && oracle_failures == 0 ? 0 : 1;
}

}  // namespace spinfold::bench
