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
  FrameCache cache(4, 1 << 20);
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
  FrameCache cache(2, 1 << 20);
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
  FrameCache cache(2, 1 << 20);
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
  FrameCache cache(1, 1 << 20);
  const FrameBytes held = cache.get("\"a\"", [] { return bytes(7); });
  cache.get("\"b\"", [] { return bytes(8); });
  EXPECT_FALSE(cache.contains("\"a\""));
  ASSERT_TRUE(held);
  EXPECT_EQ((*held)[0], 7);
}

// Bounded in bytes too: frames of 400 bytes under a 1000-byte bound keep two; a frame over the whole
// bound is served to who asked and not kept.
TEST(FrameCache, BoundedInBytesAsWellAsFrames) {
  FrameCache cache(100, 1000);
  const auto of = [](std::size_t n) {
    return [n] { return std::make_shared<const std::vector<std::uint8_t>>(n, 1); };
  };
  cache.get("\"a\"", of(400));
  cache.get("\"b\"", of(400));
  EXPECT_EQ(cache.bytes(), 800u);
  cache.get("\"c\"", of(400));
  EXPECT_FALSE(cache.contains("\"a\""));
  EXPECT_TRUE(cache.contains("\"b\""));
  EXPECT_EQ(cache.bytes(), 800u);
  EXPECT_EQ(cache.get("\"huge\"", of(5000))->size(), 5000u);
  EXPECT_FALSE(cache.contains("\"huge\""));
  EXPECT_LE(cache.bytes(), 1000u);
}

// A deleted session's frames go at once (frame_etag starts with the session's id), the others stay.
TEST(FrameCache, DropsTheFramesOfOnePrefix) {
  FrameCache cache(100, 1 << 20);
  for (const char* etag : {"W/\"s1-a\"", "W/\"s1-b\"", "W/\"s10-a\"", "W/\"s2-a\""})
    cache.get(etag, [] { return bytes(1); });
  cache.drop("W/\"s1-");
  EXPECT_FALSE(cache.contains("W/\"s1-a\""));
  EXPECT_FALSE(cache.contains("W/\"s1-b\""));
  EXPECT_TRUE(cache.contains("W/\"s10-a\""));
  EXPECT_TRUE(cache.contains("W/\"s2-a\""));
  EXPECT_EQ(cache.bytes(), 2u);
}

}  // namespace
}  // namespace spinfold::server
