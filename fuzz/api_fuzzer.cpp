// libFuzzer target: HTTP requests built from the input (method, route, query, content type, body)
// against the real server, in process, over loopback. Properties (a violation aborts):
// - the server answers, never with a 5xx other than 503 (busy);
// - an error is application/problem+json with its status and a detail;
// - a refused request (4xx) changes nothing: the session reads the same before and after;
// - a JSON answer parses.
// Event streams and play are left out: they hold connections and change the session while the
// properties are checked.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
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
    server = new spinfold::server::ApiServer(options);
    port = server->bind();
    if (port <= 0) std::abort();
    std::thread([this] { server->listen(); }).detach();
    new_session();
  }

  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port);
    c.set_read_timeout(30, 0);
    return c;
  }

  void new_session() {
    auto res =
        client().Post("/api/v1/sessions", R"({"preset": "breathing_ellipse_sphere"})", "application/json");
    if (!res || res->status != 201) std::abort();
    id = json::parse(res->body)["id"];
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

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Harness h;
  FuzzedDataProvider in(data, size);
  const std::string method = in.PickValueInArray({"GET", "POST", "PATCH", "DELETE", "PUT"});
  const std::string route = in.PickValueInArray(
      {"/api/v1/sessions", "/api/v1/sessions/{id}", "/api/v1/sessions/{id}/advance",
       "/api/v1/sessions/{id}/reset", "/api/v1/sessions/{id}/pause", "/api/v1/sessions/{id}/trajectory",
       "/api/v1/sessions/{id}/frame.png", "/api/v1/sessions/nope", "/api/v1/schema", "/api/v1/scenes",
       "/api/v1/integrators", "/api/v1/health", "/api/v1/"});
  std::string target = route;
  if (const auto at = target.find("{id}"); at != std::string::npos) target.replace(at, 4, h.id);
  const int parameters = in.ConsumeIntegralInRange(0, 3);
  for (int k = 0; k < parameters; ++k) {
    const std::string key = in.PickValueInArray({"format", "width", "height", "view", "layers", "yaw",
                                                 "pitch", "distance", "scale", "rate", "trail", "x"});
    target += (k == 0 ? "?" : "&") + key + "=" +
              httplib::detail::encode_query_param(in.ConsumeRandomLengthString(24));
  }
  const std::string type = in.PickValueInArray({"application/json", "application/merge-patch+json",
                                                "text/plain", "application/json; charset=utf-8", ""});
  const std::string body = in.ConsumeRemainingBytesAsString();

  const std::string before = h.session_body();
  httplib::Client c = h.client();
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
  // Keep the stage as it was: sessions the input made go, the target session comes back.
  if (method == "POST" && route == "/api/v1/sessions" && res->status == 201) {
    const json made = json::parse(res->body, nullptr, false);
    if (made.is_object() && made.contains("id"))
      c.Delete("/api/v1/sessions/" + made["id"].get<std::string>());
  }
  if (h.session_body().empty()) h.new_session();
  return 0;
}
