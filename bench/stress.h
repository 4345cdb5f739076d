// Numerical stability stress suite. Each case runs at a size: 1 is the long benchmark version
// (spinfold-bench stress, results in docs/numerics.md); the test suite runs small sizes.
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

namespace spinfold::bench {

struct StressResult {
  bool passed = false;
  std::string criterion;                                // the pass criterion, in words
  std::vector<std::pair<std::string, double>> figures;  // measured numbers
};

struct StressCase {
  const char* name;
  const char* summary;
  StressResult (*run)(double size);
};

std::span<const StressCase> stress_cases();

// Runs every case (or those named) at `size`, prints a Markdown table; 0 if all passed.
int run_stress(const std::vector<std::string>& names, double size);

}  // namespace spinfold::bench
