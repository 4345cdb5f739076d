// The bad-request table: every case answers problem+json naming the field and changes nothing.
// Shared by the in-process API tests and the tests through the nginx front (tests/front/).
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

// After Eigen (through the server's headers): httplib.h brings <resolv.h>'s `_res` macro.
#include <httplib.h>

namespace spinfold::server::test {

struct BadRequest {
  std::string method;
  std::string path;  // "{id}" is replaced by a live session's id
  std::string body;
  std::string content_type;
  int status;
  std::string field;  // the field the problem names ("" for any)
};

inline void PrintTo(const BadRequest& b, std::ostream* os) {
  *os << b.method << " " << b.path << " " << b.body.substr(0, 60);
}

inline std::vector<BadRequest> bad_requests() {
  const std::string kDeep = std::string(100, '[') + std::string(100, ']');
  // Over the server's 64 KiB body limit and the front's.
  const std::string kHuge = "{\"name\": \"" + std::string(70000, 'x') + "\"}";
  const std::string kNul(1, '\0');
  return {

      BadRequest{"POST", "/api/v1/sessions", "{}", "text/plain", 415, "Content-Type"},
      BadRequest{"POST", "/api/v1/sessions", "{\"surface\": ", "application/json", 400, ""},
      BadRequest{"POST", "/api/v1/sessions", "\x88", "application/json", 400, ""},  // not UTF-8
      BadRequest{"PATCH", "/api/v1/sessions/{id}", "{\"name\": \"\xff\"}", "application/json", 400, ""},
      BadRequest{"POST", "/api/v1/sessions", kDeep, "application/json", 400, ""},
      BadRequest{"POST", "/api/v1/sessions", kHuge, "application/json", 413, ""},
      BadRequest{"POST", "/api/v1/sessions", R"({"body": {"mass": -1}})", "application/json", 422,
                 "body.mass"},
      BadRequest{"POST", "/api/v1/sessions", R"({"gravity": 9.8})", "application/json", 422, "gravity"},
      BadRequest{"POST", "/api/v1/sessions", R"({"preset": "no_such"})", "application/json", 422, "preset"},
      BadRequest{"POST", "/api/v1/sessions", R"({"surface": {"kind": "klein_bottle"}})", "application/json",
                 422, "surface.kind"},
      BadRequest{"POST", "/api/v1/sessions", R"({"integrator": {"name": "euler"}})", "application/json", 422,
                 "integrator.name"},
      BadRequest{"POST", "/api/v1/sessions", R"({"initial": {"r": 1e400}})", "application/json", 400, ""},
      BadRequest{"GET", "/api/v1/sessions/0123456789abcdef", "", "", 404, "id"},
      BadRequest{"DELETE", "/api/v1/sessions/0123456789abcdef", "", "", 404, "id"},
      BadRequest{"POST", "/api/v1/sessions/{id}/advance", R"({"until": -1})", "application/json", 422,
                 "until"},
      BadRequest{"POST", "/api/v1/sessions/{id}/advance", R"({"until": 1, "steps": 2})", "application/json",
                 422, "until"},
      BadRequest{"POST", "/api/v1/sessions/{id}/advance", R"({})", "application/json", 422, "until"},
      BadRequest{"POST", "/api/v1/sessions/{id}/advance", R"({"steps": 2.5})", "application/json", 422,
                 "steps"},
      BadRequest{"POST", "/api/v1/sessions/{id}/advance", R"({"steps": 1e9})", "application/json", 422,
                 "steps"},
      BadRequest{"POST", "/api/v1/sessions/{id}/advance", R"({"until": "soon"})", "application/json", 422,
                 "until"},
      BadRequest{"POST", "/api/v1/sessions/{id}/advance", R"({"until": 1e12})", "application/json", 422,
                 "until"},
      BadRequest{"POST", "/api/v1/sessions/{id}/advance", R"({"speed": 2})", "application/json", 422,
                 "speed"},
      BadRequest{"POST", "/api/v1/sessions/{id}/advance", R"([1, 2])", "application/json", 400, ""},
      BadRequest{"POST", "/api/v1/sessions/{id}/advance", R"({"until": 1})", "application/xml", 415,
                 "Content-Type"},
      BadRequest{"GET", "/api/v1/sessions/{id}/frame.png?width=5000", "", "", 422, "width"},
      BadRequest{"GET", "/api/v1/sessions/{id}/frame.png?height=abc", "", "", 422, "height"},
      BadRequest{"GET", "/api/v1/sessions/{id}/frame.png?view=hyperboloid", "", "", 422, "view"},
      BadRequest{"GET", "/api/v1/sessions/{id}/frame.png?view=cube", "", "", 422, "view"},
      BadRequest{"GET", "/api/v1/sessions/{id}/frame.png?layers=body,glitter", "", "", 422, "layers"},
      BadRequest{"GET", "/api/v1/sessions/{id}/frame.png?scale=-1", "", "", 422, "scale"},
      BadRequest{"GET", "/api/v1/sessions/{id}/trajectory?format=xml", "", "", 422, "format"},
      BadRequest{"GET", "/api/v1/nowhere", "", "", 404, ""},
      BadRequest{"DELETE", "/api/v1/scenes", "", "", 405, "method"},
      BadRequest{"POST", "/api/v1/sessions/{id}/frame.png", "{}", "application/json", 405, "method"},
      BadRequest{"PATCH", "/api/v1/sessions/{id}/advance", "{}", "application/json", 405, "method"},
      BadRequest{"PATCH", "/api/v1/sessions/{id}", R"({"body": {"inertia": 0}})", "application/json", 422,
                 "body.inertia"},
      BadRequest{"PATCH", "/api/v1/sessions/{id}", R"({"surface": {"kind": "cylinder"}})", "application/json",
                 422, "surface.kind"},
      BadRequest{"PATCH", "/api/v1/sessions/{id}", R"({"initial": {"lambda": -1}})", "application/json", 422,
                 "initial.lambda"},
      BadRequest{"PATCH", "/api/v1/sessions/{id}", R"("mass")", "application/json", 400, ""},
      BadRequest{"POST", "/api/v1/sessions/{id}/play", R"({"rate": -1})", "application/json", 422, "rate"},
      BadRequest{"POST", "/api/v1/sessions/{id}/play", R"({"speed": 1})", "application/json", 422, "speed"},
      BadRequest{"GET", "/api/v1/sessions/{id}/events?rate=1000", "", "", 422, "rate"},
      // Not exactly one JSON value: a NUL byte (nlohmann-json alone reads it as the end of input),
      // text after the value, a second value.
      BadRequest{"PATCH", "/api/v1/sessions/{id}", R"({"body":{"mass":2.5}})" + kNul + "garbage",
                 "application/json", 400, ""},
      BadRequest{"POST", "/api/v1/sessions/{id}/advance", R"({"until":7.1})" + kNul, "application/json", 400,
                 ""},
      BadRequest{"POST", "/api/v1/sessions/{id}/advance", kNul + R"({"until":7.1})", "application/json", 400,
                 ""},
      BadRequest{"POST", "/api/v1/sessions/{id}/advance", R"({"until":7.1} x)", "application/json", 400, ""},
      BadRequest{"POST", "/api/v1/sessions/{id}/advance", R"({"until":7.1}{"until":8})", "application/json",
                 400, ""},
      BadRequest{"PATCH", "/api/v1/sessions/{id}", R"({"body":{"mass":2.5}} {"body":{"mass":3}})",
                 "application/json", 400, ""},
      BadRequest{"POST", "/api/v1/sessions/{id}/play", R"({"rate":2})" + kNul + "}", "application/json", 400,
                 ""},
      // Recording windows whose frame count does not fit an integer: 422 naming the field, no job.
      BadRequest{"POST", "/api/v1/sessions/{id}/recordings", R"({"t_end": 1e308, "format": "gif"})",
                 "application/json", 422, "t_end"},
      BadRequest{"POST", "/api/v1/sessions/{id}/recordings", R"({"t_end": 1e19, "format": "gif"})",
                 "application/json", 422, "t_end"},
      BadRequest{"POST", "/api/v1/sessions/{id}/recordings",
                 R"({"t_end": 1, "speed": 1e-300, "format": "gif"})", "application/json", 422, "speed"},
      BadRequest{"POST", "/api/v1/sessions/{id}/recordings", R"({"speed": 1e-300, "format": "gif"})",
                 "application/json", 422, "speed"},
      BadRequest{"POST", "/api/v1/sessions/{id}/recordings",
                 R"({"t_end": 1, "fps": 1e-300, "format": "gif"})", "application/json", 422, "fps"},
      BadRequest{"POST", "/api/v1/sessions/{id}/recordings", R"({"t_start": 1e308, "format": "gif"})",
                 "application/json", 422, "t_end"},
      // RFC 3986: an encoded slash is data within a segment, not a separator.
      BadRequest{"POST", "/api/v1/sessions%2F{id}/advance", R"({"until":7.1})", "application/json", 404,
                 "path"},
      BadRequest{"PATCH", "/api/v1/sessions%2f{id}", R"({"body":{"mass":2.5}})", "application/json", 404,
                 "path"}};
}

// Sends the request (with the session id in its path) and checks the answer: status,
// problem+json with a detail, the field named.
inline void expect_problem(httplib::Client& c, const BadRequest& b, const std::string& id) {
  std::string path = b.path;
  if (const auto at = path.find("{id}"); at != std::string::npos) path.replace(at, 4, id);
  httplib::Result res = b.method == "GET"      ? c.Get(path)
                        : b.method == "DELETE" ? c.Delete(path)
                        : b.method == "PATCH"  ? c.Patch(path, b.body, b.content_type)
                                               : c.Post(path, b.body, b.content_type);
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, b.status) << res->body.substr(0, 300);
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/problem+json");
  const nlohmann::json problem = nlohmann::json::parse(res->body, nullptr, false);
  ASSERT_TRUE(problem.is_object()) << res->body.substr(0, 300);
  EXPECT_EQ(problem["status"], b.status);
  EXPECT_FALSE(problem["detail"].get<std::string>().empty());
  if (!b.field.empty()) {
    bool named = false;
    for (const auto& e : problem["errors"]) named = named || e["field"] == b.field;
    EXPECT_TRUE(named) << res->body.substr(0, 300);
  }
}

}  // namespace spinfold::server::test
