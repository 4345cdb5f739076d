#include "server/api.h"

#include <sys/socket.h>

#include <set>

#include "server/context.h"
#include "server/http/framing.h"
#include "server/http/problem.h"
#include "server/routes/routes.h"
#include "server/sessions/player.h"

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
  if (status == 414) return bad(414, "URI too long", "", "", "the request line is longer than 8192 bytes");
  return bad(status, "Error", "", "", "request failed");
}

// On every response (the UI page and its files above all; harmless on the API): the page runs only
// its own scripts and styles, shows its own images and the frames it fetched (blob: URLs), talks
// only to this origin (fetch, EventSource), and is framed only by ServerOptions::frame_ancestors
// (nobody by default); no MIME sniffing, no Referer
// (a share link's scene and timeline stay out of other sites' logs).
httplib::Headers security_headers(const std::string& frame_ancestors) {
  return {{"Content-Security-Policy",
           "default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self' blob:; "
           "connect-src 'self'; base-uri 'none'; form-action 'none'; frame-ancestors " +
               frame_ancestors},
          {"X-Content-Type-Options", "nosniff"},
          {"Referrer-Policy", "no-referrer"}};
}

constexpr int kSendBuffer = 128 * 1024;  // [bytes]: 4 motion frames, a 1280x720 PNG in two writes

}  // namespace

struct ApiServer::State {
  ServerContext server;
  FramingServer http;      // reads each connection itself: the framing checks see the raw bytes
  Player player;           // destroyed (joined) before the sessions it advances
  int listen_socket = -1;  // remembered by the socket options, for bind() to raise its backlog

  explicit State(ServerOptions o)
      : server(std::move(o)),
        player(server.sessions, server.options.limits.max_play_steps, [this] { server.changes.notify(); }) {}
};

ApiServer::ApiServer(ServerOptions options) : state_(std::make_unique<State>(std::move(options))) {
  auto& http = state_->http;
  http.set_tcp_nodelay(true);  // without it every small response waits ~40 ms (docs/platform-notes.md)
  http.set_payload_max_length(state_->server.options.limits.max_body_bytes);
  const int threads = state_->server.options.threads;
  http.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  // Slow and idle clients: each connection holds a worker thread while open (ServerOptions::threads).
  const Limits& limits = state_->server.options.limits;
  http.set_read_timeout(limits.read_timeout);
  http.set_keep_alive_timeout(limits.keep_alive_timeout.count());
  http.set_keep_alive_max_count(static_cast<std::size_t>(limits.keep_alive_max_requests));
  http.set_default_headers(security_headers(state_->server.options.frame_ancestors));
  // The listening socket: SO_REUSEADDR (a restart binds at once) but not httplib's SO_REUSEPORT,
  // with which a second server on the same port silently takes part of the connections.
  // Accepted sockets inherit a send buffer of kSendBuffer (Linux doubles it): a live stream whose
  // client stops reading blocks after a few frames instead of queueing seconds of them in an
  // auto-tuned buffer of up to 4 MB (tests/server/live_test.cpp), and then sends the newest state.
  http.set_socket_options([state = state_.get()](socket_t sock) {
    const int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    ::setsockopt(sock, SOL_SOCKET, SO_SNDBUF, &kSendBuffer, sizeof kSendBuffer);
    state->listen_socket = sock;
  });
  const std::vector<Route> routes = route_table(state_->server.options.limits);
  register_routes(http, state_->server, routes);
  // Framing first, on the bytes as they arrived (server/http/framing.h): a refused head is answered and the
  // connection closed before any route, body or state is touched. Then a method the router has no
  // registration for (TRACE, CONNECT: httplib would answer 400) on a known path: 405 with Allow.
  http.set_pre_routing_handler([routes](const httplib::Request& req, httplib::Response& res) {
    const std::string* bytes = current_request_bytes();
    if (!bytes) return httplib::Server::HandlerResponse::Unhandled;
    const Framing f = read_framing(*bytes);
    if (f.status == 0) {
      static const std::set<std::string> routed{"GET", "HEAD", "POST", "PUT", "PATCH", "DELETE", "OPTIONS"};
      if (routed.contains(req.method)) return httplib::Server::HandlerResponse::Unhandled;
      const std::string allow = allow_at(routes, req.path);
      res.set_header("X-Spinfold-Version", server_version());
      if (allow.empty()) {
        send_error(res, unrouted(req, 404));  // as for any other method
        return httplib::Server::HandlerResponse::Handled;
      }
      res.set_header("Allow", allow);
      send_error(res, bad(405, "Method not allowed", "method", req.method, "this path allows " + allow));
      return httplib::Server::HandlerResponse::Handled;
    }
    res.set_header("X-Spinfold-Version", server_version());
    // (httplib adds its own when the client asked to close.)
    if (req.get_header_value("Connection") != "close") res.set_header("Connection", "close");
    const char* title = f.status == 404   ? "Not found"
                        : f.status == 501 ? "Not implemented"
                                          : "Malformed request";
    send_error(res, bad(f.status, title, f.field, f.value, f.reason));
    return httplib::Server::HandlerResponse::Handled;
  });
  http.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (res.body.empty()) send_error(res, unrouted(req, res.status));
  });
  // httplib 0.11 gives every answer without a body `Content-Length: 0`; RFC 9110 §8.6: a server MUST
  // NOT send one with 204. (A 304's stays: httplib's own client reads a 304 without one to the
  // connection's end.)
  http.set_post_routing_handler([](const httplib::Request& /*req*/, httplib::Response& res) {
    if (res.status == 204) res.headers.erase("Content-Length");
  });
}

ApiServer::~ApiServer() {
  stop();
}

int ApiServer::bind() {
  const ServerOptions& o = state_->server.options;
  const int port = o.port == 0 ? state_->http.bind_to_any_port(o.host)
                               : (state_->http.bind_to_port(o.host, o.port) ? o.port : -1);
  // httplib listens with a backlog of 5: a class opening the page at once (6 connections per
  // browser) would see connections dropped and retried 1-3 s later. Listening again sets the backlog.
  if (port > 0 && state_->listen_socket >= 0) ::listen(state_->listen_socket, SOMAXCONN);
  return port;
}

bool ApiServer::listen() {
  return state_->http.listen_after_bind();
}

std::string ApiServer::create_session(const Scene& scene) {
  std::string id;
  const auto session = state_->server.sessions.create(scene, id);
  if (!session) return "";
  const std::lock_guard lock(session->mutex);
  return state_->server.sessions.save(id, *session) == SessionStore::Saved::stored ? id : "";
}

void ApiServer::stop() {
  if (!state_) return;
  state_->server.stopping = true;  // ends the event and live streams, which would hold the pool open
  state_->server.changes.notify();
  state_->player.stop();
  state_->http.stop();
  state_->server.sessions.flush();  // the time of playing sessions
}

}  // namespace spinfold::server
