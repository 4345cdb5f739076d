// The sessions of this process (and, with a durable store, of every process sharing it): created,
// found, expired, saved and restored here (session_store.cpp). Each session is advanced and read
// under its own lock (session.h).
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "server/sessions/session.h"

namespace spinfold::server {

class Store;

class SessionStore {
 public:
  // With `db`, every session is also a row of the store (session_store.cpp): the limit counts the
  // rows, find() reloads a session another process changed, erase() and expiry delete rows.
  SessionStore(std::size_t max_sessions, std::chrono::seconds idle_expiry, Store* db = nullptr)
      : max_sessions_(max_sessions), idle_expiry_(idle_expiry), db_(db) {}

  // A new session at t = 0 of the scene, or nullptr when the store is full (after expiring idle
  // sessions).
  std::shared_ptr<Session> create(const Scene& scene, std::string& id);
  std::shared_ptr<Session> find(const std::string& id);
  bool erase(const std::string& id);
  std::size_t size();
  std::vector<std::shared_ptr<Session>> all();
  std::vector<std::pair<std::string, std::shared_ptr<Session>>> entries();

  // The durable store (session_store.cpp); without a db these do nothing.
  bool stored() const { return db_ != nullptr; }
  enum class Saved { stored, conflict, failed };
  // Commits the session (its lock held). conflict: another process changed or deleted it since this
  // one loaded it; failed: the store's error (on stderr). Either way nothing is written and the
  // memory reloads from the store at the next find (a new, never stored session is dropped).
  Saved save(const std::string& id, Session& session);
  // Stores the time of sessions played since their last save (at most once a second while playing).
  void save_played(const std::string& id, Session& session, bool now = false);
  void flush();           // save_played(now) for every session: at shutdown
  std::size_t restore();  // loads every stored session (paused) at start; returns how many
  // True when the store no longer has the session (another process deleted it or it expired): then
  // this process forgets it too. False without a store, or when the store cannot be read.
  bool deleted_elsewhere(const std::string& id);
  // Every 30 s (called by the player's ticks): forgets the sessions unused here for that long whose
  // rows are gone (deleted through another replica), so that memory does not hold them until expiry.
  void sweep_deleted_elsewhere();

 private:
  void expire_idle_locked();
  std::size_t count_locked();
  void expire_stored();
  std::shared_ptr<Session> checked(const std::string& id, std::shared_ptr<Session> memory);
  void forget(const std::string& id, const Session* session);
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<Session>> sessions_;
  std::size_t max_sessions_;
  std::chrono::seconds idle_expiry_;
  Store* db_ = nullptr;
  std::chrono::steady_clock::time_point last_sweep_{};  // guarded by mutex_
};

}  // namespace spinfold::server
