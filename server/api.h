// The HTTP API (cpp-httplib): handlers translate HTTP to engine, codec and render calls and back.
#pragma once

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>

namespace httplib {
class Server;
}

namespace spinfold {
struct Scene;
}

namespace spinfold::server {

struct Limits {
  std::size_t max_body_bytes = 64 * 1024;  // request bodies [bytes]
  std::size_t max_sessions = 64;
  std::chrono::seconds idle_expiry{1800};  // sessions unused this long are dropped
  long max_steps = 1000000;                // step attempts per advance request (and fixed steps)
  long max_play_steps = 20000;             // step attempts per session per player tick (50 Hz)
  double max_advance_time = 1e6;           // simulated time per advance request
  int max_image_side = 4096;               // [pixels]
  int max_streams = 4;                     // open event streams (each holds a worker thread)
  double max_play_rate = 1000.0;           // simulated time per second while playing
};

struct ServerOptions {
  std::string host = "127.0.0.1";
  int port = 8080;  // 0: any free port
  int threads = 8;  // HTTP worker threads (one per open connection)
  Limits limits;
};

class ApiServer {
 public:
  explicit ApiServer(ServerOptions options);
  ~ApiServer();
  // Binds and returns the port (or -1); then listen() serves until stop().
  int bind();
  bool listen();
  void stop();
  // A session on this scene, as POST /api/v1/sessions would make it; returns its id ("" if full).
  std::string create_session(const Scene& scene);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace spinfold::server
