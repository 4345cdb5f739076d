// The HTTP API (cpp-httplib): handlers translate HTTP to engine, codec and render calls and back.
#pragma once

#include <memory>
#include <string>

#include "server/options.h"

namespace httplib {
class Server;
}

namespace spinfold {
struct Scene;
}

namespace spinfold::server {

class ApiServer {
 public:
  // With a store or data_dir, opens the store and restores its sessions: StoreError (server/store/store.h)
  // when it cannot (unwritable directory, damaged or locked database).
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
