// The player: advances playing sessions in real time, 50 times a second, on its own thread.
#pragma once

#include <atomic>
#include <thread>

namespace spinfold::server {

class SessionStore;

class Player {
 public:
  // max_steps: step attempts per session per tick (a stiff scene falls behind real time).
  Player(SessionStore& sessions, long max_steps);
  ~Player();  // stops and joins
  void stop();

 private:
  void loop();
  SessionStore& sessions_;
  long max_steps_;
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace spinfold::server
