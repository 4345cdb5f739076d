// Work-precision: POST a scene (given, a preset, or a session's) → 202 and a job
// (server/jobs/work_precision_jobs.h); GET its status, progress and result; GET its plot (SVG, PNG) and
// CSV; DELETE cancels or deletes it.
#include "workprecision/work_precision.h"

#include <cmath>
#include <set>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "engine/integrator.h"
#include "engine/number_rule.h"
#include "server/context.h"
#include "server/http/problem.h"
#include "server/routes/routes.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

using nlohmann::json;
using nlohmann::ordered_json;

namespace {

namespace wp = work_precision;

const std::string kWorkPrecision = "/api/v1/work-precision";
const std::vector<std::string> kFields = {"scene",       "preset", "session",
                                          "integrators", "t_end",  "target_error"};
constexpr double kMinTargetError = 1e-15;  // the sweep's finest tolerance
constexpr double kMaxTargetError = 1.0;
constexpr double kDefaultTargetError = 1e-10;  // the CLI's

std::string integrator_names() {
  std::string names;
  for (const CatalogEntry& e : integrator_catalog()) names += std::string(e.info.name) + ", ";
  return names + std::string(kAutoIntegrator);
}

// The largest T for the scene: max_work_precision_periods of its period, never past
// max_work_precision_t_end.
double max_t_end(const Scene& scene, const Limits& limits) {
  const double period = wp::characteristic_period(scene);
  return std::isfinite(period)
             ? std::min(limits.max_work_precision_periods * period, limits.max_work_precision_t_end)
             : limits.max_work_precision_t_end;
}

// The body's fields, each checked (every refusal named at once), into a job.
WorkPrecisionJob work_precision_job(ServerContext& server, const Call& call) {
  const json body = call.body();
  require_object(body);
  refuse_unknown_keys(body, kFields);
  const Limits& limits = server.options.limits;
  WorkPrecisionJob job{.client = call.client};
  std::vector<FieldError> errors;

  // The scene: exactly one of scene, preset and session.
  int sources = 0;
  for (const char* key : {"scene", "preset", "session"}) sources += body.contains(key);
  std::optional<Scene> scene;
  if (sources != 1) {
    errors.push_back({"scene", "",
                      sources ? "give only one of scene, preset and session"
                              : "scene, preset or session is required (the scene to measure)"});
  } else if (body.contains("scene")) {
    try {
      scene = scene_of(body["scene"], "scene");
      job.source = "scene";
    } catch (const ApiError& e) {
      errors.insert(errors.end(), e.errors.begin(), e.errors.end());
    }
  } else if (body.contains("preset")) {
    const json& name = body["preset"];
    const PresetSource* preset = name.is_string() ? find_preset(name.get<std::string>()) : nullptr;
    if (!preset) {
      errors.push_back({"preset", name.dump(), "is not a preset (GET /api/v1/scenes)"});
    } else {
      scene = *parse_scene_text(preset->json).scene;
      job.source = "preset";
      job.source_name = preset->name;
    }
  } else {
    const json& id = body["session"];
    std::shared_ptr<Session> session;
    try {
      if (id.is_string()) session = find_session(server, id.get<std::string>());
    } catch (const ApiError&) {  // a field of the body: 422, not the 404 of a session's URL
    }
    if (!session) {
      errors.push_back({"session", id.dump(), "is not a session's id (POST /api/v1/sessions makes one)"});
    } else {
      // The parameters in force now (the last change of its timeline), from the scene's start.
      const std::lock_guard lock(session->mutex);
      scene = session->run.scene;
      job.source = "session";
    }
  }

  if (body.contains("integrators")) {
    const json& list = body["integrators"];
    if (!list.is_array() || list.empty()) {
      errors.push_back({"integrators", list.dump(), "must be a non-empty array of integrator names"});
    } else {
      std::set<std::string> seen;
      for (const json& item : list) {
        const std::string name = item.is_string() ? item.get<std::string>() : "";
        if (!item.is_string() || (name != kAutoIntegrator && !find_integrator(name)))
          errors.push_back({"integrators", item.dump(), "is not an integrator (" + integrator_names() + ")"});
        else if (!seen.insert(name).second)
          errors.push_back({"integrators", item.dump(), "is named twice"});
        else
          job.integrators.push_back(name);
      }
    }
  }

  job.target_error = kDefaultTargetError;
  if (body.contains("target_error")) {
    const json& v = body["target_error"];
    const double e = v.is_number() ? v.get<double>() : NAN;
    constexpr NumberRule kTargetError{.range = {.min = kMinTargetError, .max = kMaxTargetError}};
    if (const auto why = refusal(kTargetError, e))
      errors.push_back({"target_error", v.dump(), *why});
    else
      job.target_error = e;
  }

  if (scene) {
    const double most = max_t_end(*scene, limits);
    job.t_end = std::min(wp::default_t_end(*scene), most);
    if (body.contains("t_end")) {
      const json& v = body["t_end"];
      const double t = v.is_number() ? v.get<double>() : NAN;
      if (!(t > 0.0 && t <= most))
        errors.push_back({"t_end", v.dump(),
                          "must be a number > 0 and at most " + shortest(most) + " [time] for this scene (" +
                              shortest(limits.max_work_precision_periods) +
                              " characteristic periods, limits.max_work_precision_periods, and at most " +
                              shortest(limits.max_work_precision_t_end) +
                              ", limits.max_work_precision_t_end)"});
      else
        job.t_end = t, job.t_end_given = true;
    }
    job.scene = std::move(*scene);
  } else if (body.contains("t_end") && !(body["t_end"].is_number() && body["t_end"].get<double>() > 0.0)) {
    errors.push_back({"t_end", body["t_end"].dump(), "must be a number > 0 [time]"});
  }
  if (!errors.empty()) throw ApiError{422, "Invalid value", errors, ""};
  return job;
}

ordered_json number_or_null(double value) {
  return std::isfinite(value) ? ordered_json(value) : ordered_json(nullptr);
}

ordered_json point_json(const wp::Point& p) {
  return {{"method", p.method},
          {"parameter", p.parameter},
          {"value", p.parameter == "-" ? ordered_json(nullptr) : ordered_json(p.value)},
          {"seconds_per_unit_time", p.seconds_per_unit_time},
          {"state_error", number_or_null(p.state_error)},
          {"energy_error", number_or_null(p.energy_error)},
          {"position_error", number_or_null(p.position_error)},
          {"velocity_error", number_or_null(p.velocity_error)},
          {"frame_error", number_or_null(p.frame_error)},
          {"steps", p.steps}};
}

ordered_json job_json(const WorkPrecisionState& s) {
  const std::string url = kWorkPrecision + "/" + s.id;
  ordered_json out{{"id", s.id},
                   {"status", job_status_name(s.status)},
                   {"progress", s.progress},
                   {"methods_done", s.methods_done},
                   {"methods", s.methods},
                   {"url", url},
                   {"source", s.job.source},
                   {"source_name", s.job.source_name},
                   {"integrators", s.job.integrators},
                   {"t_end", s.job.t_end},
                   {"target_error", s.job.target_error}};
  // While running: computing the reference at T first, then sweeping the methods.
  if (s.status == JobStatus::running) out["stage"] = s.reference_ready ? "sweeping" : "reference";
  if (s.status == JobStatus::failed) out["reason"] = s.reason;
  if (s.status != JobStatus::done || !s.result) return out;
  const WorkPrecisionResult& r = *s.result;
  ordered_json points = ordered_json::array();
  for (const auto& [method, curve] : r.curves)
    for (const wp::Point& p : curve) points.push_back(point_json(p));
  ordered_json skipped = ordered_json::array();
  for (const auto& [method, why] : r.skipped) skipped.push_back({{"method", method}, {"reason", why}});
  ordered_json recommended = nullptr;
  if (r.recommended) {
    const wp::Point& p = *r.recommended;
    // What PATCH /api/v1/sessions/{id} takes to use it: {"integrator": this}.
    ordered_json integrator{{"name", p.method}};
    integrator[p.parameter == "dt" ? "dt" : "tolerance"] = p.value;
    recommended = point_json(p);
    recommended["integrator"] = integrator;
  }
  out["result"] = {{"t_end", r.t_end},
                   {"horizon", r.horizon_note.empty() ? ordered_json(nullptr) : ordered_json(r.horizon_note)},
                   {"reference", {{"kind", r.reference_kind}, {"description", r.reference_description}}},
                   {"error_meaning", wp::kErrorMeaning},
                   {"recommendation", r.recommendation},
                   {"recommended", recommended},
                   {"skipped", skipped},
                   {"points", points},
                   {"plot_svg", r.svg.empty() ? ordered_json(nullptr) : ordered_json(url + "/plot.svg")},
                   {"plot_png", r.png.empty() ? ordered_json(nullptr) : ordered_json(url + "/plot.png")},
                   {"data_csv", url + "/data.csv"}};
  if (!r.plot_trouble.empty()) out["result"]["plot_unavailable"] = r.plot_trouble;
  return out;
}

void create_work_precision(ServerContext& server, const Call& call, httplib::Response& res) {
  const std::string id = server.work_precision.start(work_precision_job(server, call));
  res.set_header("Location", kWorkPrecision + "/" + id);
  send_json(res, job_json(server.work_precision.state(id)), 202);
}

void get_work_precision(ServerContext& server, const Call& call, httplib::Response& res) {
  res.set_header("Cache-Control", "no-store");
  send_json(res, job_json(server.work_precision.state(call.id)));
}

// A file of the result, held in memory.
void send_result_file(httplib::Response& res, const std::string& body, const char* type,
                      const std::string& name) {
  res.set_header("Cache-Control", "private, max-age=3600");  // a done job's files never change
  res.set_header("Content-Disposition", "inline; filename=\"" + name + "\"");
  res.set_content(body, type);
}

void get_work_precision_svg(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto result = server.work_precision.result(call.id);
  if (result->svg.empty())
    throw bad(404, "No plot", "id", call.id, "no plot was drawn: " + result->plot_trouble);
  send_result_file(res, result->svg, "image/svg+xml", "work_precision.svg");
}

void get_work_precision_png(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto result = server.work_precision.result(call.id);
  if (result->png.empty())
    throw bad(404, "No plot", "id", call.id, "no plot was drawn: " + result->plot_trouble);
  send_result_file(res, result->png, "image/png", "work_precision.png");
}

void get_work_precision_csv(ServerContext& server, const Call& call, httplib::Response& res) {
  send_result_file(res, server.work_precision.result(call.id)->csv, "text/csv", "work_precision.csv");
}

void delete_work_precision(ServerContext& server, const Call& call, httplib::Response& res) {
  if (server.work_precision.cancel_or_delete(call.id)) {
    send_json(res, job_json(server.work_precision.state(call.id)));
    return;
  }
  res.status = 204;
}

}  // namespace

std::vector<Route> work_precision_routes(const Limits& limits) {
  ordered_json integrator_names = ordered_json::array();
  for (const CatalogEntry& e : integrator_catalog()) integrator_names.push_back(std::string(e.info.name));
  integrator_names.push_back(std::string(kAutoIntegrator));
  ordered_json preset_names = ordered_json::array();
  for (const PresetSource& p : preset_sources()) preset_names.push_back(std::string(p.name));
  const ordered_json preset_ref = {{"type", "object"},
                                   {"required", {"preset"}},
                                   {"properties", {{"preset", {{"type", "string"}}}}},
                                   {"additionalProperties", false}};
  const ordered_json body_schema{
      {"type", "object"},
      {"additionalProperties", false},
      {"description", "exactly one of scene, preset and session"},
      {"oneOf", {{{"required", {"scene"}}}, {{"required", {"preset"}}}, {{"required", {"session"}}}}},
      {"properties",
       {{"scene", {{"oneOf", {{{"$ref", "#/components/schemas/Scene"}}, preset_ref}}}},
        {"preset", {{"type", "string"}, {"enum", preset_names}}},
        {"session",
         {{"type", "string"},
          {"description", "a session's id: its parameters in force now, from its scene's start"}}},
        {"integrators",
         {{"type", "array"},
          {"minItems", 1},
          {"uniqueItems", true},
          {"items", {{"type", "string"}, {"enum", integrator_names}}},
          {"description", "default: every integrator of the catalog, and auto at the scene's tolerance"}}},
        {"t_end",
         {{"type", "number"},
          {"exclusiveMinimum", 0},
          {"maximum", limits.max_work_precision_t_end},
          {"x-unit", "time"},
          {"description",
           "the horizon T; at most " + shortest(limits.max_work_precision_periods) +
               " characteristic periods of the scene (default: that many, within the maximum)"}}},
        {"target_error",
         {{"type", "number"},
          {"minimum", kMinTargetError},
          {"maximum", kMaxTargetError},
          {"default", kDefaultTargetError},
          {"description", "the state error at T the recommendation is for"}}}}}};
  const std::string job = kWorkPrecision + "/{id}";
  return {
      {.method = "POST",
       .path = kWorkPrecision,
       .operation_id = "create_work_precision",
       .handler = create_work_precision,
       .summary = "Measure run time against error for each integrator on a scene (given, a preset, or a "
                  "session's) as a background job: 202 and the job",
       .body = RequestBody{.description = "the scene, the integrators, T and the target error",
                           .schema = body_schema},
       .responses = {{202, "the job, queued; Location"},
                     {422,
                      "an invalid field: an unknown preset, session or integrator, T or the target error "
                      "out of range"},
                     {429,
                      "over max_work_precision_jobs_per_client or max_work_precision_jobs; Retry-After"}}},
      {.method = "GET",
       .path = job,
       .operation_id = "get_work_precision",
       .handler = get_work_precision,
       .summary = "A work-precision job's status (queued, running, done, failed with a reason, "
                  "cancelled), progress 0…1 (methods done / methods) and, when done, its result: the "
                  "points, the reference, the recommendation and the links to the plot and the CSV",
       .responses = {{200, "the job"}}},
      {.method = "GET",
       .path = job + "/plot.svg",
       .operation_id = "get_work_precision_plot_svg",
       .handler = get_work_precision_svg,
       .summary = "The work-precision plot (cairo) as SVG",
       .responses = {{200, "image/svg+xml"}, {409, "not done yet, or failed"}}},
      {.method = "GET",
       .path = job + "/plot.png",
       .operation_id = "get_work_precision_plot_png",
       .handler = get_work_precision_png,
       .summary = "The work-precision plot (cairo) as PNG",
       .responses = {{200, "image/png"}, {409, "not done yet, or failed"}}},
      {.method = "GET",
       .path = job + "/data.csv",
       .operation_id = "get_work_precision_data",
       .handler = get_work_precision_csv,
       .summary = "The work-precision points as CSV, with provenance comments",
       .responses = {{200, "text/csv"}, {409, "not done yet, or failed"}}},
      {.method = "DELETE",
       .path = job,
       .operation_id = "delete_work_precision",
       .handler = delete_work_precision,
       .summary = "Cancels a queued or running job (200, status cancelled; a running one stops before its "
                  "next run), or deletes a finished one (204)",
       .responses = {{200, "cancelled"}, {204, "deleted"}}}};
}

}  // namespace spinfold::server
