// Giving the allocator's free memory back to the system. glibc keeps freed chunks inside its arenas
// (up to 8 per core; a server thread allocates from one of them) and returns only the free space at
// the top of each. Under the soak's mixed load (docs/performance.md) that free space grew ~2-3 MiB
// a minute, in every arena, while the memory in use stayed flat (no leak): malloc_trim(0) returns
// the free pages inside the arenas as well.
#pragma once

#include <chrono>

namespace spinfold::server {

// malloc_trim(0) with glibc (nothing elsewhere): true when memory was given back.
bool return_free_heap();

// Calls return_free_heap() once per interval, from a thread that ticks often (the player).
class HeapTrimmer {
 public:
  using Clock = std::chrono::steady_clock;
  explicit HeapTrimmer(Clock::duration interval, Clock::time_point start = Clock::now())
      : interval_(interval), last_(start) {}
  // True when this tick trimmed (an interval since the last trim, or the start, has passed).
  bool tick(Clock::time_point now = Clock::now());

 private:
  Clock::duration interval_;
  Clock::time_point last_;
};

}  // namespace spinfold::server
