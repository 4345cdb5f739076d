// libFuzzer target: HTTP requests built from the input (method, route, query, content type, body)
// against the real server, in process, over loopback. Properties (a violation aborts):
// - the server answers, never with a 5xx other than 503 (busy);
// - an error is application/problem+json with its status and a detail;
// - a refused request (4xx) changes nothing: the session reads the same before and after;
// - a JSON answer parses.
// - a recording accepted (202) has from 1 to max_recording_frames frames (a double turned into
//   an integer out of range gave INT64_MIN);
// Half the inputs are raw bytes over a socket instead (the first byte picks): a request line, header
// lines picked from framing-relevant ones (Content-Length with signs, lists and duplicates,
// Transfer-Encoding, obs-fold, LF alone, an encoded slash) and a body, sent as it is or chunked
// (its chunks' ends possibly broken). Properties: one answer with a status line; no 5xx other than
// 501 (an unknown transfer coding) and 503; a request holding a construct RFC 9112 says to refuse
// is 400/404/501; any answer >= 400 leaves the session unchanged.
// Event streams and play are left out: they hold connections and change the session while the
// properties are checked.
#include <arpa/inet.h>
#include <fuzzer/FuzzedDataProvider.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>

#include "server/api.h"

// After Eigen (through the server's headers): httplib.h brings <resolv.h>'s `_res` macro.
#include <httplib.h>

namespace {

using nlohmann::json;

struct Harness {
  spinfold::server::ApiServer* server = nullptr;
  int port = 0;
  std::string id;  // the session the requests aim at

  Harness() {
    spinfold::server::ServerOptions options;
    options.port = 0;
    options.threads = 4;
    options.limits.max_sessions = 16;
    options.limits.max_steps = 2000;  // bounded work per request keeps an input fast
    options.limits.max_advance_time = 1e3;
    // Every request comes from 127.0.0.1, thousands a second: the per-client rate limit
    // (hardening_test.cpp tests it) would answer the harness's own reads with 429.
    options.limits.requests_per_second_per_client = 0.0;
    // Accepted recordings stay small: a few tiny frames each, and deleted after the check.
    options.limits.max_recording_frames = 8;
    options.limits.max_recording_pixels = 64 * 64;
    options.limits.max_recordings_per_client = 64;
    server = new spinfold::server::ApiServer(options);
    port = server->bind();
    if (port <= 0) std::abort();
    std::thread([this] { server->listen(); }).detach();
    new_session();
  }

  // One kept-alive connection for the harness's own requests and the structured inputs: a fresh
  // connection per request left ~24,000 sockets in TIME_WAIT during a run (measured with
  // `ss -tan state time-wait`), near the 28,232 ephemeral ports, and a connect that then fails
  // stops the run. httplib opens a new one when the server closes (an answer with Connection: close).
  httplib::Client& client() const {
    if (!kept) {
      kept = std::make_unique<httplib::Client>("127.0.0.1", port);
      kept->set_read_timeout(30, 0);
      kept->set_keep_alive(true);
      kept->set_tcp_nodelay(true);  // a kept connection would wait on delayed ACKs (40 ms) otherwise
    }
    return *kept;
  }
  mutable std::unique_ptr<httplib::Client> kept;

  void new_session() {
    auto res =
        client().Post("/api/v1/sessions", R"({"preset": "breathing_ellipse_sphere"})", "application/json");
    if (!res || res->status != 201) {
      std::fprintf(stderr, "harness: the target session could not be made again (%s)\n",
                   res ? (std::to_string(res->status) + " " + res->body).c_str() : "no answer");
      std::abort();
    }
    id = json::parse(res->body)["id"];
  }

  // Deletes a session an input made, so that inputs never fill the server's max_sessions (16):
  // a full server would refuse to make the target session again.
  void delete_made(const std::string& answer_body) const {
    const json made = json::parse(answer_body, nullptr, false);
    if (made.is_object() && made.contains("id") && made["id"].is_string())
      client().Delete("/api/v1/sessions/" + made["id"].get<std::string>());
  }

  std::string session_body() const {
    auto res = client().Get("/api/v1/sessions/" + id);
    return res && res->status == 200 ? res->body : "";
  }
};

[[noreturn]] void violated(const char* what, const std::string& method, const std::string& target,
                           const std::string& body, const httplib::Result& res) {
  std::fprintf(stderr, "property violated: %s\nrequest: %s %s\n%s\n", what, method.c_str(), target.c_str(),
               body.c_str());
  if (res) std::fprintf(stderr, "response %d: %s\n", res->status, res->body.c_str());
  std::abort();
}

std::string last_read_end;  // how exchange()'s read of the answer ended

[[noreturn]] void violated_raw(const char* what, const std::string& request, const std::string& answer) {
  std::fprintf(stderr, "property violated: %s\nrequest (raw, %zu bytes):\n%s\nanswer (%zu bytes, %s):\n%s\n",
               what, request.size(), request.c_str(), answer.size(), last_read_end.c_str(), answer.c_str());
  std::abort();
}

// Sends `request` over a fresh connection to 127.0.0.1 and reads until the server closes it.
std::string exchange(int port, const std::string& request) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  int connected = 0;
  do {
    connected = ::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address);
  } while (connected != 0 && (errno == EINTR || errno == EALREADY));
  if (connected != 0 && errno != EISCONN) {
    std::perror("harness: connect");
    std::abort();
  }
  const timeval timeout{30, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  // libFuzzer's timeout timer (SIGALRM, every -timeout/2 s) interrupts system calls: an interrupted
  // call is made again (a recv given up on EINTR read as "no status line", found in CI).
  for (std::size_t sent = 0; sent < request.size();) {
    const ssize_t n = ::send(fd, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // answered and closed before reading it all
    sent += static_cast<std::size_t>(n);
  }
  ::shutdown(fd, SHUT_WR);  // nothing more: an incomplete request ends here
  std::string answer;
  char buffer[4096];
  const auto start = std::chrono::steady_clock::now();
  ssize_t n = 0;
  while ((n = ::recv(fd, buffer, sizeof buffer, 0)) > 0 || (n < 0 && errno == EINTR))
    if (n > 0) answer.append(buffer, static_cast<std::size_t>(n));
  // How the read ended, for a violation's report.
  last_read_end =
      (n == 0 ? std::string("the server closed") : std::string("recv: ") + std::strerror(errno)) + " after " +
      std::to_string(
          std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start)
              .count()) +
      " ms";
  // Closed without TIME_WAIT (the answer is read): 10,000 raw inputs a minute would otherwise hold
  // as many ephemeral ports for 60 s each (see Harness::client).
  const linger abort_on_close{1, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_LINGER, &abort_on_close, sizeof abort_on_close);
  ::close(fd);
  return answer;
}

// One raw request built from the input; see the properties at the top.
void raw_request(Harness& h, FuzzedDataProvider& in) {
  bool must_refuse = false;  // the request holds a construct RFC 9112 says to refuse
  const std::string method = in.PickValueInArray({"POST", "PATCH", "GET", "DELETE"});
  std::string target = in.PickValueInArray({"/api/v1/sessions/{id}/advance", "/api/v1/sessions/{id}",
                                            "/api/v1/sessions/{id}/recordings", "/api/v1/sessions"});
  if (in.ConsumeBool()) {
    const std::size_t slash = target.find("/{id}");
    if (slash != std::string::npos) {
      target.replace(slash, 1, in.ConsumeBool() ? "%2F" : "%2f");
      must_refuse = true;
    }
  }
  if (const auto at = target.find("{id}"); at != std::string::npos) target.replace(at, 4, h.id);
  std::string body = in.ConsumeRandomLengthString(256);
  if (in.ConsumeBool()) body = R"({"until": 0.5})";  // a body that would act, were it read
  std::string headers = "Host: 127.0.0.1\r\nConnection: close\r\nContent-Type: application/json\r\n";
  bool chunked = false, has_length = false;
  const int lines = in.ConsumeIntegralInRange(0, 4);
  for (int k = 0; k < lines; ++k) {
    switch (in.ConsumeIntegralInRange(0, 10)) {
      case 0:
        headers += "Content-Length: " + std::to_string(body.size()) + "\r\n";
        has_length = true;
        break;
      case 1:
        headers += "Content-Length: +" + std::to_string(body.size()) + "\r\n";
        must_refuse = true;
        break;
      case 2:
        headers += "Content-Length: -5\r\n";
        must_refuse = true;
        break;
      case 3:
        headers +=
            "Content-Length: " + std::to_string(body.size() + 1 + in.ConsumeIntegralInRange(0, 9)) + "\r\n";
        has_length = true;
        break;
      case 4:
        headers += "Transfer-Encoding: chunked\r\n";
        chunked = true;
        break;
      case 5:
        headers += "X-Note: a\r\n folded\r\n";
        must_refuse = true;
        break;
      case 6:
        headers += "X-Note: a\n";
        must_refuse = true;
        break;
      case 7:
        headers += "Content-Length : " + std::to_string(body.size()) + "\r\n";
        must_refuse = true;
        break;
      case 8:
        headers += "Transfer-Encoding: " + in.ConsumeRandomLengthString(12) + "\r\n";
        chunked = true;
        break;
      case 9:  // byte ranges apply to a file download only, by RFC 9110 (server/http/byte_ranges.h)
        headers += std::string(in.PickValueInArray({"Range", "RANGE", "Rnge_", "If-Range"})) + ": " +
                   in.PickValueInArray({"bytes=", "items=", "bytes=-", ""}) +
                   in.ConsumeRandomLengthString(24) + "\r\n";
        break;
      default:
        headers += "X-" + in.ConsumeRandomLengthString(12) + ": " + in.ConsumeRandomLengthString(24) + "\r\n";
    }
  }
  // Two lengths that differ, or a length with a transfer coding: ambiguous.
  if (chunked && has_length) must_refuse = true;
  std::optional<std::string> first_length;
  for (std::size_t at = headers.find("Content-Length: "); at != std::string::npos;
       at = headers.find("Content-Length: ", at + 1)) {
    const std::string value = headers.substr(at + 16, headers.find('\r', at) - at - 16);
    if (!first_length)
      first_length = value;
    else if (value != *first_length)
      must_refuse = true;
  }
  std::string payload = body;
  if (chunked) {
    payload.clear();
    const bool broken = in.ConsumeBool();
    std::size_t at = 0;
    while (at < body.size()) {
      const std::size_t n = std::min<std::size_t>(body.size() - at, in.ConsumeIntegralInRange(1, 64));
      char size[32];
      std::snprintf(size, sizeof size, "%zx\r\n", n);
      payload += size + body.substr(at, n) + (broken && at == 0 ? "XX\r\n" : "\r\n");
      at += n;
    }
    payload += "0\r\n\r\n";
    if (broken && !body.empty()) must_refuse = true;
  }
  const std::string request = method + " " + target + " HTTP/1.1\r\n" + headers + "\r\n" + payload;

  const std::string before = h.session_body();
  const std::string answer = exchange(h.port, request);
  if (answer.rfind("HTTP/1.1 ", 0) != 0) violated_raw("no status line", request, answer);
  if (answer.find("HTTP/1.1 ", 9) != std::string::npos) violated_raw("more than one answer", request, answer);
  const int status = std::atoi(answer.c_str() + 9);
  if (status >= 500 && status != 501 && status != 503) violated_raw("a server error", request, answer);
  if (must_refuse && status != 400 && status != 404 && status != 501)
    violated_raw("ambiguous framing was not refused", request, answer);
  if (status >= 400 && h.session_body() != before)
    violated_raw("a refused request changed the session", request, answer);
  // A raw POST /api/v1/sessions with a scene for a body (`{}` is one) made a session: it goes.
  if (status == 201 && method == "POST" && target == "/api/v1/sessions") {
    const std::size_t head_end = answer.find("\r\n\r\n");
    if (head_end != std::string::npos) h.delete_made(answer.substr(head_end + 4));
  }
  if (h.session_body().empty()) h.new_session();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Harness h;
  FuzzedDataProvider in(data, size);
  if (in.ConsumeBool()) {
    raw_request(h, in);
    return 0;
  }
  const std::string method = in.PickValueInArray({"GET", "POST", "PATCH", "DELETE", "PUT"});
  const std::string route = in.PickValueInArray(
      {"/api/v1/sessions", "/api/v1/sessions/{id}", "/api/v1/sessions/{id}/advance",
       "/api/v1/sessions/{id}/reset", "/api/v1/sessions/{id}/pause", "/api/v1/sessions/{id}/trajectory",
       "/api/v1/sessions/{id}/frame.png", "/api/v1/sessions/nope", "/api/v1/schema", "/api/v1/scenes",
       "/api/v1/integrators", "/api/v1/health", "/api/v1/", "/api/v1/sessions/{id}/recordings",
       "/api/v1/sessions/{id}/recordings", "/api/v1/recordings/nope", "/api/v1/sessions%2F{id}/advance",
       // The drag routes and the other pictures (issue 48: every request bounded).
       "/api/v1/sessions/{id}/handles", "/api/v1/sessions/{id}/drop", "/api/v1/sessions/{id}/frame.svg",
       "/api/v1/sessions/{id}/frame.jpg", "/api/v1/views", "/api/v1/view-parameters"});
  std::string target = route;
  if (const auto at = target.find("{id}"); at != std::string::npos) target.replace(at, 4, h.id);
  const int parameters = in.ConsumeIntegralInRange(0, 3);
  for (int k = 0; k < parameters; ++k) {
    const std::string key = in.PickValueInArray({"format", "width", "height", "view", "layers", "yaw",
                                                 "pitch", "distance", "scale", "rate", "trail", "fields",
                                                 "every", "x", "y", "handle", "at", "quality"});
    target += (k == 0 ? "?" : "&") + key + "=" +
              httplib::detail::encode_query_param(in.ConsumeRandomLengthString(24));
  }
  const std::string type = in.PickValueInArray({"application/json", "application/merge-patch+json",
                                                "text/plain", "application/json; charset=utf-8", ""});
  const std::string body = in.ConsumeRemainingBytesAsString();

  const std::string before = h.session_body();
  httplib::Client& c = h.client();
  const httplib::Headers headers;
  const httplib::Result res = [&] {
    if (method == "GET") return c.Get(target);
    if (method == "DELETE") return c.Delete(target, headers, body, type);
    if (method == "POST") return c.Post(target, headers, body, type);
    if (method == "PATCH") return c.Patch(target, headers, body, type);
    return c.Put(target, headers, body, type);
  }();

  if (!res) violated("no answer", method, target, body, res);
  if (res->status >= 500 && res->status != 503) violated("a server error", method, target, body, res);
  const std::string content_type = res->get_header_value("Content-Type");
  if (res->status >= 400) {
    if (content_type != "application/problem+json")
      violated("an error that is not problem+json", method, target, body, res);
    const json problem = json::parse(res->body, nullptr, false);
    if (problem.is_discarded() || problem.value("status", 0) != res->status || !problem.contains("detail"))
      violated("a problem without its status or detail", method, target, body, res);
    if (h.session_body() != before)
      violated("a refused request changed the session", method, target, body, res);
  } else if (content_type.starts_with("application/json") &&
             json::parse(res->body, nullptr, false).is_discarded()) {
    violated("a JSON answer that does not parse", method, target, body, res);
  }
  if (route.ends_with("/recordings") && res->status == 202) {
    const json made = json::parse(res->body, nullptr, false);
    const long long frames = made.value("frames", -1LL);
    if (frames < 1 || frames > 8)
      violated("a recording's frame count out of range", method, target, body, res);
    c.Delete("/api/v1/recordings/" + made.value("id", std::string("none")));
  }
  // Keep the stage as it was: sessions the input made go, the target session comes back.
  if (method == "POST" && route == "/api/v1/sessions" && res->status == 201) h.delete_made(res->body);
  if (h.session_body().empty()) h.new_session();
  return 0;
}
