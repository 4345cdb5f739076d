// "Something may have changed": a counter bumped after every change of any session (a request
// that is not a GET, a player tick) that live streams wait on instead of polling.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace spinfold::server {

class ChangeSignal {
 public:
  std::uint64_t generation() {
    const std::lock_guard lock(mutex_);
    return generation_;
  }
  void notify() {
    {
      const std::lock_guard lock(mutex_);
      ++generation_;
    }
    changed_.notify_all();
  }
  // Waits until the generation is no longer `seen` or the deadline passes; returns the generation.
  std::uint64_t wait(std::uint64_t seen, std::chrono::steady_clock::time_point deadline) {
    std::unique_lock lock(mutex_);
    changed_.wait_until(lock, deadline, [&] { return generation_ != seen; });
    return generation_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::uint64_t generation_ = 0;
};

}  // namespace spinfold::server
