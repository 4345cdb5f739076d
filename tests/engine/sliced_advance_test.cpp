// Slices of step attempts (engine/sliced_advance.h): the same state as one advance, bit for bit;
// the budget spent and what is left; the caller's stop before a slice.
#include "engine/sliced_advance.h"

#include <gtest/gtest.h>

#include "test_support.h"

namespace spinfold {
namespace {

Scene stepped() {
  Scene s = w5_scene();
  s.integrator = {"dop853", 0.01, 1e-12};
  return s;
}

TEST(SlicedAdvance, SlicesReachTheStateOfOneAdvanceBitForBit) {
  Simulation whole = start_simulation(stepped()), sliced = start_simulation(stepped());
  advance_to(whole, 20.0);
  std::uint64_t attempts = kNoStepLimit;
  int slices = 0;
  EXPECT_EQ(advance_in_slices(
                sliced, 20.0, attempts, [&] { return ++slices > 0; }, 7),
            Advanced::reached);
  EXPECT_GT(slices, 10) << "7 attempts a slice";
  EXPECT_TRUE(test::same_bits(whole.state, sliced.state));
  EXPECT_GE(kNoStepLimit - attempts, sliced.steps) << "every step spent an attempt";
}

TEST(SlicedAdvance, AttemptsRunOutAndTheCallerStopsBeforeASlice) {
  Simulation run = start_simulation(stepped());
  std::uint64_t attempts = 25;
  EXPECT_EQ(advance_in_slices(
                run, 1e3, attempts, [] { return true; }, 10),
            Advanced::out_of_attempts);
  EXPECT_EQ(attempts, 0u);
  EXPECT_LT(run.state.t, 1e3);
  // The caller's stop comes before any work.
  const State before = run.state;
  attempts = 1000;
  int asked = 0;
  EXPECT_EQ(advance_in_slices(
                run, 1e3, attempts, [&] { return ++asked < 3; }, 10),
            Advanced::stopped_by_caller);
  EXPECT_EQ(asked, 3);
  EXPECT_EQ(attempts, 980u) << "two slices of 10";
  EXPECT_GT(run.state.t, before.t);
}

}  // namespace
}  // namespace spinfold
