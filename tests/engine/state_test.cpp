// The run's status names and descriptions (engine/state.h): what the readouts, the API and the CLI
// print, so every status has its own name and sentence.
#include "engine/state.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace spinfold {
namespace {

constexpr Status kStatuses[] = {Status::ok,
                                Status::non_finite,
                                Status::step_failed,
                                Status::degenerate_frame,
                                Status::out_of_range,
                                Status::diverged,
                                Status::inconsistent,
                                Status::event_stop,
                                Status::event_unresolved,
                                Status::too_many_events};

// The names are the enumerators' own spelling (the API's status values).
TEST(State, StatusNamesAreTheEnumerators) {
  EXPECT_EQ(status_name(Status::ok), "ok");
  EXPECT_EQ(status_name(Status::non_finite), "non_finite");
  EXPECT_EQ(status_name(Status::step_failed), "step_failed");
  EXPECT_EQ(status_name(Status::degenerate_frame), "degenerate_frame");
  EXPECT_EQ(status_name(Status::out_of_range), "out_of_range");
  EXPECT_EQ(status_name(Status::diverged), "diverged");
  EXPECT_EQ(status_name(Status::inconsistent), "inconsistent");
  EXPECT_EQ(status_name(Status::event_stop), "event_stop");
  EXPECT_EQ(status_name(Status::event_unresolved), "event_unresolved");
  EXPECT_EQ(status_name(Status::too_many_events), "too_many_events");
}

// One distinct sentence per status, for a person; none is empty or the bare name.
TEST(State, EveryStatusHasItsOwnDescription) {
  std::set<std::string> sentences;
  for (const Status status : kStatuses) {
    const std::string sentence(status_description(status));
    EXPECT_FALSE(sentence.empty()) << status_name(status);
    EXPECT_NE(sentence, status_name(status));
    EXPECT_TRUE(sentences.insert(sentence).second) << sentence;
  }
  // An ok run's sentence fits a finished run too (a sweep row, simulate's last sample): issue 35
  // found "running" there.
  EXPECT_EQ(std::string(status_description(Status::ok)).find("running"), std::string::npos);
}

// A new state starts at t = 0 in the scene's own chart, ok, with no coordinates yet.
TEST(State, DefaultIsTheGlobalChartAtTimeZero) {
  const State state;
  EXPECT_EQ(state.t, 0.0);
  EXPECT_TRUE(state.chart.global);
  EXPECT_EQ(state.chart.A, Mat3::Identity());
  EXPECT_EQ(state.chart.b, Vec3::Zero());
  EXPECT_EQ(state.status, Status::ok);
  EXPECT_EQ(state.y.size(), 0);
}

}  // namespace
}  // namespace spinfold
