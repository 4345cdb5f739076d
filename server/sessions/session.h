// A session: a scene and its timeline of parameter changes, the run they determine, its trail.
// Each is advanced and read under its own lock; SessionStore (session_store.h) owns them and
// expires idle ones.
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
  // With a store (server/store/store.h): the row's version this memory matches (0: not stored, or
  // stale: the next find reloads it), when the row was last written, and play not yet stored.
  std::int64_t stored_version = 0;
  std::chrono::steady_clock::time_point stored_at;
  bool unsaved = false;
};

// A name of the session's state valid across the processes sharing its store and across CPUs
// (the session holds its lock): with a store, the row's version and the time (within one row
// version the scene and timeline are fixed, so they determine the state; replicas replay it to the
// same bits on one CPU class and within the bound of docs/performance.md on others); without one,
// or while the memory is ahead of the store, this process's version and a number of this process.
std::string state_tag(const Session& session);

// The session's state as its answers and events send it: the sample (codec/sample_json.h), and
// "circle": the circle its path is read as (engine/path_circle.h), {"measured", "predicted"}
// [length] (null where none yet or none at all) and "line", the readout's words ("" where the
// curvature varies). Needs the session's lock.
nlohmann::ordered_json session_sample(const Session& session);

// The operations below hold the session's lock. Each records a sample and bumps the version.

// Starts the session over at t = 0 of `scene` with an empty timeline (creation, reset, restart).
void restart(Session& session, const Scene& scene);

// How an advance ended.
enum class AdvanceEnd {
  reached,   // at `t`, or stopped there by the run's own status
  attempts,  // `max_attempts` ran out first: the progress is kept
  seconds,   // `max_seconds` of work ran out first: the progress is kept
};
// Steps are taken in slices of this many attempts; the clock is read between slices.
inline constexpr std::uint64_t kAdvanceSliceAttempts = 4096;
// Advances to `t` [time] recording the trail, making at most `max_attempts` step attempts and
// working at most about `max_seconds` [s] (to the end of the slice running then). The state is the
// same however the advance was cut: continuing gives the bits of one uncut advance.
AdvanceEnd advance(Session& session, double t, std::uint64_t max_attempts, double max_seconds);

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
