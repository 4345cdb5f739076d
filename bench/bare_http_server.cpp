// The bare minimum cpp-httplib can serve here: fixed bodies of given sizes, with the same server
// settings as Spinfold (TCP_NODELAY, a thread pool of the same size). The baseline of
// bench/http_bench.sh. Usage: bare-http-server PORT STATE_BYTES FRAME_FILE
#include <httplib.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: bare-http-server PORT STATE_BYTES FRAME_FILE\n";
    return 2;
  }
  const int port = std::atoi(argv[1]);
  const std::string state(static_cast<std::size_t>(std::atol(argv[2])), 'x');
  std::ifstream in(argv[3], std::ios::binary);
  const std::string frame((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  httplib::Server server;
  server.set_tcp_nodelay(true);
  server.new_task_queue = [] { return new httplib::ThreadPool(8); };
  server.Get("/state", [&](const httplib::Request&, httplib::Response& res) {
    res.body = state;
    res.set_header("Content-Type", "application/json");
  });
  server.Get("/frame", [&](const httplib::Request&, httplib::Response& res) {
    res.body = frame;
    res.set_header("Content-Type", "image/png");
  });
  return server.listen("127.0.0.1", port) ? 0 : 1;
}
