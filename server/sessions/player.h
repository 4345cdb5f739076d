// The player: advances playing sessions in real time, 120 times a second (more often than a display
// refreshes, so a live view has a new state for every frame it can show), on its own thread; once a
// minute it also gives the allocator's free memory back (server/sessions/heap_trim.h).
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <thread>

#include "server/sessions/heap_trim.h"

namespace spinfold::server {

class SessionStore;

class Player {
 public:
  static constexpr std::chrono::microseconds kTick{8333};
  // How often the player gives the allocator's free memory back (server/sessions/heap_trim.h).
  static constexpr std::chrono::seconds kHeapTrimInterval{60};
  // max_steps: step attempts per session per tick (a stiff scene falls behind real time).
  // played: called after each tick that advanced a session.
  Player(SessionStore& sessions, long max_steps, std::function<void()> played = {});
  ~Player();  // stops and joins
  void stop();

 private:
  void loop();
  SessionStore& sessions_;
  long max_steps_;
  std::function<void()> played_;
  std::atomic<bool> stopping_{false};
  HeapTrimmer heap_trimmer_{kHeapTrimInterval};
  std::thread thread_;
};

}  // namespace spinfold::server
