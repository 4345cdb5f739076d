// Sessions: one simulation each, advanced and read under its own lock. The store owns them and
// expires idle ones.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/simulation.h"

namespace spinfold::server {

struct Session {
  std::mutex mutex;  // guards everything below
  Scene scene;
  Simulation run;
  std::uint64_t version = 0;                       // changes with every change of state: part of frame ETags
  std::vector<nlohmann::ordered_json> trajectory;  // a sample after creation, each advance and reset
  std::vector<Vec3> trail;                         // positions of those samples, for frames
  std::size_t reported_events = 0;
  std::string body;  // the serialized GET response of `body_version`
  std::uint64_t body_version = ~std::uint64_t{0};
  bool playing = false;  // advanced in real time by the server's player
  double rate = 1.0;     // simulated time per second of wall time while playing
  std::chrono::steady_clock::time_point last_used;
};

class SessionStore {
 public:
  SessionStore(std::size_t max_sessions, std::chrono::seconds idle_expiry)
      : max_sessions_(max_sessions), idle_expiry_(idle_expiry) {}

  // A new session at t = start_time, or nullptr when the store is full (after expiring idle sessions).
  std::shared_ptr<Session> create(const Scene& scene, std::string& id, double start_time = 0.0);
  std::shared_ptr<Session> find(const std::string& id);
  bool erase(const std::string& id);
  std::size_t size();
  std::vector<std::shared_ptr<Session>> all();

 private:
  void expire_idle_locked();
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<Session>> sessions_;
  std::size_t max_sessions_;
  std::chrono::seconds idle_expiry_;
  std::uint64_t next_id_ = 1;
};

// The most recent samples kept per session (older ones are dropped in halves).
inline constexpr std::size_t kMaxTrajectory = 20000;

// Records the session's current state as a trajectory sample and a trail point (lock held).
void record_sample(Session& session);

}  // namespace spinfold::server
