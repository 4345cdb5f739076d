#include "server/player.h"

#include <chrono>
#include <mutex>

#include "server/sessions.h"

namespace spinfold::server {

Player::Player(SessionStore& sessions, long max_steps)
    : sessions_(sessions), max_steps_(max_steps), thread_([this] { loop(); }) {}

Player::~Player() {
  stop();
}

void Player::stop() {
  stopping_ = true;
  // Joined here too, so that a flush after stop() stores the last tick.
  if (thread_.joinable() && thread_.get_id() != std::this_thread::get_id()) thread_.join();
}

void Player::loop() {
  auto last = std::chrono::steady_clock::now();
  while (!stopping_) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const auto now = std::chrono::steady_clock::now();
    const double wall = std::chrono::duration<double>(now - last).count();
    last = now;
    for (const auto& [id, s] : sessions_.entries()) {
      const std::lock_guard lock(s->mutex);
      if (!s->playing) continue;
      // A stiff scene falls behind real time rather than holding the player from the others.
      advance(*s, s->run.state.t + s->rate * wall, static_cast<std::uint64_t>(max_steps_));
      s->unsaved = true;
      if (s->run.state.status != Status::ok) s->playing = false;
      sessions_.save_played(id, *s);  // with a store: about once a second, and when it stops
    }
  }
}

}  // namespace spinfold::server
