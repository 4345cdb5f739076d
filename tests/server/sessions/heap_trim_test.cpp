// Giving the allocator's free memory back (server/sessions/heap_trim.h): freed chunks below a live one stay
// resident until trimmed; the trimmer trims once per interval.
#include "server/sessions/heap_trim.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace spinfold::server {
namespace {

using namespace std::chrono_literals;

// VmRSS of this process [KiB].
long rss_kib() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

#if defined(__GLIBC__)
// 48 MiB in 32 KiB chunks (each below the mmap threshold, so from an arena), all freed but the last:
// the free space lies below a live chunk, where free() does not give it back, as in the soak.
TEST(HeapTrim, ReturnsFreeChunksInsideTheArenas) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the sanitizers' allocator, not glibc's, holds this build's memory";
#endif
  constexpr std::size_t kChunk = 32 << 10, kCount = 1536;
  long before = 0, after = 0;
  std::thread worker([&] {  // a thread of its own, as the server's workers
    std::vector<char*> chunks;
    for (std::size_t i = 0; i < kCount; ++i) {
      chunks.push_back(static_cast<char*>(std::malloc(kChunk)));
      std::memset(chunks.back(), static_cast<int>(i), kChunk);  // resident
    }
    for (std::size_t i = 0; i + 1 < kCount; ++i) std::free(chunks[i]);
    before = rss_kib();
    const auto start = std::chrono::steady_clock::now();
    EXPECT_TRUE(return_free_heap());
    const auto took = std::chrono::steady_clock::now() - start;
    after = rss_kib();
    std::printf("malloc_trim: %ld → %ld KiB in %.2f ms\n", before, after,
                std::chrono::duration<double, std::milli>(took).count());
    std::free(chunks.back());
  });
  worker.join();
  EXPECT_GT(before - after, 32L << 10) << "RSS " << before << " → " << after << " KiB";
}
#endif

TEST(HeapTrim, TrimsOncePerInterval) {
  const auto t0 = HeapTrimmer::Clock::time_point{} + 1h;
  HeapTrimmer trimmer(60s, t0);
  EXPECT_FALSE(trimmer.tick(t0));
  EXPECT_FALSE(trimmer.tick(t0 + 59s));
  EXPECT_TRUE(trimmer.tick(t0 + 60s));
  EXPECT_FALSE(trimmer.tick(t0 + 61s));
  EXPECT_FALSE(trimmer.tick(t0 + 119s));
  EXPECT_TRUE(trimmer.tick(t0 + 125s));
  EXPECT_FALSE(trimmer.tick(t0 + 184s));  // the next interval counts from the trim
  EXPECT_TRUE(trimmer.tick(t0 + 185s));
}

}  // namespace
}  // namespace spinfold::server
