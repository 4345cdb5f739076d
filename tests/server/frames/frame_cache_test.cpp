// Encoded frames by ETag (server/frames/frame_cache.h): one render per frame for everyone asking, a
// failure kept by no one, least recently used frames dropped beyond the capacity.
#include "server/frames/frame_cache.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

namespace spinfold::server {
namespace {

using namespace std::chrono_literals;

// Eight viewers asking for one frame at once: one render, eight answers; a failed render reaches
// everyone waiting and is made again at the next ask.
TEST(FrameCache, OneRenderPerFrameForEveryoneAsking) {
  FrameCache cache(4);
  std::atomic<int> made{0};
  const auto make = [&] {
    ++made;
    std::this_thread::sleep_for(50ms);
    return std::make_shared<const std::vector<std::uint8_t>>(3, 7);
  };
  std::vector<std::thread> viewers;
  std::atomic<int> answers{0};
  for (int i = 0; i < 8; ++i)
    viewers.emplace_back([&] { answers += cache.get("\"frame\"", make)->size() == 3; });
  for (auto& v : viewers) v.join();
  EXPECT_EQ(made.load(), 1);
  EXPECT_EQ(answers.load(), 8);
  EXPECT_TRUE(cache.contains("\"frame\""));

  EXPECT_THROW(cache.get("\"broken\"", []() -> FrameBytes { throw std::runtime_error("no context"); }),
               std::runtime_error);
  EXPECT_FALSE(cache.contains("\"broken\""));
  EXPECT_EQ(cache.get("\"broken\"", make)->size(), 3u);
  for (const char* etag : {"\"1\"", "\"2\"", "\"3\"", "\"4\""}) cache.get(etag, make);
  EXPECT_FALSE(cache.contains("\"frame\""));  // least recently used, beyond the capacity
}

FrameBytes bytes(std::uint8_t value) {
  return std::make_shared<const std::vector<std::uint8_t>>(1, value);
}

// A hit is served from memory: `make` is not called again, and the bytes are the same object.
TEST(FrameCache, HitServesTheKeptFrameWithoutMaking) {
  FrameCache cache(2);
  int made = 0;
  const FrameBytes first = cache.get("\"a\"", [&] {
    ++made;
    return bytes(1);
  });
  const FrameBytes again = cache.get("\"a\"", [&] {
    ++made;
    return bytes(2);
  });
  EXPECT_EQ(made, 1);
  EXPECT_EQ(again, first);
  EXPECT_EQ((*again)[0], 1);
}

// Using a frame makes it the most recent: with capacity 2, after a, b, a again, c, it is b that
// goes, not a.
TEST(FrameCache, EvictsTheLeastRecentlyUsedNotTheOldest) {
  FrameCache cache(2);
  cache.get("\"a\"", [] { return bytes(1); });
  cache.get("\"b\"", [] { return bytes(2); });
  cache.get("\"a\"", [] { return bytes(9); });
  cache.get("\"c\"", [] { return bytes(3); });
  EXPECT_TRUE(cache.contains("\"a\""));
  EXPECT_FALSE(cache.contains("\"b\""));
  EXPECT_TRUE(cache.contains("\"c\""));
  int made = 0;
  EXPECT_EQ((*cache.get("\"b\"",
                        [&] {
                          ++made;
                          return bytes(4);
                        }))[0],
            4);  // made again
  EXPECT_EQ(made, 1);
}

// An evicted frame's bytes stay valid for whoever holds them (shared, not owned by the cache).
TEST(FrameCache, EvictedBytesOutliveTheEntry) {
  FrameCache cache(1);
  const FrameBytes held = cache.get("\"a\"", [] { return bytes(7); });
  cache.get("\"b\"", [] { return bytes(8); });
  EXPECT_FALSE(cache.contains("\"a\""));
  ASSERT_TRUE(held);
  EXPECT_EQ((*held)[0], 7);
}

}  // namespace
}  // namespace spinfold::server
