// Sessions: create, read, patch, delete, and the run's controls (advance, play, pause, reset) and
// record (trajectory).
#include <cmath>
#include <sstream>
#include <variant>

#include "codec/presets.h"
#include "codec/sample_json.h"
#include "codec/scene_json.h"
#include "engine/number_text.h"
#include "engine/paper_coordinates.h"
#include "server/context.h"
#include "server/problem.h"
#include "server/route_table.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

namespace {

using nlohmann::json;
using nlohmann::ordered_json;

const std::string kSessions = "/api/v1/sessions";

// The current state as a scene's "initial" block, so that new parameters apply from here on; or
// the reason it cannot be written in the paper's coordinates.
std::variant<json, std::string> current_initial(const Session& s) {
  const PaperCoordinates c = paper_coordinates(s.scene, s.run.state);
  if (!c.phi || !c.r_dot || !c.phi_dot) return std::string("the body is at a pole, where phi is undefined");
  if (!(c.mu > 0.0))
    return std::string("the frame is mirrored (det L <= 0), which an initial state cannot be");
  const bool rigid = s.scene.body.model == BodyModel::rigid;
  const bool isotropic = !c.alpha;  // λ = μ: only θ = α − β is defined; write it as α with β = 0
  json q{{"r", c.r},
         {"phi", *c.phi},
         {"alpha", isotropic ? c.theta.value_or(0.0) : *c.alpha},
         {"beta", isotropic ? 0.0 : *c.beta},
         {"lambda", rigid ? s.scene.initial.lambda : c.lambda},
         {"mu", rigid ? s.scene.initial.lambda : c.mu},
         {"r_dot", *c.r_dot},
         {"phi_dot", *c.phi_dot},
         {"alpha_dot", isotropic ? c.theta_dot.value_or(0.0) : *c.alpha_dot},
         {"beta_dot", isotropic ? 0.0 : *c.beta_dot},
         {"lambda_dot", rigid ? 0.0 : c.lambda_dot},
         {"mu_dot", rigid ? 0.0 : c.mu_dot}};
  return q;
}

// The session's answer with its provenance.
void send_session(httplib::Response& res, const std::string& id, const Session& s, int status = 200) {
  res.set_header("X-Spinfold-Provenance", provenance(s));
  send_json(res, session_json(id, s), status);
}

// POST /sessions: a scene, or {"preset": name}; ?start_time=t0: its initial state holds at t0.
void create_session(ServerContext& server, const Call& call, httplib::Response& res) {
  json body = call.body();
  SceneParse parsed;
  if (body.is_object() && body.size() == 1 && body.contains("preset")) {
    const json& name = body["preset"];
    const PresetSource* p = name.is_string() ? find_preset(name.get<std::string>()) : nullptr;
    if (!p) throw bad(422, "Unknown preset", "preset", name.dump(), "is not a preset (GET /api/v1/scenes)");
    parsed = parse_scene_text(p->json);
  } else {
    parsed = parse_scene(body);
  }
  if (!parsed.scene) throw ApiError{422, "Invalid scene", parsed.errors, ""};
  std::string id;
  const auto session = server.sessions.create(*parsed.scene, id, *call.query.number("start_time"));
  if (!session)
    throw ApiError{503, "Too many sessions", {{"", "", "the session limit is reached; retry later"}}, "30"};
  const std::lock_guard lock(session->mutex);
  res.set_header("Location", kSessions + "/" + id);
  send_session(res, id, *session, 201);
}

// GET: the state's JSON is built once per change of state and then served as it is.
void get_session(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto s = find_session(server, call.id);
  const std::lock_guard lock(s->mutex);
  if (s->body_version != s->version) {
    s->body = session_json(call.id, *s).dump();
    s->body_version = s->version;
  }
  res.set_header("X-Spinfold-Provenance", provenance(*s));
  res.body = s->body;
  res.set_header("Content-Type", "application/json");
}

void delete_session(ServerContext& server, const Call& call, httplib::Response& res) {
  if (!server.sessions.erase(call.id)) throw unknown_session(call.id);
  res.status = 204;
}

// PATCH: a JSON merge patch of the scene. Without "initial" the run continues from its current
// state (and time) under the new parameters; with it, that state is set.
void patch_session(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto s = find_session(server, call.id);
  const json patch = call.body();
  require_object(patch);
  const std::lock_guard lock(s->mutex);
  json document = scene_to_json(s->scene);
  if (!patch.contains("initial")) {
    // A patch that changes nothing leaves the run as it is (no restart from the paper coordinates,
    // which would cost bits and the integrator's step size).
    json unchanged = document;
    unchanged.merge_patch(patch);
    const SceneParse same = parse_scene(unchanged);
    if (same.scene && scene_to_json(*same.scene) == document) return send_session(res, call.id, *s);
    auto initial = current_initial(*s);
    if (auto* why = std::get_if<std::string>(&initial))
      throw bad(409, "Conflict", "initial", "", *why + ": give \"initial\" explicitly");
    document["initial"] = std::get<json>(initial);
  }
  document.merge_patch(patch);
  const SceneParse parsed = parse_scene(document);
  if (!parsed.scene) throw ApiError{422, "Invalid scene", parsed.errors, ""};
  const double now = s->run.state.t;
  s->scene = *parsed.scene;
  s->run = start_simulation(s->scene, now);
  s->reported_events = 0;
  record_sample(*s);
  send_session(res, call.id, *s);
}

// The time an advance request aims at ({"until": t} or {"steps": n}), within the limits (lock held).
double advance_target(const json& body, const Session& s, const Limits& limits) {
  refuse_unknown_keys(body, {"until", "steps"});
  if (body.contains("until") == body.contains("steps"))
    throw bad(422, "Invalid value", "until", body.dump(), "give exactly one of until or steps");
  const double now = s.run.state.t;
  double target = 0.0;
  if (body.contains("until")) {
    target = number_field(body, "until");
    if (target < now)
      throw bad(422, "Invalid value", "until", body["until"].dump(),
                "is before the session's time (t = " + shortest(now) + ")");
  } else {
    const double steps = number_field(body, "steps");
    if (steps < 1 || steps != std::floor(steps))
      throw bad(422, "Invalid value", "steps", body["steps"].dump(), "must be a whole number >= 1");
    if (steps > static_cast<double>(limits.max_steps))
      throw bad(422, "Over a limit", "steps", body["steps"].dump(),
                "exceeds the limit of " + shortest(static_cast<long long>(limits.max_steps)) +
                    " steps per request");
    target = now + steps * s.scene.integrator.dt;
  }
  if (target - now > limits.max_advance_time)
    throw bad(422, "Over a limit", "until", shortest(target),
              "advances more than " + shortest(limits.max_advance_time) + " time units in one request");
  if (!s.run.info->adaptive && !s.run.info->exact &&
      (target - now) / s.scene.integrator.dt > static_cast<double>(limits.max_steps))
    throw bad(422, "Over a limit", "until", shortest(target),
              "needs more than " + shortest(static_cast<long long>(limits.max_steps)) +
                  " fixed steps in one request");
  return target;
}

// An adaptive method may need any number of steps: the work is bounded, the progress kept.
void advance_session(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto s = find_session(server, call.id);
  const json body = call.body();
  require_object(body);
  const Limits& limits = server.options.limits;
  const std::lock_guard lock(s->mutex);
  const double target = advance_target(body, *s, limits);
  const bool complete = advance_to(s->run, target, static_cast<std::uint64_t>(limits.max_steps));
  record_sample(*s);
  res.set_header("X-Spinfold-Provenance", provenance(*s));
  ordered_json out = session_json(call.id, *s);
  out["advance"] = {{"until", target}, {"complete", complete}};
  if (!complete)
    out["advance"]["reason"] = "stopped after " + shortest(static_cast<long long>(limits.max_steps)) +
                               " step attempts, the limit per request, at t = " + shortest(s->run.state.t) +
                               ": advance again to continue";
  send_json(res, out);
}

void play_session(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto s = find_session(server, call.id);
  double rate = 1.0;
  if (call.has_body()) {
    const json body = call.body();
    require_object(body);
    refuse_unknown_keys(body, {"rate"});
    if (body.contains("rate")) {
      rate = number_field(body, "rate");
      if (!(rate > 0.0) || rate > server.options.limits.max_play_rate)
        throw bad(422, "Invalid value", "rate", body["rate"].dump(),
                  "must be > 0 and <= " + shortest(server.options.limits.max_play_rate));
    }
  }
  const std::lock_guard lock(s->mutex);
  if (s->run.state.status != Status::ok)
    throw bad(409, "Conflict", "status", std::string(status_name(s->run.state.status)),
              "the run has stopped; reset or PATCH it first");
  s->playing = true;
  s->rate = rate;
  send_json(res, session_json(call.id, *s));
}

void pause_session(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto s = find_session(server, call.id);
  const std::lock_guard lock(s->mutex);
  s->playing = false;
  send_json(res, session_json(call.id, *s));
}

// Back to where the scene's initial state holds: its start time (after a PATCH, the moment of the
// patch), not t = 0 with a later state.
void reset_session(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto s = find_session(server, call.id);
  const std::lock_guard lock(s->mutex);
  s->run = start_simulation(s->scene, s->run.start_time);
  s->trajectory.clear();
  s->trail.clear();
  s->reported_events = 0;
  record_sample(*s);
  send_json(res, session_json(call.id, *s));
}

void get_trajectory(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto s = find_session(server, call.id);
  const std::lock_guard lock(s->mutex);
  if (*call.query.text("format") == "json") return send_json(res, ordered_json(s->trajectory));
  std::ostringstream csv;
  csv.precision(17);
  csv << "t,r,phi,lambda,mu,det_L,energy,energy_error,X0,X1,X2,status\n";
  const auto cell = [](const ordered_json& v) { return v.is_null() ? std::string() : v.dump(); };
  for (const ordered_json& row : s->trajectory)
    csv << cell(row["t"]) << "," << cell(row["r"]) << "," << cell(row["phi"]) << "," << cell(row["lambda"])
        << "," << cell(row["mu"]) << "," << cell(row["det_L"]) << "," << cell(row["energy"]) << ","
        << cell(row["energy_error"]) << "," << cell(row["X"][0]) << "," << cell(row["X"][1]) << ","
        << cell(row["X"][2]) << "," << row["status"].get<std::string>() << "\n";
  res.body = csv.str();
  res.set_header("Content-Type", "text/csv");
}

}  // namespace

std::vector<Route> session_routes(const Limits& limits) {
  const std::string sid = kSessions + "/{id}";
  const ordered_json scene_ref = {{"$ref", "#/components/schemas/Scene"}};
  return {
      {.method = "POST",
       .path = kSessions,
       .handler = create_session,
       .summary = "Create a session from a scene or {\"preset\": name}",
       .query = {{.name = "start_time",
                  .type = ParamType::number,
                  .minimum = 0.0,
                  .default_value = 0.0,
                  .description = "the time at which the scene's initial state holds (a shared PATCHed "
                                 "session)"}},
       .body = RequestBody{.description = "a scene, or {\"preset\": name} (GET /api/v1/scenes)",
                           .schema = {{"oneOf",
                                       {scene_ref,
                                        {{"type", "object"},
                                         {"required", {"preset"}},
                                         {"properties", {{"preset", {{"type", "string"}}}}},
                                         {"additionalProperties", false}}}}}},
       .responses = {{201, "created: Location, {\"id\", \"state\", \"scene\", \"start_time\"}"},
                     {422, "invalid scene, unknown preset"},
                     {503, "session limit; Retry-After"}}},
      {.method = "GET",
       .path = sid,
       .handler = get_session,
       .summary = "The session's state and scene",
       .responses = {{200, "{\"id\", \"state\", \"scene\", \"start_time\"}"}}},
      {.method = "PATCH",
       .path = sid,
       .handler = patch_session,
       .summary = "Merge-patch the scene (continues from the current state) or set the state (\"initial\")",
       .body = RequestBody{.description = "a JSON merge patch (RFC 7396) of the scene",
                           .content_types = {"application/json", "application/merge-patch+json"},
                           .schema = {{"type", "object"}}},
       .responses = {{200, "the session"},
                     {409, "the current state has no paper coordinates: give \"initial\""},
                     {422, "invalid scene"}}},
      {.method = "DELETE",
       .path = sid,
       .handler = delete_session,
       .summary = "Delete the session",
       .responses = {{204, "deleted"}}},
      {.method = "POST",
       .path = sid + "/advance",
       .handler = advance_session,
       .summary = "Advance to {\"until\": t} or by {\"steps\": n}; at most " +
                  shortest(static_cast<long long>(limits.max_steps)) +
                  " step attempts (\"advance\": {\"complete\": false} when they run out first)",
       .body =
           RequestBody{
               .description = "exactly one of until (a time) or steps (of the scene's dt)",
               .schema = {{"type", "object"},
                          {"properties",
                           {{"until", {{"type", "number"}}},
                            {"steps", {{"type", "integer"}, {"minimum", 1}, {"maximum", limits.max_steps}}}}},
                          {"additionalProperties", false}}},
       .responses = {{200, "the session and \"advance\": {\"until\", \"complete\", \"reason\"}"},
                     {422, "invalid, or over a limit per request"}}},
      {.method = "POST",
       .path = sid + "/play",
       .handler = play_session,
       .summary = "Advance in real time at {\"rate\": r} simulated time per second",
       .body = RequestBody{.description = "optional: {\"rate\": r}, default 1",
                           .required = false,
                           .schema = {{"type", "object"},
                                      {"properties",
                                       {{"rate",
                                         {{"type", "number"},
                                          {"exclusiveMinimum", true},
                                          {"minimum", 0},
                                          {"maximum", limits.max_play_rate},
                                          {"default", 1}}}}},
                                      {"additionalProperties", false}}},
       .responses = {{200, "the session"}, {409, "the run has stopped"}}},
      {.method = "POST",
       .path = sid + "/pause",
       .handler = pause_session,
       .summary = "Stop real-time advancing",
       .responses = {{200, "the session"}}},
      {.method = "POST",
       .path = sid + "/reset",
       .handler = reset_session,
       .summary = "Back to the scene's initial state at the session's start time",
       .responses = {{200, "the session"}}},
      {.method = "GET",
       .path = sid + "/trajectory",
       .handler = get_trajectory,
       .summary = "The recorded samples: one after creation and after every advance",
       .query = {{.name = "format",
                  .type = ParamType::enumeration,
                  .values = {"json", "csv"},
                  .default_value = "json",
                  .description = "json: an array of samples; csv: t, r, phi, lambda, mu, det_L, energy, "
                                 "energy_error, X, status"}},
       .responses = {{200, "application/json or text/csv"}}},
  };
}

}  // namespace spinfold::server
