// The engine against the oracle (oracle.h) on one scene: each integrator is run through the
// engine's public path (the scene's JSON text read by the codec, start_simulation, advance_to, as
// `spinfold simulate` does) and its state at T compared on chart-free quantities.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "oracle/oracle.h"

namespace spinfold {
struct Scene;
struct State;
}  // namespace spinfold

namespace spinfold::oracle {

// What an integrator is run with in the differential test, and the bound its answer must meet:
// 1e-8 (positions in lengths, frames relative to |e|, energy relative to the scene's energy scale)
// for every integrator at these settings, except implicit_midpoint (order 2): 1e-5 at dt = 2e-5. Fixed steps:
// rk4, gauss4 1e-4, split4 5e-5, gauss6 5e-4, split6 2.5e-4; dop853 and auto at tolerance 1e-12.
struct IntegratorCase {
  std::string name;
  double dt = 0.01, tolerance = 1e-12;
  double bound = 1e-8;
};
std::vector<IntegratorCase> integrator_cases();  // every catalog name and "auto"

struct Verdict {
  std::string integrator;
  bool refused = false;     // the engine refused the scene for this integrator (a 422 reason)
  std::string message;      // the refusal, the engine's stop status, or ""
  bool stopped = false;     // the engine's status at T was not ok
  bool incomplete = false;  // the engine ran out of max_attempts (not a verdict)
  Difference diff;
  double error = 0;  // max of the differences
  bool pass = false;
  std::string scene_json;  // the scene as run (replay: spinfold simulate FILE --t-end T)
};

// An engine state (any chart) as compare() takes it: mapped in 50 digits into the oracle's start
// frame of `oracle_scene` (the same scene as read by read_scene), and in the engine's own chart.
struct EngineBody {
  Body3 in_start_frame;
  Body3 in_chart;
};
EngineBody engine_body(const Scene& scene, const State& state, const OracleScene& oracle_scene);

// The scene with the case's integrator settings, as JSON text.
std::string with_integrator(std::string_view scene_json, const IntegratorCase& c);

// Runs the engine on `scene_json` (with c's settings) to t_end and compares with `reference`.
Verdict check(std::string_view scene_json, const IntegratorCase& c, double t_end, const OracleScene& scene,
              const OracleRun& reference, std::uint64_t max_attempts = 20'000'000);

// A random scene of the regime named (the test's and the sweep's generator; deterministic in the
// seed). Regimes: see regimes().
std::string random_scene(const std::string& regime, unsigned long long seed);
const std::vector<std::string>& regimes();
// The regimes on surfaces whose curvature varies (torus, spheroid, bump, catenoid, axis, zero_circle,
// inner_equator, friction):
// there the chart's splitting methods and `exact` are refused, not run.
bool varying_regime(const std::string& regime);

}  // namespace spinfold::oracle
