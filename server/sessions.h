// Sessions: a scene and its timeline of parameter changes, the run they determine, its trail.
// Each is advanced and read under its own lock; the store owns them and expires idle ones.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/timeline.h"
#include "engine/trail.h"
#include "engine/validation.h"

namespace spinfold::server {

struct Session {
  std::mutex mutex;  // guards everything below
  // The session is a pure function of these two: the parameters at t = 0 (as created, restarted or
  // reset) and the changes since, in order, each as given and as the whole scene after it.
  Scene scene;
  nlohmann::ordered_json timeline = nlohmann::ordered_json::array();  // [{"t", "patch"}]
  std::vector<ParameterChange> changes;
  Simulation run;             // run.scene: the parameters in force now
  Trail trail;                // the path at fixed times since t = 0
  std::uint64_t version = 0;  // changes with every change of state: part of frame ETags
  std::string body;           // the serialized GET response of `body_version`
  std::uint64_t body_version = ~std::uint64_t{0};
  bool playing = false;  // advanced in real time by the server's player
  double rate = 1.0;     // simulated time per second of wall time while playing
  std::chrono::steady_clock::time_point last_used;
  // With a store (server/session_db.h): the row's version this memory matches (0: not stored, or
  // stale: the next find reloads it), when the row was last written, and play not yet stored.
  std::int64_t stored_version = 0;
  std::chrono::steady_clock::time_point stored_at;
  bool unsaved = false;
};

class SessionDb;

class SessionStore {
 public:
  // With `db`, every session is also a row of the store (session_store.cpp): the limit counts the
  // rows, find() reloads a session another process changed, erase() and expiry delete rows.
  SessionStore(std::size_t max_sessions, std::chrono::seconds idle_expiry, SessionDb* db = nullptr)
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
  std::uint64_t next_id_ = 1;
  SessionDb* db_ = nullptr;
  std::chrono::steady_clock::time_point last_sweep_{};  // guarded by mutex_
};

// A name of the session's state valid across the processes sharing its store and across CPUs
// (the session holds its lock): with a store, the row's version and the time (within one row
// version the scene and timeline are fixed, so they determine the state; replicas replay it to the
// same bits on one CPU class and within the bound of docs/performance.md on others); without one,
// or while the memory is ahead of the store, this process's version and a number of this process.
std::string state_tag(const Session& session);

// The operations below hold the session's lock. Each records a sample and bumps the version.

// Starts the session over at t = 0 of `scene` with an empty timeline (creation, reset, restart).
void restart(Session& session, const Scene& scene);

// Advances to `t` [time] recording the trail; false when `max_attempts` ran out first.
bool advance(Session& session, double t, std::uint64_t max_attempts);

// What a merge patch of the parameters did.
struct ChangeOutcome {
  enum Kind {
    unchanged,  // the patch changes nothing: the run is left as it is
    continued,  // new parameters from the current time and state on (a timeline entry)
    restarted,  // a new start (`initial`) or another surface: the run starts over at t = 0
  } kind = unchanged;
  std::string reason;              // one sentence for a person
  std::vector<FieldError> errors;  // non-empty: refused, nothing changed
};

// Applies a JSON merge patch of the scene at the current time.
ChangeOutcome change(Session& session, const nlohmann::json& patch);

// Rebuilds a session from a scene, a timeline [{"t", "patch"}] and a time: the state and the
// trail are those of the session that made the timeline, bit for bit. Refusals name the entry.
struct Rebuild {
  std::vector<FieldError> errors;  // non-empty: refused
  bool complete = true;            // false: max_attempts ran out before `until`
};
Rebuild rebuild(Session& session, const Scene& scene, const nlohmann::json& timeline, double until,
                std::uint64_t max_attempts);

}  // namespace spinfold::server
