#include "server/player.h"

#include <chrono>
#include <mutex>

#include "server/sessions.h"

namespace spinfold::server {

Player::Player(SessionStore& sessions, long max_steps)
    : sessions_(sessions), max_steps_(max_steps), thread_([this] { loop(); }) {}

Player::~Player() {
  stop();
  thread_.join();
}

void Player::stop() {
  stopping_ = true;
}

void Player::loop() {
  auto last = std::chrono::steady_clock::now();
  while (!stopping_) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const auto now = std::chrono::steady_clock::now();
    const double wall = std::chrono::duration<double>(now - last).count();
    last = now;
    for (const auto& s : sessions_.all()) {
      const std::lock_guard lock(s->mutex);
      if (!s->playing) continue;
      // A stiff scene falls behind real time rather than holding the player from the others.
      advance(*s, s->run.state.t + s->rate * wall, static_cast<std::uint64_t>(max_steps_));
      if (s->run.state.status != Status::ok) s->playing = false;
    }
  }
}

}  // namespace spinfold::server
