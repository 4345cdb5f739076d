// A server of a test suite's own: an ApiServer on a free loopback port, listening on a thread of its
// own from start() (SetUpTestSuite) to stop() (TearDownTestSuite). Include it after every header
// that brings Eigen: it brings httplib.h, whose <resolv.h> defines the `_res` macro.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <thread>

#include "server/api.h"

// clang-format off
#include <httplib.h>
// clang-format on

namespace spinfold::server::test {

class TestServer {
 public:
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

 private:
  std::unique_ptr<ApiServer> api_;
  std::thread thread_;
  int port_ = 0;
};

}  // namespace spinfold::server::test
