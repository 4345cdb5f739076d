// What every handler shares: the server's state (sessions, the render pool, the frame cache, the
// open streams and live viewers) and the few answers built the same way on every route.
#pragma once

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

#include "server/frames/frame_cache.h"
#include "server/frames/frames.h"
#include "server/frames/render_pool.h"
#include "server/http/quota.h"
#include "server/jobs/recordings.h"
#include "server/jobs/work_precision_jobs.h"
#include "server/options.h"
#include "server/sessions/change_signal.h"
#include "server/sessions/session_store.h"
#include "server/store/store.h"

namespace httplib {
struct Response;
}

namespace spinfold::server {

// One live stream's picture (GET …/live), steered by PATCH …/live?viewer=.
struct Viewer {
  std::mutex mutex;  // guards the two below
  FrameRequest request;
  std::uint64_t generation = 0;  // bumped by every PATCH
};

struct ServerContext {
  ServerOptions options;
  std::unique_ptr<Store> db;  // the durable store (options.store, else options.data_dir), or none
  SessionStore sessions;
  RenderPool renderer{options.render_threads};
  FrameCache frames{options.limits.frame_cache_frames, options.limits.frame_cache_bytes};
  Recordings recordings{options.limits, renderer, db.get()};  // after the pool and the store
  WorkPrecisionJobs work_precision{options.limits};
  ChangeSignal changes;              // bumped after every change of a session (live streams wait on it)
  std::atomic<int> open_streams{0};  // event and live streams now open
  std::mutex viewers_mutex;          // guards viewers
  std::map<std::string, std::weak_ptr<Viewer>> viewers;  // by "session id/viewer"
  ClientQuotas quotas{options.limits};                   // per client address (server/http/quota.h)
  std::atomic<bool> stopping{false};                     // set by stop(): ends the event streams

  explicit ServerContext(ServerOptions o)
      : options(std::move(o)),
        db(open_store(options.store, options.data_dir)),
        sessions(options.limits.max_sessions, options.limits.idle_expiry, db.get()) {
    sessions.restore();
  }
};

// A scene, or {"preset": name}; `field` names it in errors ("" at the top, "scene" in a link):
// ApiError 422 naming each refused field.
Scene scene_of(const nlohmann::json& body, const std::string& field);

// The session with this id, or ApiError 404 (the same answer on every route).
std::shared_ptr<Session> find_session(ServerContext& server, const std::string& id);

// Holds one of the server's and the client's stream slots while alive, or ApiError 429 when
// either limit is reached.
std::shared_ptr<void> open_stream(ServerContext& server, const std::string& client);

// Commits a change before it is acknowledged (the session's lock held): ApiError 409 when another
// server changed the session meanwhile, 503 when the store cannot be written (nothing is kept).
void commit(ServerContext& server, const std::string& id, Session& s);

// Deletes the session from memory and store, or ApiError 404 (503 when the store cannot be written).
void remove_session(ServerContext& server, const std::string& id);

// X-Spinfold-Provenance: "version=…; commit=…; scene_hash=…; integrator=…; dt=…; tolerance=…" of
// the scene in force now (codec/provenance.h; numbers in shortest form).
std::string provenance(const Session& s);

// {"id", "state", "scene", "timeline", "current", "playing", "rate", "provenance"} of a session (its
// lock held).
nlohmann::ordered_json session_json(const std::string& id, const Session& s);

// A JSON answer.
void send_json(httplib::Response& res, const nlohmann::ordered_json& body, int status = 200);

// The version every response carries (X-Spinfold-Version).
std::string server_version();

}  // namespace spinfold::server
