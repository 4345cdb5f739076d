// A server of a test's or a suite's own: an ApiServer on a free loopback port, listening on a thread of
// its own from start() (or the constructor) to stop() (or the destructor). Include it after every header
// that brings Eigen: it brings httplib.h, whose <resolv.h> defines the `_res` macro.
#pragma once

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <memory>
#include <string>
#include <thread>

#include "server/api.h"

// clang-format off
#include <httplib.h>
// clang-format on

namespace spinfold::server::test {

// A suite's options: a free port, `threads` HTTP workers and `render_threads`, no request-rate limit
// (the quotas have tests of their own).
inline ServerOptions suite_options(int threads, int render_threads) {
  ServerOptions options;
  options.port = 0;
  options.threads = threads;
  options.render_threads = render_threads;
  options.limits.requests_per_second_per_client = 0.0;
  return options;
}

// A TCP connection to 127.0.0.1:port (the tests that write raw HTTP).
inline int connect_loopback(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  return fd;
}

class TestServer {
 public:
  TestServer() = default;
  explicit TestServer(const ServerOptions& options) { start(options); }
  ~TestServer() { stop(); }
  TestServer(const TestServer&) = delete;
  TestServer& operator=(const TestServer&) = delete;
  void start(const ServerOptions& options) {
    api_ = std::make_unique<ApiServer>(options);
    port_ = api_->bind();
    ASSERT_GT(port_, 0) << "no free port";
    thread_ = std::thread([this] { api_->listen(); });
  }
  void stop() {
    if (!api_) return;
    api_->stop();
    if (thread_.joinable()) thread_.join();
    api_.reset();
  }
  int port() const { return port_; }
  ApiServer& api() { return *api_; }
  // A client of this server that waits up to `read_timeout_s` for an answer.
  httplib::Client client(int read_timeout_s = 30) const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(read_timeout_s, 0);
    return c;
  }
  // A client whose every request says X-Forwarded-For: address (a client behind a proxy).
  httplib::Client client_from(const std::string& address) const {
    httplib::Client c = client();
    c.set_default_headers({{"X-Forwarded-For", address}});
    return c;
  }

 private:
  std::unique_ptr<ApiServer> api_;
  std::thread thread_;
  int port_ = 0;
};

}  // namespace spinfold::server::test
