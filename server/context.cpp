#include "server/context.h"

#include <cstdio>

#include "codec/provenance.h"
#include "codec/sample_json.h"
#include "codec/scene_json.h"
#include "engine/number_text.h"
#include "engine/scene_fields.h"
#include "engine/surface.h"
#include "server/http/problem.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

std::shared_ptr<Session> find_session(ServerContext& server, const std::string& id) {
  std::shared_ptr<Session> s;
  try {
    s = server.sessions.find(id);
  } catch (const StoreError& e) {
    // Not in this process's memory and the store is away: unknown is not the same as gone.
    std::fprintf(stderr, "spinfold: %s\n", e.what());
    throw ApiError{
        503, "Store unavailable", {{"id", id, "the session store cannot be read now; retry later"}}, "2"};
  }
  if (!s) throw unknown_session(id);
  return s;
}

namespace {

// Releases a stream slot (and the client's, server/http/quota.h) when destroyed.
struct StreamSlot {
  std::atomic<int>& open;
  std::shared_ptr<void> client;
  StreamSlot(std::atomic<int>& counter, std::shared_ptr<void> client_slot)
      : open(counter), client(std::move(client_slot)) {}
  ~StreamSlot() { --open; }
};

}  // namespace

std::shared_ptr<void> open_stream(ServerContext& server, const std::string& client) {
  std::shared_ptr<void> client_slot = server.quotas.open_stream(client);  // 429 over the client's quota
  if (++server.open_streams > server.options.limits.max_streams) {
    --server.open_streams;
    throw ApiError{429, "Too many streams", {{"", "", "the stream limit of the server is reached"}}, "10"};
  }
  return std::make_shared<StreamSlot>(server.open_streams, std::move(client_slot));
}

namespace {

ApiError store_unavailable(const std::string& what) {
  return ApiError{503, "Store unavailable", {{"", "", what + " could not be stored; retry later"}}, "1"};
}

}  // namespace

void commit(ServerContext& server, const std::string& id, Session& s) {
  switch (server.sessions.save(id, s)) {
    case SessionStore::Saved::stored: return;
    case SessionStore::Saved::conflict:
      throw bad(409, "Conflict", "id", id,
                "another server changed or deleted the session meanwhile; nothing was changed here: "
                "GET it and retry");
    case SessionStore::Saved::failed: throw store_unavailable("the change");
  }
}

void remove_session(ServerContext& server, const std::string& id) {
  bool removed = false;
  try {
    removed = server.sessions.erase(id);
  } catch (const StoreError& e) {
    std::fprintf(stderr, "spinfold: %s\n", e.what());
    throw store_unavailable("the deletion");
  }
  if (!removed) throw unknown_session(id);
  server.frames.drop(frame_etag_prefix(id));
}

std::string provenance(const Session& s) {
  return provenance_header(s.run.scene);
}

nlohmann::ordered_json session_json(const std::string& id, const Session& s) {
  nlohmann::ordered_json j;
  j["id"] = id;
  j["state"] = session_sample(s);
  j["scene"] = scene_to_json(s.scene);        // the parameters at t = 0
  j["timeline"] = s.timeline;                 // the changes since: [{"t", "patch"}]
  j["current"] = scene_to_json(s.run.scene);  // the parameters in force now
  j["playing"] = s.playing;                   // advanced in real time by the player
  j["rate"] = s.rate;                         // simulated time per second while playing
  j["provenance"] = provenance_json(s.run.scene, "");
  // The surface in force, resolved: its kind and radius also when the scene gave K (a dial through
  // 0: the server's kFlatCurvature decides the plane), and K = σ/R² [1/length²]; the UI reads these
  // rather than re-deriving them.
  const Surface& surface = s.run.scene.surface;
  // Where the curvature varies there is no one radius or K: the kind alone (K at the body is in the
  // state, "K").
  for (const auto& kind : kSurfaceKindNames)
    if (kind.value == surface.kind)
      j["surface"] = chart_free(surface) ? nlohmann::ordered_json{{"kind", kind.name}}
                                         : nlohmann::ordered_json{{"kind", kind.name},
                                                                  {"radius", surface.radius},
                                                                  {"curvature", curvature(surface)}};
  return j;
}

void send_json(httplib::Response& res, const nlohmann::ordered_json& body, int status) {
  res.status = status;
  res.body = body.dump();
  res.set_header("Content-Type", "application/json");
}

std::string server_version() {
  return std::string(build_version());
}

}  // namespace spinfold::server
