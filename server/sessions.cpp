#include "server/sessions.h"

#include <cstdio>

#include "codec/sample_json.h"
#include "engine/chart.h"

namespace spinfold::server {

void record_sample(Session& session) {
  const std::span<const DegenerateEvent> fresh(session.run.events.data() + session.reported_events,
                                               session.run.events.size() - session.reported_events);
  session.trajectory.push_back(sample_to_json(session.run, fresh));
  session.reported_events = session.run.events.size();
  session.trail.push_back(global_embedding(session.scene, session.run.state).X);
  if (session.trajectory.size() > kMaxTrajectory) {
    session.trajectory.erase(session.trajectory.begin(), session.trajectory.begin() + kMaxTrajectory / 2);
    session.trail.erase(session.trail.begin(), session.trail.begin() + kMaxTrajectory / 2);
  }
  ++session.version;
}

std::shared_ptr<Session> SessionStore::create(const Scene& scene, std::string& id, double start_time) {
  const std::lock_guard lock(mutex_);
  expire_idle_locked();
  if (sessions_.size() >= max_sessions_) return nullptr;
  char text[32];
  std::snprintf(text, sizeof text, "%016llx",
                static_cast<unsigned long long>(next_id_++ * 0x9E3779B97F4A7C15ull));
  id = text;
  auto session = std::make_shared<Session>();
  session->scene = scene;
  session->run = start_simulation(scene, start_time);
  session->last_used = std::chrono::steady_clock::now();
  record_sample(*session);
  sessions_[id] = session;
  return session;
}

std::shared_ptr<Session> SessionStore::find(const std::string& id) {
  const std::lock_guard lock(mutex_);
  const auto it = sessions_.find(id);
  if (it == sessions_.end()) return nullptr;
  it->second->last_used = std::chrono::steady_clock::now();
  return it->second;
}

bool SessionStore::erase(const std::string& id) {
  const std::lock_guard lock(mutex_);
  return sessions_.erase(id) > 0;
}

std::size_t SessionStore::size() {
  const std::lock_guard lock(mutex_);
  return sessions_.size();
}

std::vector<std::shared_ptr<Session>> SessionStore::all() {
  const std::lock_guard lock(mutex_);
  std::vector<std::shared_ptr<Session>> list;
  for (const auto& [id, session] : sessions_) list.push_back(session);
  return list;
}

void SessionStore::expire_idle_locked() {
  const auto now = std::chrono::steady_clock::now();
  for (auto it = sessions_.begin(); it != sessions_.end();)
    it = now - it->second->last_used > idle_expiry_ ? sessions_.erase(it) : std::next(it);
}

}  // namespace spinfold::server
