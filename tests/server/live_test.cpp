// The live stream (GET/PATCH …/live). A real server in-process, real HTTP clients. What it stands
// on has its own files: the render pool's order per session (render_pool_test.cpp) and the frame
// cache's one render per frame (frame_cache_test.cpp).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "decoded_image.h"
#include "render/camera_follow.h"
#include "render/snapshot.h"
#include "server/api.h"
#include "server/frames/render_pool.h"

// After Eigen (through the server's headers): httplib.h brings <resolv.h>'s `_res` macro.
#include <httplib.h>

#include "test_server.h"

namespace spinfold::server {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

// One part of a multipart/x-mixed-replace stream.
struct Part {
  std::string type;
  std::map<std::string, std::string> frame;  // X-Spinfold-Frame: seq, version, t, kind
  std::string body;
};

// Parses the stream as it arrives.
struct MultipartReader {
  std::string buffer;
  std::vector<Part> parts;
  void feed(const char* data, std::size_t n) {
    buffer.append(data, n);
    for (;;) {
      const std::size_t head_end = buffer.find("\r\n\r\n");
      if (head_end == std::string::npos) return;
      const std::string head = buffer.substr(0, head_end);
      EXPECT_EQ(head.rfind("--spinfold-frame\r\n", 0), 0u) << head;
      const auto header = [&](const std::string& name) {
        const std::size_t at = head.find(name + ": ");
        if (at == std::string::npos) return std::string();
        const std::size_t from = at + name.size() + 2;
        return head.substr(from, head.find("\r\n", from) - from);
      };
      const std::size_t length = std::stoul(header("Content-Length"));
      if (buffer.size() < head_end + 4 + length + 2) return;
      Part part{header("Content-Type"), {}, buffer.substr(head_end + 4, length)};
      std::string fields = header("X-Spinfold-Frame");
      for (std::size_t at = 0; at < fields.size();) {
        const std::size_t end = std::min(fields.find("; ", at), fields.size());
        const std::string item = fields.substr(at, end - at);
        part.frame[item.substr(0, item.find('='))] = item.substr(item.find('=') + 1);
        at = end + 2;
      }
      EXPECT_EQ(buffer.substr(head_end + 4 + length, 2), "\r\n");
      parts.push_back(std::move(part));
      buffer.erase(0, head_end + 4 + length + 2);
    }
  }
  std::vector<Part> frames() const {
    std::vector<Part> images;
    for (const Part& p : parts)
      if (p.type.rfind("image/", 0) == 0) images.push_back(p);
    return images;
  }
};

// Reads a whole chunked HTTP response as it arrives: the status line, then the chunks' bytes into
// the multipart reader.
struct ResponseReader {
  std::string raw;
  bool head_read = false;
  int status = 0;
  MultipartReader body;
  void feed(const char* data, std::size_t n) {
    raw.append(data, n);
    if (!head_read) {
      const std::size_t end = raw.find("\r\n\r\n");
      if (end == std::string::npos) return;
      status = std::stoi(raw.substr(raw.find(' ') + 1, 3));
      raw.erase(0, end + 4);
      head_read = true;
    }
    for (;;) {
      const std::size_t eol = raw.find("\r\n");
      if (eol == std::string::npos) return;
      const std::size_t size = std::stoul(raw.substr(0, eol), nullptr, 16);
      if (size == 0 || raw.size() < eol + 2 + size + 2) return;
      body.feed(raw.data() + eol + 2, size);
      raw.erase(0, eol + 2 + size + 2);
    }
  }
};

class Live : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { server_.start(test::suite_options(16, 2)); }
  static void TearDownTestSuite() { server_.stop(); }
  static httplib::Client client() { return server_.client(30); }
  static std::string create() {
    auto res = client().Post("/api/v1/sessions", "{}", "application/json");
    EXPECT_EQ(res->status, 201);
    return json::parse(res->body)["id"];
  }
  static int post(const std::string& path, const std::string& body = "{}") {
    return client().Post(path, body, "application/json")->status;
  }

  // Reads a live stream on its own thread until stop(), over a plain socket that it polls: no read
  // timeout judges the stream, since under a sanitizer on a busy machine a frame can take seconds.
  struct Watch {
    ResponseReader reader;
    std::mutex mutex;
    std::atomic<bool> stopping{false};
    int sock;
    std::thread thread;
    explicit Watch(const std::string& path) : sock(test::connect_loopback(server_.port())) {
      const std::string request = "GET " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n";
      EXPECT_EQ(::send(sock, request.data(), request.size(), 0), static_cast<ssize_t>(request.size()));
      thread = std::thread([this] {
        char chunk[65536];
        while (!stopping) {
          pollfd readable{sock, POLLIN, 0};
          if (::poll(&readable, 1, 50) <= 0) continue;
          const ssize_t n = ::recv(sock, chunk, sizeof chunk, 0);
          if (n <= 0) return;
          const std::lock_guard lock(mutex);
          reader.feed(chunk, static_cast<std::size_t>(n));
        }
      });
    }
    std::vector<Part> frames() {
      const std::lock_guard lock(mutex);
      return reader.body.frames();
    }
    int status() {
      const std::lock_guard lock(mutex);
      return reader.status;
    }
    // Waits (up to 60 s: the bound only matters when the test fails) until `n` frames arrived.
    bool wait_for(std::size_t n) {
      for (int i = 0; i < 6000 && frames().size() < n; ++i) std::this_thread::sleep_for(10ms);
      return frames().size() >= n;
    }
    void stop() {
      if (stopping.exchange(true)) return;
      thread.join();
      ::close(sock);
    }
    ~Watch() { stop(); }
  };

  static test::TestServer server_;
};

test::TestServer Live::server_;

// A paused session: its still frame (a PNG) at once, then nothing at all.
TEST_F(Live, PausedSessionSendsOneStillFrameThenNothing) {
  const std::string id = create();
  Watch watch("/api/v1/sessions/" + id + "/live?viewer=paused");
  ASSERT_TRUE(watch.wait_for(1));
  std::this_thread::sleep_for(2s);  // nothing more comes: no frame, no keep-alive part
  watch.stop();
  EXPECT_EQ(watch.status(), 200);
  const auto frames = watch.frames();
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_TRUE(watch.reader.body.buffer.empty()) << watch.reader.body.buffer.size() << " bytes after it";
  EXPECT_EQ(frames[0].type, "image/png");
  EXPECT_EQ(frames[0].frame.at("kind"), "still");
  EXPECT_EQ(frames[0].frame.at("seq"), "1");
  EXPECT_EQ(frames[0].body, client().Get("/api/v1/sessions/" + id + "/frame.png")->body);
}

// Playing: motion frames (JPEG) in order; paused: one PNG of the last state, which is the motion
// frame's picture within JPEG's error and frame.png's bytes.
TEST_F(Live, MotionFramesInOrderThenTheStillFrame) {
  const std::string id = create();
  const std::string session = "/api/v1/sessions/" + id;
  Watch watch(session + "/live?viewer=player&quality=80");
  ASSERT_TRUE(watch.wait_for(1));
  ASSERT_EQ(post(session + "/play", R"({"rate": 1})"), 200);
  EXPECT_EQ(json::parse(client().Get(session)->body)["playing"], true);
  ASSERT_TRUE(watch.wait_for(6));
  ASSERT_EQ(post(session + "/pause"), 200);
  EXPECT_EQ(json::parse(client().Get(session)->body)["playing"], false);
  const double paused_t = json::parse(client().Get(session)->body)["state"]["t"];
  // The still frame follows (the stream is then silent).
  for (int i = 0; i < 500 && watch.frames().back().frame.at("kind") != "still"; ++i)
    std::this_thread::sleep_for(10ms);
  std::this_thread::sleep_for(300ms);
  watch.stop();
  const auto frames = watch.frames();
  ASSERT_GE(frames.size(), 7u);
  long seq = 0, version = 0;
  for (std::size_t i = 1; i + 1 < frames.size(); ++i) {
    EXPECT_EQ(frames[i].type, "image/jpeg") << i;
    EXPECT_EQ(frames[i].frame.at("kind"), "motion") << i;
  }
  for (const Part& f : frames) {
    EXPECT_EQ(std::stol(f.frame.at("seq")), seq + 1);
    seq = std::stol(f.frame.at("seq"));
    EXPECT_GE(std::stol(f.frame.at("version")), version);
    version = std::stol(f.frame.at("version"));
  }
  const Part& still = frames.back();
  const Part& motion = frames[frames.size() - 2];
  EXPECT_EQ(still.type, "image/png");
  EXPECT_EQ(still.frame.at("kind"), "still");
  EXPECT_EQ(still.frame.at("version"), motion.frame.at("version"));
  EXPECT_EQ(std::stod(still.frame.at("t")), paused_t);
  EXPECT_EQ(still.body, client().Get(session + "/frame.png")->body);
  int width = 0, height = 0;
  const auto lossless = png_pixels(still.body, width, height);
  EXPECT_EQ(width, 640);
  EXPECT_LT(mean_difference(jpeg_pixels(motion.body, width, height), lossless), 3.0);  // of 255
}

// PATCH steers the stream: a new camera gives a motion frame then a still one; an unknown viewer
// is 404, a bad one 422, a second stream with the same viewer 409.
TEST_F(Live, PatchSteersTheStreamsCamera) {
  const std::string id = create();
  const std::string live = "/api/v1/sessions/" + id + "/live";
  auto c = client();
  // Streams the tests before left are counted until a heartbeat finds them gone (up to 2 × 5 s):
  // the count is checked from none, or one of theirs could leave as this one comes.
  const auto open_streams = [&] { return json::parse(c.Get("/api/v1/health")->body)["streams"].get<int>(); };
  for (int i = 0; i < 300 && open_streams() != 0; ++i) std::this_thread::sleep_for(100ms);
  ASSERT_EQ(open_streams(), 0);
  Watch watch(live + "?viewer=steer");
  ASSERT_TRUE(watch.wait_for(1));
  EXPECT_EQ(open_streams(), 1);
  EXPECT_EQ(c.Patch(live + "?viewer=steer&yaw=1.5&pitch=0.4", "", "text/plain")->status, 204);
  ASSERT_TRUE(watch.wait_for(3));
  const auto frames = watch.frames();
  EXPECT_EQ(frames[1].frame.at("kind"), "motion");
  EXPECT_EQ(frames[2].frame.at("kind"), "still");
  EXPECT_EQ(frames[2].frame.at("version"), frames[0].frame.at("version"));  // same state, new camera
  EXPECT_NE(frames[2].body, frames[0].body);
  EXPECT_EQ(frames[2].body, c.Get("/api/v1/sessions/" + id + "/frame.png?yaw=1.5&pitch=0.4")->body);

  EXPECT_EQ(c.Patch(live + "?viewer=nobody&yaw=1", "", "text/plain")->status, 404);
  auto bad = c.Patch(live + "?viewer=no%20spaces&yaw=1", "", "text/plain");
  EXPECT_EQ(bad->status, 422);
  EXPECT_NE(bad->body.find("viewer"), std::string::npos);
  EXPECT_EQ(c.Patch(live + "?viewer=steer&pitch=9", "", "text/plain")->status, 422);
  // Each side allowed, the two together over limits.max_image_pixels (4K UHD): refused, as for frame.png.
  auto large = c.Patch(live + "?viewer=steer&width=4096&height=4096", "", "text/plain");
  EXPECT_EQ(large->status, 422);
  EXPECT_NE(large->body.find("limits.max_image_pixels"), std::string::npos) << large->body;
  EXPECT_EQ(c.Get(live + "?viewer=steer")->status, 409);
  watch.stop();
}

// An aimed 3-D camera glides: back from the viewer's own camera to the aim (`aim=body`), frames say
// where the camera is (yaw, pitch, distance) and that it is on its way (glide=1), each turned from
// the last by at most the catch-up rate's step at the stream's longest frame interval; the frame it
// arrives at is the aimed one, to the byte (frame.png), and the stream is then still.
TEST_F(Live, AnAimedCameraGlidesBackFromTheViewersOwnAndSaysWhereItIs) {
  const std::string id = create();
  const std::string live = "/api/v1/sessions/" + id + "/live";
  Watch watch(live + "?viewer=glide");
  ASSERT_TRUE(watch.wait_for(1));
  const Part aimed = watch.frames()[0];
  ASSERT_EQ(aimed.frame.count("yaw"), 1u);
  EXPECT_EQ(aimed.frame.at("glide"), "0");
  const double yaw = std::stod(aimed.frame.at("yaw")), pitch = std::stod(aimed.frame.at("pitch"));
  auto c = client();
  const std::string own = "&yaw=" + std::to_string(yaw + 1.2) + "&pitch=" + std::to_string(pitch);
  // Until the stream has sent a frame after the n-th and is still.
  const auto settled = [&](std::size_t n) {
    ASSERT_TRUE(watch.wait_for(n + 1));
    for (int i = 0; i < 3000 && watch.frames().back().frame.at("kind") != "still"; ++i)
      std::this_thread::sleep_for(10ms);
  };
  EXPECT_EQ(c.Patch(live + "?viewer=glide" + own, "", "text/plain")->status, 204);
  settled(1);
  const std::size_t before = watch.frames().size();
  EXPECT_NEAR(std::stod(watch.frames().back().frame.at("yaw")), yaw + 1.2, 1e-5);
  EXPECT_EQ(c.Patch(live + "?viewer=glide&aim=body", "", "text/plain")->status, 204);
  settled(before);
  std::this_thread::sleep_for(300ms);
  watch.stop();
  const auto frames = watch.frames();
  std::vector<double> yaws{yaw + 1.2};
  int gliding = 0;
  for (std::size_t i = before; i < frames.size(); ++i) {
    yaws.push_back(std::stod(frames[i].frame.at("yaw")));
    gliding += frames[i].frame.at("glide") == "1";
  }
  EXPECT_GE(gliding, 3);  // 1.2 rad at most 0.5 a frame, and gently at first
  for (std::size_t i = 1; i < yaws.size(); ++i) {
    EXPECT_LE(yaws[i], yaws[i - 1] + 1e-9) << i;  // always towards the aim
    EXPECT_LE(yaws[i - 1] - yaws[i], render::kFollowCatchUpRate * render::kFollowMaxSeconds + 1e-6) << i;
  }
  const Part& last = frames.back();
  EXPECT_EQ(last.frame.at("kind"), "still");
  EXPECT_EQ(last.frame.at("glide"), "0");
  EXPECT_NEAR(std::stod(last.frame.at("yaw")), yaw, 1e-6);
  EXPECT_EQ(last.body, c.Get("/api/v1/sessions/" + id + "/frame.png")->body);
}

// A client that stops reading while the session plays is sent fewer, newer frames: the server
// renders a frame only when the previous one was taken, so nothing piles up for it.
TEST_F(Live, ASlowReaderGetsFewerNewerFramesNotAQueue) {
  const std::string id = create();
  const std::string session = "/api/v1/sessions/" + id;
  const int sock = ::socket(AF_INET, SOCK_STREAM, 0);
  const int small = 16 * 1024;  // set before connecting, or the window is already offered
  ::setsockopt(sock, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(server_.port()));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::connect(sock, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  const std::string request = "GET " + session + "/live?viewer=slow HTTP/1.1\r\nHost: x\r\n\r\n";
  ASSERT_EQ(::send(sock, request.data(), request.size(), 0), static_cast<ssize_t>(request.size()));
  ASSERT_EQ(post(session + "/play", R"({"rate": 1})"), 200);
  std::this_thread::sleep_for(3s);  // ~360 states played; the client reads nothing
  const double t_before = json::parse(client().Get(session)->body)["state"]["t"];
  // Now read everything the server had sent (and goes on sending) for one second.
  timeval timeout{0, 100000};
  ::setsockopt(sock, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  std::string received;
  const auto until = std::chrono::steady_clock::now() + 1s;
  char chunk[65536];
  while (std::chrono::steady_clock::now() < until) {
    const ssize_t n = ::recv(sock, chunk, sizeof chunk, 0);
    if (n > 0) received.append(chunk, static_cast<std::size_t>(n));
  }
  ::close(sock);
  ASSERT_EQ(post(session + "/pause"), 200);
  ResponseReader reader;
  reader.feed(received.data(), received.size());
  EXPECT_EQ(reader.status, 200);
  const auto frames = reader.body.frames();
  ASSERT_GE(frames.size(), 2u);
  // Sent while the client was not reading: what fits in the socket buffers, not 3 s of frames.
  std::size_t stale = 0;
  for (const Part& f : frames) stale += std::stod(f.frame.at("t")) < t_before;
  EXPECT_LE(stale, 16u) << frames.size() << " frames";
  std::printf("slow reader: %zu stale frames of %zu\n", stale, frames.size());
  // And after it read again, frames of the state now, not of the backlog.
  EXPECT_GE(std::stod(frames.back().frame.at("t")), t_before);
}

}  // namespace
}  // namespace spinfold::server
