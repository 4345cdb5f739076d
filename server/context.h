// What every handler shares: the server's state (sessions, the render thread, the frame cache,
// the open event streams) and the few answers built the same way on every route.
#pragma once

#include <atomic>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "server/api.h"
#include "server/frame_cache.h"
#include "server/render_worker.h"
#include "server/sessions.h"

namespace httplib {
struct Response;
}

namespace spinfold::server {

struct ServerContext {
  ServerOptions options;
  SessionStore sessions;
  RenderWorker renderer;
  FrameCache frames{64};
  std::atomic<int> open_streams{0};   // event streams now open
  std::atomic<bool> stopping{false};  // set by stop(): ends the event streams

  explicit ServerContext(ServerOptions o)
      : options(std::move(o)), sessions(options.limits.max_sessions, options.limits.idle_expiry) {}
};

// The session with this id, or ApiError 404 (the same answer on every route).
std::shared_ptr<Session> find_session(ServerContext& server, const std::string& id);

// X-Spinfold-Provenance: "version=…; integrator=…; tolerance=…" (numbers in shortest form).
std::string provenance(const Session& s);

// {"id", "state", "scene", "timeline", "current"} of a session (its lock held).
nlohmann::ordered_json session_json(const std::string& id, const Session& s);

// A JSON answer.
void send_json(httplib::Response& res, const nlohmann::ordered_json& body, int status = 200);

// The version every response carries (X-Spinfold-Version).
const char* server_version();

}  // namespace spinfold::server
