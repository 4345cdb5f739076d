// RFC 9110 §14's byte ranges (server/http/byte_ranges.h), case by case; the recording file's route
// is checked over HTTP in tests/server/jobs/recordings_test.cpp.
#include "server/http/byte_ranges.h"

#include <gtest/gtest.h>

#include <string>

namespace spinfold::server {
namespace {

using Kind = RangeAnswer::Kind;

TEST(ByteRanges, OneSatisfiableRangeIsServedWithinTheFile) {
  const struct {
    const char* header;
    std::uint64_t first, last;
  } cases[] = {
      {"bytes=0-3", 0, 3},
      {"bytes=5-", 5, 9},
      {"bytes=-3", 7, 9},
      {"bytes=-30", 0, 9},
      {"bytes=2-2", 2, 2},
      {"Bytes=0-99", 0, 9},
      {" bytes = 4-6 ", 4, 6},
      {"bytes=, 4-6 ,", 4, 6},
      {"bytes=0-18446744073709551615", 0, 9},
      {"bytes=1-99999999999999999999999", 1, 9},
  };
  for (const auto& c : cases) {
    const RangeAnswer a = answer_range(c.header, 10);
    EXPECT_EQ(a.kind, Kind::partial) << c.header;
    EXPECT_EQ(a.first, c.first) << c.header;
    EXPECT_EQ(a.last, c.last) << c.header;
    EXPECT_EQ(a.content_range, "bytes " + std::to_string(c.first) + "-" + std::to_string(c.last) + "/10")
        << c.header;
  }
}

// §14.1.2: 416 with `bytes */L` when no byte asked for is in the file (a first at or beyond the
// end, of any size; a suffix of 0; any range of an empty file).
TEST(ByteRanges, NothingSatisfiableIs416WithTheLength) {
  for (const char* header :
       {"bytes=10-", "bytes=10-15", "bytes=99999999-", "bytes=99999999999999999999999-", "bytes=-0"}) {
    const RangeAnswer a = answer_range(header, 10);
    EXPECT_EQ(a.kind, Kind::unsatisfiable) << header;
    EXPECT_EQ(a.content_range, "bytes */10") << header;
  }
  EXPECT_EQ(answer_range("bytes=0-", 0).kind, Kind::unsatisfiable);
  EXPECT_EQ(answer_range("bytes=-5", 0).content_range, "bytes */0");
}

// Ignored (the whole file): no header, a unit this server does not know (§14.2: MUST ignore),
// invalid syntax (a last before the first, a sign, no dash, no list), and several ranges (the
// documented single-range policy: no multipart/byteranges).
TEST(ByteRanges, OtherUnitsInvalidSyntaxAndSeveralRangesAskForTheWhole) {
  for (const char* header :
       {"", "items=0-1", "bytes", "bytes=", "bytes=5-2", "bytes=+1-2", "bytes=1", "bytes=a-b", "bytes=1-2-3",
        "bytes=--1", "bytes=0-1,4-5", "bytes=0-1, -2", "bytesx=0-1"}) {
    const RangeAnswer a = answer_range(header, 10);
    EXPECT_EQ(a.kind, Kind::whole) << header;
    EXPECT_TRUE(a.content_range.empty()) << header;
  }
}

}  // namespace
}  // namespace spinfold::server
