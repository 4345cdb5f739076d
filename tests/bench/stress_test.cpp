// The stress suite's short versions: every case must pass at a small size.
#include "bench/stress.h"

#include <gtest/gtest.h>

namespace spinfold::bench {
namespace {

class StressShort : public ::testing::TestWithParam<StressCase> {};

TEST_P(StressShort, Passes) {
  const StressResult r = GetParam().run(0.001);
  std::string figures;
  for (const auto& [label, value] : r.figures) figures += label + " = " + std::to_string(value) + "\n";
  EXPECT_TRUE(r.passed) << r.criterion << "\n" << figures;
}

INSTANTIATE_TEST_SUITE_P(Cases, StressShort,
                         ::testing::ValuesIn(stress_cases().begin(), stress_cases().end()),
                         [](const auto& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace spinfold::bench
