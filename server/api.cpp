#include "server/api.h"

#include "server/context.h"
#include "server/player.h"
#include "server/problem.h"
#include "server/route_table.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

namespace {

// What no route answered (an unknown path, a body over the limit, a request httplib could not
// read), said as problem+json too.
ApiError unrouted(const httplib::Request& req, int status) {
  if (status == 404) return bad(404, "Not found", "", "", "no such resource");
  if (status == 413)
    return bad(413, "Payload too large", "", "", "the request body exceeds the server's limit");
  if (status == 400) {
    const bool unsized = (req.method == "POST" || req.method == "PATCH" || req.method == "PUT") &&
                         !req.has_header("Content-Length") && !req.has_header("Transfer-Encoding");
    return bad(400, "Malformed request", "", "",
               unsized ? "a " + req.method + " needs a Content-Length header (0 when there is no body)"
                       : "the request could not be read");
  }
  return bad(status, "Error", "", "", "request failed");
}

}  // namespace

struct ApiServer::State {
  ServerContext server;
  httplib::Server http;
  Player player;  // destroyed (joined) before the sessions it advances

  explicit State(ServerOptions o)
      : server(std::move(o)), player(server.sessions, server.options.limits.max_play_steps) {}
};

ApiServer::ApiServer(ServerOptions options) : state_(std::make_unique<State>(std::move(options))) {
  auto& http = state_->http;
  http.set_tcp_nodelay(true);  // without it every small response waits ~40 ms (platform-notes.md)
  http.set_payload_max_length(state_->server.options.limits.max_body_bytes);
  const int threads = state_->server.options.threads;
  http.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  register_routes(http, state_->server, route_table(state_->server.options.limits));
  http.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (res.body.empty()) send_error(res, unrouted(req, res.status));
  });
}

ApiServer::~ApiServer() {
  stop();
}

int ApiServer::bind() {
  const ServerOptions& o = state_->server.options;
  if (o.port == 0) return state_->http.bind_to_any_port(o.host);
  return state_->http.bind_to_port(o.host, o.port) ? o.port : -1;
}

bool ApiServer::listen() {
  return state_->http.listen_after_bind();
}

std::string ApiServer::create_session(const Scene& scene) {
  std::string id;
  return state_->server.sessions.create(scene, id) ? id : std::string();
}

void ApiServer::stop() {
  if (!state_) return;
  state_->server.stopping = true;  // ends the event streams, which would hold the pool open
  state_->player.stop();
  state_->http.stop();
}

}  // namespace spinfold::server
