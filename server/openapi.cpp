#include "server/openapi.h"

#include <string>
#include <vector>

#include "codec/scene_schema.h"

namespace spinfold::server {

using json = nlohmann::ordered_json;

namespace {

struct Operation {
  const char* path;
  const char* method;
  const char* summary;
  std::vector<std::pair<const char*, const char*>> responses;  // status → description
  bool json_body = false;
};

}  // namespace

json openapi_document() {
  const std::vector<Operation> operations = {
      {"/api/v1/health", "get", "Liveness, version and session count", {{"200", "ok"}}},
      {"/api/v1/scenes", "get", "The preset scenes", {{"200", "name, description, scene"}}},
      {"/api/v1/integrators", "get", "The integrator catalog", {{"200", "catalog entries"}}},
      {"/api/v1/schema", "get", "The scene format as JSON Schema", {{"200", "JSON Schema"}}},
      {"/api/v1/openapi.json", "get", "This document", {{"200", "OpenAPI 3"}}},
      {"/api/v1/sessions",
       "post",
       "Create a session from a scene or {\"preset\": name}",
       {{"201", "created; Location"},
        {"400", "malformed"},
        {"413", "too large"},
        {"415", "not JSON"},
        {"422", "invalid scene"},
        {"503", "session limit; Retry-After"}},
       true},
      {"/api/v1/sessions/{id}",
       "get",
       "The session's state and scene",
       {{"200", "state"}, {"404", "unknown"}}},
      {"/api/v1/sessions/{id}",
       "patch",
       "Merge-patch the scene (continues from the current state) or set the state",
       {{"200", "state"}, {"409", "state not expressible"}, {"422", "invalid"}},
       true},
      {"/api/v1/sessions/{id}", "delete", "Delete the session", {{"204", "deleted"}, {"404", "unknown"}}},
      {"/api/v1/sessions/{id}/advance",
       "post",
       "Advance to {\"until\": t} or by {\"steps\": n}; at most max_steps attempts (\"advance\": "
       "{\"complete\": false} when they run out first)",
       {{"200", "state"}, {"422", "invalid or over a limit"}},
       true},
      {"/api/v1/sessions/{id}/play",
       "post",
       "Advance in real time at {\"rate\": r}",
       {{"200", "state"}, {"409", "stopped"}},
       true},
      {"/api/v1/sessions/{id}/pause", "post", "Stop real-time advancing", {{"200", "state"}}},
      {"/api/v1/sessions/{id}/reset", "post", "Back to the scene's initial state at its start time", {{"200", "state"}}},
      {"/api/v1/sessions/{id}/events",
       "get",
       "Server-Sent Events: the state when it changes (?rate=hz)",
       {{"200", "text/event-stream"}, {"429", "stream limit; Retry-After"}}},
      {"/api/v1/sessions/{id}/trajectory",
       "get",
       "Recorded samples (?format=json|csv)",
       {{"200", "samples"}}},
      {"/api/v1/sessions/{id}/frame.png",
       "get",
       "A PNG frame (?view=&width=&height=&layers=&scale=); ETag, 304",
       {{"200", "image/png"},
        {"304", "unchanged"},
        {"422", "invalid parameter"},
        {"503", "rendering unavailable"}}},
  };
  json paths = json::object();
  for (const Operation& op : operations) {
    json responses = json::object();
    for (const auto& [status, description] : op.responses) responses[status] = {{"description", description}};
    json operation{{"summary", op.summary}, {"responses", responses}};
    if (std::string(op.path).find("{id}") != std::string::npos)
      operation["parameters"] = {
          {{"name", "id"}, {"in", "path"}, {"required", true}, {"schema", {{"type", "string"}}}}};
    if (op.json_body)
      operation["requestBody"] = {{"content", {{"application/json", {{"schema", {{"type", "object"}}}}}}}};
    paths[op.path][op.method] = operation;
  }
  json components{{"schemas",
                   {{"Scene", scene_schema()},
                    {"Problem",
                     {{"type", "object"},
                      {"properties",
                       {{"type", {{"type", "string"}}},
                        {"title", {{"type", "string"}}},
                        {"status", {{"type", "integer"}}},
                        {"detail", {{"type", "string"}}},
                        {"errors", {{"type", "array"}}}}}}}}}};
  return {{"openapi", "3.0.3"},
          {"info", {{"title", "Spinfold API"}, {"version", "1"}}},
          {"servers", {{{"url", "/"}}}},
          {"paths", paths},
          {"components", components}};
}

}  // namespace spinfold::server
