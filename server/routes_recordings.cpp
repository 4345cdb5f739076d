// Recordings: POST a time window of a session → 202 and a job (server/recordings.h); GET its status
// and progress; GET its file; DELETE cancels or deletes it.
#include <fstream>

#include "engine/number_text.h"
#include "server/context.h"
#include "server/problem.h"
#include "server/recordings.h"
#include "server/route_table.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

using nlohmann::json;
using nlohmann::ordered_json;

namespace {

const std::string kRecordings = "/api/v1/recordings";
const std::vector<std::string> kFields = {"t_start", "t_end", "fps",    "speed",   "width",
                                          "height",  "view",  "layers", "format",  "trail",
                                          "scale",   "yaw",   "pitch",  "distance"};

// The body's fields, each checked (every refusal named at once), into a job on the session's copy.
RecordingJob recording_job(ServerContext& server, const Call& call, Session& s) {
  const json body = call.body();
  require_object(body);
  refuse_unknown_keys(body, kFields);
  const Limits& limits = server.options.limits;
  std::vector<FieldError> errors;
  const auto number = [&](const char* key, std::optional<double> fallback) -> std::optional<double> {
    if (!body.contains(key)) {
      if (!fallback) errors.push_back({key, "", "is required"});
      return fallback;
    }
    const json& v = body[key];
    if (!v.is_number() || !std::isfinite(v.get<double>())) {
      errors.push_back({key, v.dump(), "must be a finite number"});
      return fallback;
    }
    return v.get<double>();
  };
  const auto side = [&](const char* key, int fallback) {
    if (!body.contains(key)) return fallback;
    const json& v = body[key];
    if (!v.is_number_integer() || v.get<long long>() < 16 || v.get<long long>() > limits.max_image_side) {
      errors.push_back(
          {key, v.dump(),
           "must be a whole number from 16 to " + std::to_string(limits.max_image_side) + " [pixels]"});
      return fallback;
    }
    return static_cast<int>(v.get<long long>());
  };
  const auto text = [&](const char* key) -> std::optional<std::string> {
    if (!body.contains(key)) return std::nullopt;
    if (!body[key].is_string()) {
      errors.push_back({key, body[key].dump(), "must be a string"});
      return std::nullopt;
    }
    return body[key].get<std::string>();
  };

  RecordingJob job{.session = call.id, .client = call.client};
  job.clip.t_start = *number("t_start", 0.0);
  job.clip.t_end = number("t_end", std::nullopt).value_or(job.clip.t_start + 1.0);
  job.clip.fps = *number("fps", 30.0);
  job.clip.speed = *number("speed", 1.0);
  // Each refusal of a field the body gave; a clip refused only for its defaults (t_end is t_start + 1
  // unless given) is refused all the same, before any frame count becomes an integer.
  const std::vector<FieldError> clip_refusals = record::clip_errors(job.clip);
  bool clip_named = false;
  for (const FieldError& e : clip_refusals)
    if (body.contains(e.field)) {
      errors.push_back(e);
      clip_named = true;
    }
  if (!clip_named) errors.insert(errors.end(), clip_refusals.begin(), clip_refusals.end());
  const auto format = text("format");
  if (!format)
    errors.push_back({"format", body.contains("format") ? body["format"].dump() : "",
                      "is required: gif, webm, mp4 or png-zip"});
  else if (!record::parse_format(*format))
    errors.push_back({"format", *format, "must be gif, webm, mp4 or png-zip"});
  else
    job.format = *record::parse_format(*format);

  render::ViewOptions& view = job.frames.view;
  view.width = side("width", 640);
  view.height = side("height", 480);
  if (format && record::parse_format(*format))
    if (const auto why = record::size_unsupported_reason(job.format, view.width, view.height))
      errors.push_back({view.width % 2 ? "width" : "height",
                        std::to_string(view.width % 2 ? view.width : view.height), *why});
  const auto view_name = text("view");
  if (view_name && !render::parse_view(*view_name))
    errors.push_back({"view", *view_name, "must be one of " + render::joined_view_names(", ")});
  if (const auto layers = text("layers")) {
    std::string unknown;
    if (const auto mask = render::parse_layers(*layers, &unknown))
      view.layers = *mask;
    else
      errors.push_back(
          {"layers", *layers, "'" + unknown + "' is not one of surface, grid, body, frame, trail, hud"});
  }
  const double scale = *number("scale", 0.25);
  if (!(scale > 0.0 && scale <= 10.0))
    errors.push_back({"scale", shortest(scale), "must be a number in (0, 10]"});
  job.frames.trail_span = body.contains("trail") ? number("trail", 0.0) : std::nullopt;
  if (job.frames.trail_span && *job.frames.trail_span < 0.0)
    errors.push_back({"trail", shortest(*job.frames.trail_span), "must be >= 0 [time]"});
  job.frames.yaw = body.contains("yaw") ? number("yaw", 0.0) : std::nullopt;
  job.frames.pitch = body.contains("pitch") ? number("pitch", 0.0) : std::nullopt;
  job.frames.distance = body.contains("distance") ? number("distance", 3.4) : std::nullopt;
  if (job.frames.pitch && std::abs(*job.frames.pitch) > 1.55)
    errors.push_back({"pitch", shortest(*job.frames.pitch), "must be a number from -1.55 to 1.55 [rad]"});
  if (job.frames.distance && (*job.frames.distance < 1.2 || *job.frames.distance > 100.0))
    errors.push_back(
        {"distance", shortest(*job.frames.distance), "must be a number from 1.2 to 100 [radii]"});
  if (!errors.empty()) throw ApiError{422, "Invalid value", errors, ""};

  // The copy: the parameters at t = 0 and the timeline, under the session's lock only to read them.
  const std::lock_guard lock(s.mutex);
  view.kind = view_name ? *render::parse_view(*view_name) : render::default_view(s.run.scene.surface.kind);
  if (const auto why = render::view_unsupported_reason(view.kind, s.run.scene.surface.kind))
    throw bad(422, "Invalid value", "view", std::string(render::view_name(view.kind)), *why);
  view.scale = scale * render::body_scale_length(view.kind, s.run.scene.surface);
  job.frames.scene = s.scene;
  job.frames.changes = s.changes;
  job.frames.max_attempts = static_cast<std::uint64_t>(limits.max_steps);
  return job;
}

ordered_json recording_json(const RecordingState& r) {
  ordered_json out{{"id", r.id},
                   {"status", status_name(r.status)},
                   {"progress", r.progress},
                   {"url", kRecordings + "/" + r.id},
                   {"file", kRecordings + "/" + r.id + "/file"},
                   {"session", r.job.session},
                   {"format", record::format_name(r.job.format)},
                   {"frames", r.frames},
                   {"t_start", r.job.clip.t_start},
                   {"t_end", r.job.clip.t_end},
                   {"fps", r.job.clip.fps},
                   {"speed", r.job.clip.speed},
                   {"width", r.job.frames.view.width},
                   {"height", r.job.frames.view.height},
                   {"bytes", r.bytes}};
  if (r.status == RecordingStatus::failed) out["reason"] = r.reason;
  return out;
}

void create_recording(ServerContext& server, const Call& call, httplib::Response& res) {
  RecordingJob job = recording_job(server, call, *find_session(server, call.id));
  const std::string id = server.recordings.start(std::move(job));
  res.set_header("Location", kRecordings + "/" + id);
  send_json(res, recording_json(server.recordings.state(id)), 202);
}

void get_recording(ServerContext& server, const Call& call, httplib::Response& res) {
  res.set_header("Cache-Control", "no-store");
  send_json(res, recording_json(server.recordings.state(call.id)));
}

void get_recording_file(ServerContext& server, const Call& call, httplib::Response& res) {
  const std::filesystem::path path = server.recordings.file(call.id);
  const RecordingState r = server.recordings.state(call.id);
  auto file = std::make_shared<std::ifstream>(path, std::ios::binary);  // readable even if deleted meanwhile
  if (!*file) throw bad(404, "Unknown recording", "id", call.id, "the recording's file is gone");
  char name[160];
  std::snprintf(name, sizeof name, "spinfold-%s-t%s-%s.%s", r.job.session.substr(0, 8).c_str(),
                shortest(r.job.clip.t_start).c_str(), shortest(r.job.clip.t_end).c_str(),
                std::string(record::file_extension(r.job.format)).c_str());
  res.set_header("Content-Disposition", std::string("attachment; filename=\"") + name + "\"");
  res.set_header("Cache-Control", "no-store");
  res.set_content_provider(static_cast<std::size_t>(r.bytes), std::string(record::content_type(r.job.format)),
                           [file](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
                             char buffer[64 * 1024];
                             file->seekg(static_cast<std::streamoff>(offset));
                             file->read(buffer,
                                        static_cast<std::streamsize>(std::min(length, sizeof buffer)));
                             const auto got = file->gcount();
                             if (got <= 0) return false;
                             sink.write(buffer, static_cast<std::size_t>(got));
                             return true;
                           });
}

void delete_recording(ServerContext& server, const Call& call, httplib::Response& res) {
  if (server.recordings.cancel_or_delete(call.id)) {
    send_json(res, recording_json(server.recordings.state(call.id)));
    return;
  }
  res.status = 204;
}

}  // namespace

std::vector<Route> recording_routes(const Limits& limits) {
  const ordered_json number{{"type", "number"}};
  ordered_json view_names = ordered_json::array();
  for (const render::ViewInfo& v : render::views()) view_names.push_back(std::string(v.name));
  const ordered_json body_schema{
      {"type", "object"},
      {"required", {"t_end", "format"}},
      {"additionalProperties", false},
      {"properties",
       {{"t_start", {{"type", "number"}, {"minimum", 0}, {"default", 0}, {"x-unit", "time"}}},
        {"t_end",
         {{"type", "number"},
          {"x-unit", "time"},
          {"description", "end of the window (excluded), > t_start"}}},
        {"fps",
         {{"type", "number"}, {"minimum", record::kMinFps}, {"maximum", record::kMaxFps}, {"default", 30}}},
        {"speed",
         {{"type", "number"}, {"default", 1}, {"description", "simulated time per second of the file"}}},
        {"width",
         {{"type", "integer"}, {"minimum", 16}, {"maximum", limits.max_image_side}, {"default", 640}}},
        {"height",
         {{"type", "integer"}, {"minimum", 16}, {"maximum", limits.max_image_side}, {"default", 480}}},
        {"view", {{"type", "string"}, {"enum", view_names}}},
        {"layers", {{"type", "string"}, {"default", "surface,grid,body,frame,trail,hud"}}},
        {"format", {{"type", "string"}, {"enum", {"gif", "webm", "mp4", "png-zip"}}}},
        {"trail", {{"type", "number"}, {"minimum", 0}, {"x-unit", "time"}}},
        {"scale", number},
        {"yaw", number},
        {"pitch", number},
        {"distance", number}}}};
  return {
      {.method = "POST",
       .path = "/api/v1/sessions/{id}/recordings",
       .operation_id = "create_recording",
       .handler = create_recording,
       .summary = "Record a time window of the session (a copy of its timeline; the session is not "
                  "changed) as GIF, WebM, MP4 or a zip of PNGs: 202 and the recording",
       .body = RequestBody{.description = "the window, rate, picture and format", .schema = body_schema},
       .responses = {{202, "the recording, queued; Location"},
                     {422, "an invalid field, or over max_recording_frames / max_recording_pixels"},
                     {429, "over max_recordings_per_client, max_recordings or max_recording_disk_bytes"}}},
      {.method = "GET",
       .path = kRecordings + "/{id}",
       .operation_id = "get_recording",
       .handler = get_recording,
       .summary = "A recording's status (queued, running, done, failed with a reason, cancelled) and "
                  "progress 0…1",
       .responses = {{200, "the recording"}, {404, "unknown recording"}}},
      {.method = "GET",
       .path = kRecordings + "/{id}/file",
       .operation_id = "get_recording_file",
       .handler = get_recording_file,
       .summary = "The recorded file, with its content type and a download file name",
       .responses = {{200, "image/gif, video/webm, video/mp4 or application/zip"},
                     {404, "unknown recording"},
                     {409, "not done yet, or failed"}}},
      {.method = "DELETE",
       .path = kRecordings + "/{id}",
       .operation_id = "delete_recording",
       .handler = delete_recording,
       .summary = "Cancels a queued or running recording (200, status cancelled), or deletes a "
                  "finished one and its file (204)",
       .responses = {{200, "cancelled"}, {204, "deleted"}, {404, "unknown recording"}}}};
}

}  // namespace spinfold::server
