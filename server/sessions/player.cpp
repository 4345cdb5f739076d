#include "server/sessions/player.h"

#include <chrono>
#include <limits>
#include <mutex>

#include "server/sessions/session_store.h"

namespace spinfold::server {

Player::Player(SessionStore& sessions, long max_steps, std::function<void()> played)
    : sessions_(sessions), max_steps_(max_steps), played_(std::move(played)), thread_([this] { loop(); }) {}

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
  auto next = last;
  while (!stopping_) {
    next += kTick;  // on a fixed schedule: the sleep's overshoot does not slow the ticks down
    const auto now_before = std::chrono::steady_clock::now();
    if (next < now_before) next = now_before;  // fell behind (a stiff scene): no burst to catch up
    std::this_thread::sleep_until(next);
    const auto now = std::chrono::steady_clock::now();
    const double wall = std::chrono::duration<double>(now - last).count();
    last = now;
    bool played = false;
    for (const auto& [id, s] : sessions_.entries()) {
      const std::lock_guard lock(s->mutex);
      if (!s->playing) continue;
      played = true;
      // A stiff scene falls behind real time rather than holding the player from the others.
      advance(*s, s->run.state.t + s->rate * wall, static_cast<std::uint64_t>(max_steps_),
              std::numeric_limits<double>::infinity());
      s->unsaved = true;
      if (s->run.state.status != Status::ok) s->playing = false;
      sessions_.save_played(id, *s);  // with a store: about once a second, and when it stops
    }
    if (played && played_) played_();
    sessions_.sweep_deleted_elsewhere();  // with a store: every 30 s
    heap_trimmer_.tick(now);              // once a minute
  }
}

}  // namespace spinfold::server
