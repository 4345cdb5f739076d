// spinfold-bench oracle-sweep: thousands of random scenes of every regime, each run with every
// integrator and compared with the independent oracle (oracle/); a table per integrator and regime.
#pragma once

#include <string>

namespace spinfold::bench {

struct OracleSweepOptions {
  int scenes = 1000;            // per regime
  unsigned long long seed = 1;  // the first seed; scene i of a regime uses seed + i
  double t_end = 2.0;
  std::string regime;      // "" all
  std::string integrator;  // "" all
  bool verbose = false;    // print every failing scene's JSON
};

int run_oracle_sweep(const OracleSweepOptions& options);

}  // namespace spinfold::bench
