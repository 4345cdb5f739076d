#include "server/api.h"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <thread>
#include <variant>

#include "codec/presets.h"
#include "codec/sample_json.h"
#include "codec/scene_json.h"
#include "codec/scene_schema.h"
#include "engine/integrator.h"
#include "engine/paper_coordinates.h"
#include "render/snapshot.h"
#include "render/view.h"
#include "server/frame_cache.h"
#include "server/openapi.h"
#include "server/render_worker.h"
#include "server/web_assets.h"
#include "server/sessions.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

#ifndef SPINFOLD_VERSION
#define SPINFOLD_VERSION "0.0.0"
#endif

namespace spinfold::server {

namespace {

using nlohmann::json;
using nlohmann::ordered_json;

// An error a handler reports: mapped to application/problem+json in one place (send_error).
struct ApiError {
  int status;
  std::string title;
  std::vector<FieldError> errors;
  std::string retry_after;  // seconds, for 429/503
};

ApiError bad(int status, const std::string& title, const std::string& field, const std::string& value,
             const std::string& reason) {
  return {status, title, {{field, value, reason}}, ""};
}

void send_error(httplib::Response& res, const ApiError& e) {
  ordered_json body{{"type", "about:blank"}, {"title", e.title}, {"status", e.status}};
  std::string detail;
  json errors = json::array();
  for (const FieldError& f : e.errors) {
    errors.push_back({{"field", f.field}, {"value", f.value}, {"reason", f.reason}});
    detail += (detail.empty() ? "" : "; ") + (f.field.empty() ? std::string() : f.field + ": ") + f.reason;
  }
  body["detail"] = detail;
  body["errors"] = errors;
  res.status = e.status;
  if (!e.retry_after.empty()) res.set_header("Retry-After", e.retry_after);
  // The values quoted back may hold bytes that are not UTF-8 (a malformed body, a header): they
  // are replaced (U+FFFD) rather than failing the answer.
  res.body = body.dump(-1, ' ', false, json::error_handler_t::replace);
  res.set_header("Content-Type", "application/problem+json");
}

void send_json(httplib::Response& res, const ordered_json& body, int status = 200) {
  res.status = status;
  res.body = body.dump();
  res.set_header("Content-Type", "application/json");
}

std::string provenance(const Session& s) {
  return std::string("version=") + SPINFOLD_VERSION + "; integrator=" + std::string(s.run.info->name) +
         "; tolerance=" + std::to_string(s.scene.integrator.tolerance);
}

// The JSON body of a request: Content-Type application/json, well-formed, nested at most 32 deep.
json parse_body(const httplib::Request& req) {
  const std::string type = req.get_header_value("Content-Type");
  if (type.rfind("application/json", 0) != 0)
    throw bad(415, "Unsupported media type", "Content-Type", type, "must be application/json");
  try {
    const json::parser_callback_t guard = [](int depth, json::parse_event_t, json&) {
      if (depth > kMaxJsonDepth) throw std::length_error("nesting");
      return true;
    };
    return json::parse(req.body, guard);
  } catch (const std::length_error&) {
    throw bad(400, "Malformed request", "", "",
              "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  } catch (const json::exception& e) {
    throw bad(400, "Malformed request", "", "", std::string("malformed JSON: ") + e.what());
  }
}

double number_field(const json& body, const char* key) {
  const auto it = body.find(key);
  if (!it->is_number()) throw bad(422, "Invalid value", key, it->dump(), "must be a number");
  const double v = it->get<double>();
  if (!std::isfinite(v)) throw bad(422, "Invalid value", key, it->dump(), "must be finite");
  return v;
}

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

ordered_json session_json(const std::string& id, const Session& s) {
  ordered_json j;
  j["id"] = id;
  j["state"] = sample_to_json(s.run, {});
  j["scene"] = scene_to_json(s.scene);
  j["start_time"] = s.run.start_time;  // when the scene's initial state holds (after a PATCH: > 0)
  return j;
}

}  // namespace

// Releases an event-stream slot when the last copy of its stream's provider is gone.
struct StreamSlot {
  std::atomic<int>& open;
  explicit StreamSlot(std::atomic<int>& counter) : open(counter) {}
  ~StreamSlot() { --open; }
};

struct ApiServer::State {
  ServerOptions options;
  httplib::Server http;
  SessionStore sessions;
  RenderWorker renderer;
  FrameCache frames{64};
  std::atomic<int> open_streams{0};
  std::atomic<bool> stopping{false};
  std::thread player;

  explicit State(ServerOptions o)
      : options(std::move(o)), sessions(options.limits.max_sessions, options.limits.idle_expiry) {
    player = std::thread([this] { play_loop(); });
  }
  ~State() {
    stopping = true;
    player.join();
  }

  // Advances playing sessions in real time, 50 times a second.
  void play_loop() {
    auto last = std::chrono::steady_clock::now();
    while (!stopping) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      const auto now = std::chrono::steady_clock::now();
      const double wall = std::chrono::duration<double>(now - last).count();
      last = now;
      for (const auto& s : sessions.all()) {
        const std::lock_guard lock(s->mutex);
        if (!s->playing) continue;
        // A stiff scene falls behind real time rather than holding the player from the others.
        advance_to(s->run, s->run.state.t + s->rate * wall, options.limits.max_play_steps);
        record_sample(*s);
        if (s->run.state.status != Status::ok) s->playing = false;
      }
    }
  }

  std::shared_ptr<Session> session(const std::string& id) {
    auto s = sessions.find(id);
    if (!s) throw bad(404, "Unknown session", "id", id, "no session with this id (it may have expired)");
    return s;
  }

  // Runs a handler, mapping ApiError to problem+json; every response carries the version.
  template <typename Handler>
  httplib::Server::Handler wrap(Handler handler) {
    return [handler](const httplib::Request& req, httplib::Response& res) {
      res.set_header("X-Spinfold-Version", SPINFOLD_VERSION);
      try {
        handler(req, res);
      } catch (const ApiError& e) {
        send_error(res, e);
      }
    };
  }

  void routes();
};

void ApiServer::State::routes() {
  const std::string api = "/api/v1";
  const std::string sid = "/sessions/([0-9a-f]{1,32})";

  http.Get(api + "/health", wrap([this](const httplib::Request&, httplib::Response& res) {
             send_json(res, {{"status", "ok"}, {"version", SPINFOLD_VERSION}, {"sessions", sessions.size()}});
           }));

  http.Get(api + "/scenes", wrap([](const httplib::Request&, httplib::Response& res) {
             ordered_json list = ordered_json::array();
             for (const PresetSource& p : preset_sources()) {
               const SceneParse parsed = parse_scene_text(p.json);
               list.push_back({{"name", std::string(p.name)},
                               {"description", parsed.scene ? parsed.scene->description : ""},
                               {"scene", json::parse(p.json)}});
             }
             send_json(res, list);
           }));

  http.Get(api + "/integrators", wrap([](const httplib::Request&, httplib::Response& res) {
             ordered_json list = ordered_json::array();
             for (const CatalogEntry& e : integrator_catalog())
               list.push_back({{"name", std::string(e.info.name)},
                               {"order", e.info.order},
                               {"symplectic", e.info.symplectic},
                               {"adaptive", e.info.adaptive},
                               {"exact", e.info.exact},
                               {"summary", std::string(e.info.summary)}});
             send_json(res, list);
           }));

  http.Get(api + "/schema",
           wrap([](const httplib::Request&, httplib::Response& res) { send_json(res, scene_schema()); }));
  http.Get(api + "/openapi.json",
           wrap([](const httplib::Request&, httplib::Response& res) { send_json(res, openapi_document()); }));

  http.Post(api + "/sessions", wrap([this, api](const httplib::Request& req, httplib::Response& res) {
              json body = parse_body(req);
              SceneParse parsed;
              if (body.is_object() && body.size() == 1 && body.contains("preset")) {
                const json& name = body["preset"];
                const PresetSource* p = name.is_string() ? find_preset(name.get<std::string>()) : nullptr;
                if (!p)
                  throw bad(422, "Unknown preset", "preset", name.dump(),
                            "is not a preset (GET /api/v1/scenes)");
                parsed = parse_scene_text(p->json);
              } else {
                parsed = parse_scene(body);
              }
              if (!parsed.scene) throw ApiError{422, "Invalid scene", parsed.errors, ""};
              // ?start_time=t0: the scene's initial state holds at t0 (a shared PATCHed session).
              double start_time = 0.0;
              if (req.has_param("start_time")) {
                const std::string v = req.get_param_value("start_time");
                char* end = nullptr;
                start_time = std::strtod(v.c_str(), &end);
                if (v.empty() || *end || !std::isfinite(start_time) || start_time < 0.0)
                  throw bad(422, "Invalid value", "start_time", v, "must be a finite number >= 0");
              }
              std::string id;
              const auto session = sessions.create(*parsed.scene, id, start_time);
              if (!session)
                throw ApiError{
                    503, "Too many sessions", {{"", "", "the session limit is reached; retry later"}}, "30"};
              const std::lock_guard lock(session->mutex);
              res.set_header("Location", api + "/sessions/" + id);
              res.set_header("X-Spinfold-Provenance", provenance(*session));
              send_json(res, session_json(id, *session), 201);
            }));

  // The state's JSON is built once per change of state and then served as it is.
  http.Get(api + sid, wrap([this](const httplib::Request& req, httplib::Response& res) {
             const auto s = session(req.matches[1]);
             const std::lock_guard lock(s->mutex);
             if (s->body_version != s->version) {
               s->body = session_json(req.matches[1], *s).dump();
               s->body_version = s->version;
             }
             res.set_header("X-Spinfold-Provenance", provenance(*s));
             res.body = s->body;
             res.set_header("Content-Type", "application/json");
           }));

  http.Delete(api + sid, wrap([this](const httplib::Request& req, httplib::Response& res) {
                if (!sessions.erase(req.matches[1]))
                  throw bad(404, "Unknown session", "id", req.matches[1], "no session with this id");
                res.status = 204;
              }));

  // PATCH: a JSON merge patch of the scene. Without "initial" the run continues from its current
  // state (and time) under the new parameters; with it, that state is set.
  http.Patch(api + sid, wrap([this](const httplib::Request& req, httplib::Response& res) {
               const auto s = session(req.matches[1]);
               const json patch = parse_body(req);
               if (!patch.is_object())
                 throw bad(400, "Malformed request", "", patch.dump(), "the body must be a JSON object");
               const std::lock_guard lock(s->mutex);
               json document = scene_to_json(s->scene);
               if (!patch.contains("initial")) {
                 // A patch that changes nothing leaves the run as it is (no restart from the
                 // paper coordinates, which would cost bits and the integrator's step size).
                 json unchanged = document;
                 unchanged.merge_patch(patch);
                 const SceneParse same = parse_scene(unchanged);
                 if (same.scene && scene_to_json(*same.scene) == document) {
                   res.set_header("X-Spinfold-Provenance", provenance(*s));
                   send_json(res, session_json(req.matches[1], *s));
                   return;
                 }
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
               res.set_header("X-Spinfold-Provenance", provenance(*s));
               send_json(res, session_json(req.matches[1], *s));
             }));

  http.Post(
      api + sid + "/advance", wrap([this](const httplib::Request& req, httplib::Response& res) {
        const auto s = session(req.matches[1]);
        const json body = parse_body(req);
        if (!body.is_object())
          throw bad(400, "Malformed request", "", body.dump(), "the body must be a JSON object");
        for (const auto& [key, value] : body.items())
          if (key != "until" && key != "steps")
            throw bad(422, "Invalid value", key, value.dump(), "is not a known field (until, steps)");
        if (body.contains("until") == body.contains("steps"))
          throw bad(422, "Invalid value", "until", body.dump(), "give exactly one of until or steps");
        const Limits& limits = options.limits;
        const std::lock_guard lock(s->mutex);
        double target = 0.0;
        if (body.contains("until")) {
          target = number_field(body, "until");
          if (target < s->run.state.t)
            throw bad(422, "Invalid value", "until", body["until"].dump(), "is before the session's time");
        } else {
          const double steps = number_field(body, "steps");
          if (steps < 1 || steps != std::floor(steps))
            throw bad(422, "Invalid value", "steps", body["steps"].dump(), "must be a whole number >= 1");
          if (steps > static_cast<double>(limits.max_steps))
            throw bad(422, "Over a limit", "steps", body["steps"].dump(),
                      "exceeds the limit of " + std::to_string(limits.max_steps) + " steps per request");
          target = s->run.state.t + steps * s->scene.integrator.dt;
        }
        if (target - s->run.state.t > limits.max_advance_time)
          throw bad(
              422, "Over a limit", "until", std::to_string(target),
              "advances more than " + std::to_string(limits.max_advance_time) + " time units in one request");
        if (!s->run.info->adaptive && !s->run.info->exact &&
            (target - s->run.state.t) / s->scene.integrator.dt > static_cast<double>(limits.max_steps))
          throw bad(422, "Over a limit", "until", std::to_string(target),
                    "needs more than " + std::to_string(limits.max_steps) + " fixed steps in one request");
        // An adaptive method may need any number of steps: the work is bounded, the progress kept.
        const bool complete = advance_to(s->run, target, static_cast<std::uint64_t>(limits.max_steps));
        record_sample(*s);
        res.set_header("X-Spinfold-Provenance", provenance(*s));
        ordered_json out = session_json(req.matches[1], *s);
        out["advance"] = {{"until", target}, {"complete", complete}};
        if (!complete)
          out["advance"]["reason"] = "stopped after " + std::to_string(limits.max_steps) +
                                     " step attempts, the limit per request, at t = " +
                                     std::to_string(s->run.state.t) + ": advance again to continue";
        send_json(res, out);
      }));

  http.Post(api + sid + "/play", wrap([this](const httplib::Request& req, httplib::Response& res) {
              const auto s = session(req.matches[1]);
              double rate = 1.0;
              if (!req.body.empty()) {
                const json body = parse_body(req);
                if (!body.is_object())
                  throw bad(400, "Malformed request", "", body.dump(), "the body must be a JSON object");
                for (const auto& [key, value] : body.items())
                  if (key != "rate")
                    throw bad(422, "Invalid value", key, value.dump(), "is not a known field (rate)");
                if (body.contains("rate")) {
                  rate = number_field(body, "rate");
                  if (!(rate > 0.0) || rate > options.limits.max_play_rate)
                    throw bad(422, "Invalid value", "rate", body["rate"].dump(),
                              "must be > 0 and <= " + std::to_string(options.limits.max_play_rate));
                }
              }
              const std::lock_guard lock(s->mutex);
              if (s->run.state.status != Status::ok)
                throw bad(409, "Conflict", "status", std::string(status_name(s->run.state.status)),
                          "the run has stopped; reset or PATCH it first");
              s->playing = true;
              s->rate = rate;
              send_json(res, session_json(req.matches[1], *s));
            }));

  http.Post(api + sid + "/pause", wrap([this](const httplib::Request& req, httplib::Response& res) {
              const auto s = session(req.matches[1]);
              const std::lock_guard lock(s->mutex);
              s->playing = false;
              send_json(res, session_json(req.matches[1], *s));
            }));

  // Server-Sent Events: the state whenever it changed, checked `rate` times a second.
  http.Get(api + sid + "/events", wrap([this](const httplib::Request& req, httplib::Response& res) {
             const std::string id = req.matches[1];
             session(id);
             double hz = 10.0;
             if (req.has_param("rate")) {
               char* end = nullptr;
               const std::string v = req.get_param_value("rate");
               hz = std::strtod(v.c_str(), &end);
               if (v.empty() || *end || !(hz >= 0.5 && hz <= 60.0))
                 throw bad(422, "Invalid value", "rate", v, "must be between 0.5 and 60 events per second");
             }
             if (++open_streams > options.limits.max_streams) {
               --open_streams;
               throw ApiError{429, "Too many streams", {{"", "", "the event-stream limit is reached"}}, "10"};
             }
             auto slot = std::make_shared<StreamSlot>(open_streams);
             const auto interval = std::chrono::duration<double>(1.0 / hz);
             std::uint64_t sent = ~std::uint64_t{0};
             res.set_header("Cache-Control", "no-cache");
             res.set_chunked_content_provider(
                 "text/event-stream",
                 [this, id, interval, slot, sent](std::size_t, httplib::DataSink& sink) mutable {
                   if (stopping) return false;
                   const auto s = sessions.find(id);
                   if (!s) {
                     sink.done();  // the session is gone: end the stream
                     return true;
                   }
                   std::string event = ":\n\n";  // a comment keeps the connection checked
                   {
                     const std::lock_guard lock(s->mutex);
                     if (s->version != sent) {
                       event = "event: state\ndata: " + sample_to_json(s->run, {}).dump() + "\n\n";
                       sent = s->version;
                     }
                   }
                   if (!sink.write(event.data(), event.size())) return false;  // the client left
                   std::this_thread::sleep_for(interval);
                   return true;
                 });
           }));

  http.Post(api + sid + "/reset", wrap([this](const httplib::Request& req, httplib::Response& res) {
              const auto s = session(req.matches[1]);
              const std::lock_guard lock(s->mutex);
              // Back to where the scene's initial state holds: its start time (after a PATCH, the
              // moment of the patch), not t = 0 with a later state.
              s->run = start_simulation(s->scene, s->run.start_time);
              s->trajectory.clear();
              s->trail.clear();
              s->reported_events = 0;
              record_sample(*s);
              send_json(res, session_json(req.matches[1], *s));
            }));

  http.Get(api + sid + "/trajectory", wrap([this](const httplib::Request& req, httplib::Response& res) {
             const auto s = session(req.matches[1]);
             const std::string format = req.has_param("format") ? req.get_param_value("format") : "json";
             if (format != "json" && format != "csv")
               throw bad(422, "Invalid value", "format", format, "must be json or csv");
             const std::lock_guard lock(s->mutex);
             if (format == "json") {
               send_json(res, ordered_json(s->trajectory));
               return;
             }
             std::ostringstream csv;
             csv.precision(17);
             csv << "t,r,phi,lambda,mu,det_L,energy,energy_error,X0,X1,X2,status\n";
             const auto cell = [](const ordered_json& v) { return v.is_null() ? std::string() : v.dump(); };
             for (const ordered_json& row : s->trajectory)
               csv << cell(row["t"]) << "," << cell(row["r"]) << "," << cell(row["phi"]) << ","
                   << cell(row["lambda"]) << "," << cell(row["mu"]) << "," << cell(row["det_L"]) << ","
                   << cell(row["energy"]) << "," << cell(row["energy_error"]) << "," << cell(row["X"][0])
                   << "," << cell(row["X"][1]) << "," << cell(row["X"][2]) << ","
                   << row["status"].get<std::string>() << "\n";
             res.body = csv.str();
             res.set_header("Content-Type", "text/csv");
           }));

  http.Get(api + sid + "/frame.png", wrap([this](const httplib::Request& req, httplib::Response& res) {
             const auto s = session(req.matches[1]);
             render::ViewOptions view;
             {
               const std::lock_guard lock(s->mutex);
               view.kind = render::default_view(s->scene.surface.kind);
             }
             const auto param = [&](const char* key) {
               return req.has_param(key) ? std::optional<std::string>(req.get_param_value(key))
                                         : std::nullopt;
             };
             const auto integer = [&](const char* key, int& out) {
               if (const auto v = param(key)) {
                 char* end = nullptr;
                 const long n = std::strtol(v->c_str(), &end, 10);
                 if (v->empty() || *end || n < 16 || n > options.limits.max_image_side)
                   throw bad(422, "Invalid value", key, *v,
                             "must be a whole number of pixels from 16 to " +
                                 std::to_string(options.limits.max_image_side));
                 out = static_cast<int>(n);
               }
             };
             integer("width", view.width);
             integer("height", view.height);
             if (const auto v = param("view")) {
               const auto kind = render::parse_view(*v);
               if (!kind)
                 throw bad(422, "Invalid value", "view", *v, "must be sphere, hyperboloid, disk or plane");
               view.kind = *kind;
             }
             if (const auto v = param("layers")) {
               std::string unknown;
               const auto mask = render::parse_layers(*v, &unknown);
               if (!mask) throw bad(422, "Invalid value", "layers", *v, "unknown layer '" + unknown + "'");
               view.layers = *mask;
             }
             // Camera (3-D views): yaw and pitch [rad], distance [radii]; absent: aimed at the body.
             std::optional<double> yaw, pitch, distance;
             const auto real = [&](const char* key, double lo, double hi, std::optional<double>& out) {
               if (const auto v = param(key)) {
                 char* end = nullptr;
                 const double x = std::strtod(v->c_str(), &end);
                 if (v->empty() || *end || !std::isfinite(x) || x < lo || x > hi)
                   throw bad(422, "Invalid value", key, *v,
                             "must be a number from " + std::to_string(lo) + " to " + std::to_string(hi));
                 out = x;
               }
             };
             real("yaw", -100.0, 100.0, yaw);
             real("pitch", -1.55, 1.55, pitch);
             real("distance", 1.2, 100.0, distance);
             double scale = 0.25;
             if (const auto v = param("scale")) {
               char* end = nullptr;
               scale = std::strtod(v->c_str(), &end);
               if (v->empty() || *end || !std::isfinite(scale) || !(scale > 0.0) || scale > 10.0)
                 throw bad(422, "Invalid value", "scale", *v, "must be a number in (0, 10]");
             }
             // The ETag names the state and every parameter of the picture: a match renders nothing.
             const auto camera = [](const std::optional<double>& v) {
               char text[32] = "auto";  // aimed at the body
               if (v) std::snprintf(text, sizeof text, "%.17g", *v);
               return std::string(text);
             };
             const auto etag_of = [&](std::uint64_t version) {
               char text[256];
               std::snprintf(text, sizeof text, "\"%s-%llu-%d-%dx%d-%u-%.17g-%s-%s-%s\"",
                             req.matches[1].str().c_str(), static_cast<unsigned long long>(version),
                             static_cast<int>(view.kind), view.width, view.height, view.layers, scale,
                             camera(yaw).c_str(), camera(pitch).c_str(), camera(distance).c_str());
               return std::string(text);
             };
             std::string etag;
             Png png;
             std::optional<render::Snapshot> snapshot;
             {
               const std::lock_guard lock(s->mutex);
               if (const auto why = render::view_unsupported_reason(view.kind, s->scene.surface.kind))
                 throw bad(422, "Invalid value", "view", std::string(render::view_name(view.kind)), *why);
               etag = etag_of(s->version);
               png = frames.find(etag);
               if (!png && req.get_header_value("If-None-Match") != etag) {
                 view.scale = scale * s->scene.surface.radius;
                 std::vector<Vec3> trail;
                 if (view.layers & render::kTrail) trail = s->trail;  // copied only when drawn
                 snapshot = render::make_snapshot(s->run, std::move(trail));
               }
             }
             res.set_header("ETag", etag);
             res.set_header("Cache-Control", "no-cache");
             {
               const std::lock_guard lock(s->mutex);
               res.set_header("X-Spinfold-Provenance", provenance(*s));
             }
             if (req.get_header_value("If-None-Match") == etag) {
               res.status = 304;
               return;
             }
             if (!png) {
               render::aim_camera_at_body(view, *snapshot);
               if (yaw) view.yaw = *yaw;
               if (pitch) view.pitch = *pitch;
               if (distance) view.distance = *distance;
               try {
                 png = std::make_shared<const std::vector<std::uint8_t>>(
                     renderer.render(std::move(*snapshot), view).get());
               } catch (const std::exception& e) {
                 throw ApiError{503, "Rendering unavailable", {{"", "", e.what()}}, "5"};
               }
               frames.insert(etag, png);
             }
             res.body.assign(png->begin(), png->end());
             res.set_header("Content-Type", "image/png");
           }));

  // The browser UI, embedded.
  http.Get("(/|/app\\.js|/style\\.css|/vendor/uPlot\\.esm\\.js|/vendor/uPlot\\.min\\.css)",
           wrap([](const httplib::Request& req, httplib::Response& res) {
             const WebAsset* asset = web_asset(req.matches[1].str());
             if (!asset) throw bad(404, "Not found", "path", req.path, "no such file");
             res.body.assign(asset->body.begin(), asset->body.end());
             res.set_header("Content-Type", std::string(asset->content_type));
           }));

  // A known path asked with a method it does not have: 405 with Allow, not the router's 404.
  const auto only = [this](const std::string& pattern, const std::string& allowed) {
    const auto refuse = wrap([allowed](const httplib::Request& req, httplib::Response& res) {
      res.set_header("Allow", allowed);
      throw bad(405, "Method not allowed", "method", req.method, "allowed: " + allowed);
    });
    if (allowed.find("GET") == std::string::npos) http.Get(pattern, refuse);
    if (allowed.find("POST") == std::string::npos) http.Post(pattern, refuse);
    if (allowed.find("PATCH") == std::string::npos) http.Patch(pattern, refuse);
    if (allowed.find("DELETE") == std::string::npos) http.Delete(pattern, refuse);
    http.Put(pattern, refuse);
  };
  for (const char* path : {"/health", "/scenes", "/integrators", "/schema", "/openapi.json"})
    only(api + path, "GET");
  only(api + "/sessions", "POST");
  only(api + sid, "GET, PATCH, DELETE");
  for (const char* action : {"/advance", "/play", "/pause", "/reset"}) only(api + sid + action, "POST");
  for (const char* view : {"/events", "/trajectory", "/frame.png"}) only(api + sid + view, "GET");

  http.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (!res.body.empty()) return;
    const int status = res.status;
    send_error(res, {status,
                     status == 413   ? "Payload too large"
                     : status == 404 ? "Not found"
                                     : "Error",
                     {{"", "",
                       status == 413   ? "the request body exceeds the server's limit"
                       : status == 404 ? "no such resource"
                                       : "request failed"}},
                     ""});
  });
}

ApiServer::ApiServer(ServerOptions options) : state_(std::make_unique<State>(std::move(options))) {
  auto& http = state_->http;
  http.set_tcp_nodelay(true);  // without it every small response waits ~40 ms (platform-notes.md)
  http.set_payload_max_length(state_->options.limits.max_body_bytes);
  const int threads = state_->options.threads;
  http.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  state_->routes();
}

ApiServer::~ApiServer() {
  stop();
}

int ApiServer::bind() {
  const ServerOptions& o = state_->options;
  if (o.port == 0) return state_->http.bind_to_any_port(o.host);
  return state_->http.bind_to_port(o.host, o.port) ? o.port : -1;
}

bool ApiServer::listen() {
  return state_->http.listen_after_bind();
}

std::string ApiServer::create_session(const Scene& scene) {
  std::string id;
  return state_->sessions.create(scene, id) ? id : std::string();
}

void ApiServer::stop() {
  if (!state_) return;
  state_->stopping = true;  // ends the event streams, which would hold the pool open
  state_->http.stop();
}

}  // namespace spinfold::server
