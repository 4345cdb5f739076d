// Sessions: create, read, patch, delete, and the run's controls (advance, play, pause, reset) and
// record (trajectory).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "codec/presets.h"
#include "codec/provenance.h"
#include "codec/sample_json.h"
#include "codec/sample_table.h"
#include "codec/scene_json.h"
#include "engine/number_rule.h"
#include "engine/number_text.h"
#include "engine/timeline.h"
#include "server/context.h"
#include "server/http/problem.h"
#include "server/routes/routes.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

using nlohmann::json;
using nlohmann::ordered_json;

// A scene, or {"preset": name}; `field` names it in errors ("" at the top, "scene" in a link).
Scene scene_of(const json& body, const std::string& field) {
  const std::string prefix = field.empty() ? "" : field + ".";
  SceneParse parsed;
  if (body.is_object() && body.size() == 1 && body.contains("preset")) {
    const json& name = body["preset"];
    const PresetSource* p = name.is_string() ? find_preset(name.get<std::string>()) : nullptr;
    if (!p)
      throw bad(422, "Unknown preset", prefix + "preset", name.dump(),
                "is not a preset (GET /api/v1/scenes)");
    parsed = parse_scene_text(p->json);
  } else {
    parsed = parse_scene(body);
    for (FieldError& e : parsed.errors) e.field = e.field.empty() ? field : prefix + e.field;
  }
  if (!parsed.scene) throw ApiError{422, "Invalid scene", parsed.errors, ""};
  return *parsed.scene;
}

namespace {

const std::string kSessions = "/api/v1/sessions";
constexpr double kMaxTrajectoryRows = 100000;

// Bytes as a person reads them, to three digits: "64.0 MiB", "9.25 kiB", "512 B".
std::string size_text(double bytes) {
  const char* units[] = {"B", "kiB", "MiB", "GiB"};
  int unit = 0;
  for (; unit < 3 && bytes >= 1024.0; ++unit) bytes /= 1024.0;
  const int decimals = unit == 0 || bytes >= 100.0 ? 0 : bytes >= 10.0 ? 1 : 2;
  char text[32];
  std::snprintf(text, sizeof text, "%.*f %s", decimals, bytes, units[unit]);
  return text;
}

// The bytes a row's numbers may take past those of `row`'s text: a run's first row (t = 0, numbers
// such as 0 and 1) is shorter than the rows after it, whose doubles take up to 17 digits, a sign, a
// point and an exponent, and whose counts grow.
double row_widening(const ordered_json& row) {
  constexpr double kDoubleWidth = 22, kCountWidth = 10;  // "-0.12345678901234567e-5"; 10¹⁰ steps
  if (row.is_structured()) {
    double extra = 0.0;
    for (const ordered_json& value : row) extra += row_widening(value);
    return extra;
  }
  if (!row.is_number()) return 0.0;
  const double width = row.is_number_float() ? kDoubleWidth : kCountWidth;
  return std::max(0.0, width - static_cast<double>(row.dump().size()));
}

// A share link's body: {"scene", "timeline", "until"} (a scene itself never has a "scene" key).
bool is_share_link(const json& body) {
  if (!body.is_object() || !body.contains("scene")) return false;
  for (const auto& [key, value] : body.items())
    if (key != "scene" && key != "timeline" && key != "until") return false;
  return true;
}

// POST /sessions: a scene, {"preset": name}, or a share link rebuilt from t = 0 to `until`.
void create_session(ServerContext& server, const Call& call, httplib::Response& res) {
  const json body = call.body();
  require_object(body);
  const Limits& limits = server.options.limits;
  const bool link = is_share_link(body);
  const Scene scene = scene_of(link ? body["scene"] : body, link ? "scene" : "");
  double until = 0.0;
  const json timeline = link ? body.value("timeline", json::array()) : json::array();
  if (link && body.contains("until")) {
    until = number_field(body, "until");
    const NumberRule rule{.range = {.min = 0.0, .max = limits.max_advance_time}, .unit = "time"};
    if (const auto why = refusal(rule, until))
      throw bad(422, "Invalid value", "until", body["until"].dump(), *why);
  }
  std::string id;
  const auto session = server.sessions.create(scene, id);
  if (!session)
    throw ApiError{503, "Too many sessions", {{"", "", "the session limit is reached; retry later"}}, "30"};
  try {
    // Counted until deleted (here or, with a store, through another replica) or expired.
    server.quotas.add_session(call.client, id, session, [&server](const std::string& other) {
      return server.sessions.deleted_elsewhere(other);
    });
  } catch (const ApiError&) {
    server.sessions.erase(id);
    throw;
  }
  const std::lock_guard lock(session->mutex);
  std::optional<Rebuild> rebuilt;
  if (link) {
    // The work is bounded like that of advances: max_steps attempts per segment of the timeline.
    const auto budget = static_cast<std::uint64_t>(limits.max_steps) * (timeline.size() + 1);
    rebuilt = rebuild(*session, scene, timeline, until, budget);
    if (!rebuilt->errors.empty()) {
      server.sessions.erase(id);
      throw ApiError{422, "Invalid timeline", rebuilt->errors, ""};
    }
  }
  commit(server, id, *session);
  res.set_header("Location", kSessions + "/" + id);
  res.set_header("X-Spinfold-Provenance", provenance(*session));
  ordered_json out = session_json(id, *session);
  if (rebuilt) {
    out["advance"] = {{"until", until}, {"complete", rebuilt->complete}};
    if (!rebuilt->complete)
      out["advance"]["reason"] = "stopped at t = " + shortest(session->run.state.t) +
                                 " after the step attempts allowed per request: advance again to continue";
  }
  send_json(res, out, 201);
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
  remove_session(server, call.id);
  server.quotas.release_session(call.id);
  res.status = 204;
}

// PATCH: a JSON merge patch of the parameters in force. The run continues from its current time
// and state (a timeline entry), or starts over when the start or the surface changed.
void patch_session(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto s = find_session(server, call.id);
  const json patch = call.body();
  require_object(patch);
  const std::lock_guard lock(s->mutex);
  const double t = s->run.state.t;
  const ChangeOutcome outcome = change(*s, patch);
  if (!outcome.errors.empty()) throw ApiError{422, "Invalid scene", outcome.errors, ""};
  if (outcome.kind != ChangeOutcome::unchanged) commit(server, call.id, *s);
  static constexpr const char* kinds[] = {"unchanged", "continued", "restarted"};
  ordered_json out = session_json(call.id, *s);
  out["change"] = {{"kind", kinds[outcome.kind]},
                   {"t", outcome.kind == ChangeOutcome::restarted ? 0.0 : t},
                   {"reason", outcome.reason}};
  res.set_header("X-Spinfold-Provenance", provenance(*s));
  send_json(res, out);
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
    if (const auto why = refusal({.whole = true, .range = {.min = 1.0}}, steps))
      throw bad(422, "Invalid value", "steps", body["steps"].dump(), *why);
    if (steps > static_cast<double>(limits.max_steps))
      throw bad(422, "Over a limit", "steps", body["steps"].dump(),
                "exceeds the limit of " + shortest(static_cast<long long>(limits.max_steps)) +
                    " steps per request");
    target = now + steps * s.run.scene.integrator.dt;
  }
  if (target - now > limits.max_advance_time)
    throw bad(422, "Over a limit", "until", shortest(target),
              "advances more than " + shortest(limits.max_advance_time) + " time units in one request");
  if (!s.run.info->adaptive && !s.run.info->exact &&
      (target - now) / s.run.scene.integrator.dt > static_cast<double>(limits.max_steps))
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
  const AdvanceEnd end =
      advance(*s, target, static_cast<std::uint64_t>(limits.max_steps), limits.max_advance_seconds);
  commit(server, call.id, *s);
  res.set_header("X-Spinfold-Provenance", provenance(*s));
  ordered_json out = session_json(call.id, *s);
  out["advance"] = {{"until", target}, {"complete", end == AdvanceEnd::reached}};
  if (end != AdvanceEnd::reached)
    out["advance"]["reason"] =
        "stopped after " +
        (end == AdvanceEnd::attempts ? shortest(static_cast<long long>(limits.max_steps)) + " step attempts"
                                     : shortest(limits.max_advance_seconds) + " s of work") +
        ", the limit per request, at t = " + shortest(s->run.state.t) + ": advance again to continue";
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
  commit(server, call.id, *s);
  send_json(res, session_json(call.id, *s));
}

void pause_session(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto s = find_session(server, call.id);
  const std::lock_guard lock(s->mutex);
  s->playing = false;
  commit(server, call.id, *s);  // the time played so far too
  send_json(res, session_json(call.id, *s));
}

// Back to t = 0 with the parameters in force: they become the scene, the timeline empties.
void reset_session(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto s = find_session(server, call.id);
  const std::lock_guard lock(s->mutex);
  restart(*s, s->run.scene);
  commit(server, call.id, *s);
  send_json(res, session_json(call.id, *s));
}

// The samples at t = 0 and k·every up to the session's time, replayed from its timeline outside
// the lock: the rows `spinfold simulate --every E` writes for the same scene, however the session
// was advanced (by plays, advances or a restore).
void get_trajectory(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto s = find_session(server, call.id);
  Scene scene;
  std::vector<ParameterChange> changes;
  double until = 0.0;
  std::uint64_t attempts = 0;
  std::string provenance_text;
  {
    const std::lock_guard lock(s->mutex);
    scene = s->scene;
    changes = s->changes;
    until = s->run.state.t;
    // What the session's own steps took, and room for the cut steps to each sample time.
    attempts = s->run.steps + s->run.rejected + static_cast<std::uint64_t>(server.options.limits.max_steps);
    provenance_text = provenance(*s);
  }
  const double every = *call.query.number("every");
  if (until / every > kMaxTrajectoryRows)
    throw bad(422, "Too many samples", "every", shortest(every),
              "gives more than " + shortest(kMaxTrajectoryRows) + " samples up to t = " + shortest(until) +
                  ": choose a larger interval");
  const double rows = std::floor(until / every) + 1.0;
  const std::size_t budget = server.options.limits.max_trajectory_bytes;
  const std::string fields = call.query.text("fields").value_or("");
  const bool json_rows = *call.query.text("format") == "json";
  const auto too_large = [&](const std::string& why) {
    return bad(422, "Answer too large", "every", shortest(every),
               why + "; an answer holds at most " + size_text(static_cast<double>(budget)) +
                   ": choose a larger interval or fewer fields");
  };
  // The answer is written row by row as the replay makes the samples: memory is the answer's text
  // and one sample, never every sample as JSON values (10⁴ rows of 5 bodies took 650 MB that way).
  std::optional<SampleTable> table;
  std::string text;
  double reported_until = -1.0;
  // One row's text appended; the first row's numbers are widened (row_widening) to foresee the rest.
  const auto append_row = [&](const ordered_json& sample) {
    if (!json_rows) {
      text += table->csv_row(sample);
      return;
    }
    if (text.size() > 1) text += ',';
    text += fields.empty() ? sample.dump() : table->json_row(sample).dump();
  };
  const auto widest_row = [&](const ordered_json& sample) {
    if (!json_rows)
      return static_cast<double>(table->csv_row(sample).size()) +
             row_widening(ordered_json(table->row(sample)));
    const ordered_json row = fields.empty() ? sample : table->json_row(sample);
    return static_cast<double>(row.dump().size() + 1) + row_widening(row);
  };
  const bool complete = replay_sampled(
      scene, changes, until, every,
      [&](const Simulation& run) {
        const ordered_json sample = sample_to_json(run, reported_until);
        reported_until = run.state.t;
        if (table) {
          append_row(sample);
          if (text.size() > budget)
            throw too_large("passed " + size_text(static_cast<double>(text.size())) +
                            " at t = " + shortest(run.state.t) + " of " + shortest(until));
          return;
        }
        // The first row: the columns, and the size the answer would reach, before the replay runs.
        table = make_sample_table(fields, sample);
        if (json_rows) {
          text = "[";
        } else {
          const std::string comment[] = {"spinfold trajectory " + version_line(),
                                         "provenance: " + provenance_json(scene, "").dump()};
          text = samples_csv({}, *table, comment);
        }
        append_row(sample);
        const double row_bytes = widest_row(sample);
        const double expected = static_cast<double>(text.size()) + (rows - 1.0) * row_bytes;
        if (expected > static_cast<double>(budget))
          throw too_large("gives " + shortest(rows) + " rows of up to " + size_text(row_bytes) +
                          " up to t = " + shortest(until) + ", about " + size_text(expected));
        text.reserve(static_cast<std::size_t>(expected) + 1);
      },
      attempts);
  if (!complete)
    throw ApiError{503,
                   "Trajectory unavailable",
                   {{"", "", "the replay of the timeline ran out of step attempts"}},
                   "1"};
  res.set_header("X-Spinfold-Provenance", provenance_text);
  if (json_rows) text += ']';
  res.body = std::move(text);
  res.set_header("Content-Type", json_rows ? "application/json" : "text/csv");
}

}  // namespace

std::vector<Route> session_routes(const Limits& limits) {
  const std::string sid = kSessions + "/{id}";
  const ordered_json scene_ref = {{"$ref", "#/components/schemas/Scene"}};
  const ordered_json preset_ref = {{"type", "object"},
                                   {"required", {"preset"}},
                                   {"properties", {{"preset", {{"type", "string"}}}}},
                                   {"additionalProperties", false}};
  return {
      {.method = "POST",
       .path = kSessions,
       .operation_id = "create_session",
       .handler = create_session,
       .summary = "Create a session from a scene, {\"preset\": name}, or a share link {\"scene\", "
                  "\"timeline\", \"until\"} (rebuilt from t = 0, bit for bit)",
       .body =
           RequestBody{
               .description = "a scene, {\"preset\": name} (GET /api/v1/scenes), or {\"scene\": a "
                              "scene or preset, \"timeline\": [{\"t\", \"patch\"}], \"until\": t}",
               .schema =
                   {{"oneOf",
                     {scene_ref,
                      preset_ref,
                      {{"type", "object"},
                       {"required", {"scene"}},
                       {"properties",
                        {{"scene", {{"oneOf", {scene_ref, preset_ref}}}},
                         {"timeline",
                          {{"type", "array"},
                           {"items",
                            {{"type", "object"},
                             {"required", {"t", "patch"}},
                             {"properties",
                              {{"t", {{"type", "number"}, {"minimum", 0}}}, {"patch", {{"type", "object"}}}}},
                             {"additionalProperties", false}}}}},
                         {"until",
                          {{"type", "number"}, {"minimum", 0}, {"maximum", limits.max_advance_time}}}}},
                       {"additionalProperties", false}}}}}},
       .responses = {{201,
                      "created: Location, the session {\"id\", \"state\", \"scene\", \"timeline\", "
                      "\"current\"} (and \"advance\" for a share link)"},
                     {422, "invalid scene, unknown preset"},
                     {429, "this client's session quota (limits.max_sessions_per_client); Retry-After"},
                     {503, "session limit; Retry-After"}}},
      {.method = "GET",
       .path = sid,
       .operation_id = "get_session",
       .handler = get_session,
       .summary = "The session: its state, scene (t = 0), timeline of changes and parameters in force",
       .responses = {{200,
                      "{\"id\", \"state\", \"scene\", \"timeline\", \"current\", \"surface\": "
                      "{\"kind\", \"radius\", \"curvature\"} (resolved)}"}}},
      {.method = "PATCH",
       .path = sid,
       .operation_id = "update_session",
       .handler = patch_session,
       .summary = "Merge-patch the parameters in force: the run continues from now (a timeline entry), or "
                  "restarts at t = 0 for \"initial\" or another surface kind; \"change\" says which",
       .body = RequestBody{.description = "a JSON merge patch (RFC 7396) of the scene",
                           .content_types = {"application/json", "application/merge-patch+json"},
                           .schema = {{"type", "object"}}},
       .responses = {{200, "the session and \"change\": {\"kind\", \"t\", \"reason\"}"},
                     {422, "invalid scene"}}},
      {.method = "DELETE",
       .path = sid,
       .operation_id = "delete_session",
       .handler = delete_session,
       .summary = "Delete the session",
       .responses = {{204, "deleted"}}},
      {.method = "POST",
       .path = sid + "/advance",
       .operation_id = "advance_session",
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
       .operation_id = "play_session",
       .handler = play_session,
       .summary = "Advance in real time at {\"rate\": r} simulated time per second",
       .body = RequestBody{.description = "optional: {\"rate\": r}, default 1",
                           .required = false,
                           .schema = {{"type", "object"},
                                      {"properties",
                                       {{"rate",
                                         {{"type", "number"},
                                          {"exclusiveMinimum", 0},
                                          {"maximum", limits.max_play_rate},
                                          {"default", 1}}}}},
                                      {"additionalProperties", false}}},
       .responses = {{200, "the session"}, {409, "the run has stopped"}}},
      {.method = "POST",
       .path = sid + "/pause",
       .operation_id = "pause_session",
       .handler = pause_session,
       .summary = "Stop real-time advancing",
       .responses = {{200, "the session"}}},
      {.method = "POST",
       .path = sid + "/reset",
       .operation_id = "reset_session",
       .handler = reset_session,
       .summary = "Back to t = 0 with the parameters in force (the timeline empties)",
       .responses = {{200, "the session"}}},
      {.method = "GET",
       .path = sid + "/trajectory",
       .operation_id = "get_trajectory",
       .handler = get_trajectory,
       .summary = "The run's samples at t = 0 and every `every` up to the session's time, replayed from "
                  "its timeline (the rows of `spinfold simulate --every`, however the session was advanced)",
       .query = {{.name = "format",
                  .type = ParamType::enumeration,
                  .values = {"json", "csv"},
                  .default_value = "json",
                  .description = "json: an array of samples (companions nested in each), or of rows of the "
                                 "chosen fields; csv: '# ' comment lines (version, provenance), the header, "
                                 "one row per sample (companions' columns named LABEL.column; null cells "
                                 "empty)"},
                 {.name = "every",
                  .type = ParamType::number,
                  .unit = "time",
                  .minimum = 0.0,
                  .maximum = 1e9,
                  .exclusive_minimum = true,
                  .default_value = 0.5,
                  .description = "the sample interval (at most 100000 samples, and an answer of at most "
                                 "limits.max_trajectory_bytes: " +
                                 size_text(static_cast<double>(limits.max_trajectory_bytes)) + ")"},
                 {.name = "fields",
                  .type = ParamType::list,
                  .values = sample_field_names(),
                  .description =
                      "the columns or groups of them (X for X.0, X.1, X.2; as `spinfold "
                      "simulate --fields`); absent: every column (csv) or the whole sample (json)"}},
       .responses = {{200, "application/json or text/csv"},
                     {422, "more than 100000 samples, or an answer over " +
                               size_text(static_cast<double>(limits.max_trajectory_bytes)) +
                               " (its size foreseen from the first row)"}}},
  };
}

}  // namespace spinfold::server
