// Reading a timeline (codec/timeline_json.h): the changes it gives and every refusal naming its entry.
// The API's rebuild route runs the same through HTTP (tests/server/api_test.cpp).
#include "codec/timeline_json.h"

#include <gtest/gtest.h>

#include "codec/scene_json.h"

namespace spinfold {
namespace {

using nlohmann::json;

Scene base() {
  return *parse_scene(json::parse(R"({"body": {"mass": 1.0}})")).scene;
}

std::string refused_field(const char* timeline, double until = 3.0) {
  const TimelineParse parsed = parse_timeline(base(), json::parse(timeline), until);
  EXPECT_TRUE(parsed.changes.empty());
  return parsed.errors.empty() ? "(accepted)" : parsed.errors.front().field;
}

TEST(TimelineJson, ChangesAreTheScenesInForceFromEachTime) {
  const TimelineParse parsed = parse_timeline(
      base(),
      json::parse(R"([{"t": 1, "patch": {"body": {"mass": 2}}}, {"t": 2, "patch": {"body": {"mass": 3}}}])"),
      3.0);
  ASSERT_TRUE(parsed.errors.empty());
  ASSERT_EQ(parsed.changes.size(), 2u);
  EXPECT_EQ(parsed.changes[0].t, 1.0);
  EXPECT_EQ(parsed.changes[1].scene.body.mass, 3.0);
  EXPECT_EQ(parsed.entries.size(), 2u);
  EXPECT_EQ(parsed.entries[1]["patch"]["body"]["mass"], 3);
}

TEST(TimelineJson, RefusalsNameTheEntry) {
  EXPECT_EQ(refused_field(R"({"t": 1})"), "timeline");
  EXPECT_EQ(refused_field(R"([1])"), "timeline[0]");
  EXPECT_EQ(refused_field(R"([{"t": 1, "patch": {}, "extra": 1}])"), "timeline[0].extra");
  EXPECT_EQ(refused_field(R"([{"patch": {}}])"), "timeline[0].t");
  EXPECT_EQ(refused_field(R"([{"t": 2, "patch": {}}, {"t": 1, "patch": {}}])"), "timeline[1].t");
  EXPECT_EQ(refused_field(R"([{"t": 4, "patch": {}}])"), "timeline[0].t");  // after until
  EXPECT_EQ(refused_field(R"([{"t": 1, "patch": []}])"), "timeline[0].patch");
  EXPECT_EQ(refused_field(R"([{"t": 1, "patch": {"body": {"mass": -2}}}])"), "timeline[0].patch.body.mass");
  // A change that would start the run over (a new start) belongs in the scene.
  EXPECT_EQ(refused_field(R"([{"t": 1, "patch": {"initial": {"r": 0.5}}}])"), "timeline[0].patch");
}

}  // namespace
}  // namespace spinfold
