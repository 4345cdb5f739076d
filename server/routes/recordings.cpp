// Recordings: POST a time window of a session → 202 and a job (server/jobs/recordings.h); GET its status
// and progress; GET its file; DELETE cancels or deletes it.
#include "server/jobs/recordings.h"

#include "engine/number_text.h"
#include "render/view_parameters.h"
#include "server/context.h"
#include "server/frames/frames.h"
#include "server/http/byte_ranges.h"
#include "server/http/problem.h"
#include "server/routes/routes.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

using nlohmann::json;
using nlohmann::ordered_json;

namespace {

const std::string kRecordings = "/api/v1/recordings";
// The body's fields: the clip's, then one per view parameter (render/view_parameters.h).
const std::vector<std::string> kClipFields = {"t_start", "t_end", "fps", "speed", "format"};
std::vector<std::string> body_fields() {
  std::vector<std::string> fields = kClipFields;
  for (const render::ViewParameter& p : render::view_parameters()) fields.emplace_back(p.name);
  return fields;
}

// The body's fields, each checked (every refusal named at once), into a job on the session's copy.
RecordingJob recording_job(ServerContext& server, const Call& call, Session& s) {
  const json body = call.body();
  require_object(body);
  refuse_unknown_keys(body, body_fields());
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
  const std::string formats = record::joined_format_names(", ", " or ");
  if (!format)
    errors.push_back(
        {"format", body.contains("format") ? body["format"].dump() : "", "is required: " + formats});
  else if (!record::parse_format(*format))
    errors.push_back({"format", *format, "must be " + formats});
  else
    job.format = *record::parse_format(*format);

  // The view parameters, each read and checked by its row of the table.
  render::ViewRequest picture;
  for (const render::ViewParameter& p : render::view_parameters()) {
    const std::string key(p.name);
    if (!body.contains(key)) continue;
    const json& v = body[key];
    const render::ParameterType type = render::parameter_type(p);
    const bool numeric = type == render::ParameterType::integer || type == render::ParameterType::number;
    std::optional<std::string> why =
        render::expectation(p, limits.max_image_side);  // a value of another JSON type
    if (numeric && v.is_number())
      why = render::set_parameter(picture, p, v.get<double>(), limits.max_image_side);
    else if (!numeric && v.is_string())
      why = render::set_parameter(picture, p, v.get<std::string>(), limits.max_image_side);
    if (why) errors.push_back({key, v.is_string() ? v.get<std::string>() : v.dump(), *why});
  }
  render::ViewOptions& view = job.frames.view;
  view.width = picture.width;
  view.height = picture.height;
  view.layers = picture.layers;
  if (format && record::parse_format(*format))
    if (const auto why = record::size_unsupported_reason(job.format, view.width, view.height))
      errors.push_back({view.width % 2 ? "width" : "height",
                        std::to_string(view.width % 2 ? view.width : view.height), *why});
  job.frames.trail_span = picture.trail;
  job.frames.yaw = picture.yaw;
  job.frames.pitch = picture.pitch;
  job.frames.distance = picture.distance;
  job.frames.motion = picture.motion;
  if (!errors.empty()) throw ApiError{422, "Invalid value", errors, ""};

  // The copy: the parameters at t = 0 and the timeline, under the session's lock only to read them.
  const std::lock_guard lock(s.mutex);
  try {
    view = render::view_options(picture, s.run.scene.surface);
  } catch (const render::ViewRefused& e) {
    throw bad(422, "Invalid value", e.parameter, e.value, e.what());
  }
  job.frames.scene = s.scene;
  job.frames.changes = s.changes;
  job.frames.max_attempts = static_cast<std::uint64_t>(limits.max_steps);
  return job;
}

void create_recording(ServerContext& server, const Call& call, httplib::Response& res) {
  RecordingJob job = recording_job(server, call, *find_session(server, call.id));
  const std::string id = server.recordings.start(std::move(job));
  res.set_header("Location", kRecordings + "/" + id);
  send_json(res, server.recordings.describe(id), 202);
}

// From the store when there is one: any replica answers for any recording (server/jobs/recordings.h).
void get_recording(ServerContext& server, const Call& call, httplib::Response& res) {
  res.set_header("Cache-Control", "no-store");
  send_json(res, server.recordings.describe(call.id));
}

// The whole file (200), or one byte range of it (206) by RFC 9110 §14 (server/http/byte_ranges.h).
// An If-Range is never matched (no validator is sent), so it asks for the whole file.
void get_recording_file(ServerContext& server, const Call& call, httplib::Response& res) {
  const RecordingDownload file = server.recordings.file(call.id);
  const std::string asked = call.http.get_header_value(std::string(kRangeHeader));
  const RangeAnswer range = call.http.has_header("If-Range")
                                ? RangeAnswer{}
                                : answer_range(asked, static_cast<std::uint64_t>(file.bytes));
  res.set_header("Accept-Ranges", "bytes");
  if (range.kind == RangeAnswer::Kind::unsatisfiable) {
    res.set_header("Content-Range", range.content_range);
    throw bad(416, "Range not satisfiable", "Range", asked,
              "the file has " + std::to_string(file.bytes) + " bytes: no byte asked for is in it");
  }
  const bool partial = range.kind == RangeAnswer::Kind::partial;
  const std::uint64_t first = partial ? range.first : 0;
  const std::uint64_t count = partial ? range.last - range.first + 1 : static_cast<std::uint64_t>(file.bytes);
  res.set_header("Content-Disposition", "attachment; filename=\"" + file.file_name + "\"");
  res.set_header("Cache-Control", "no-store");
  if (partial) {
    res.status = 206;
    res.set_header("Content-Range", range.content_range);
  }
  res.set_content_provider(
      static_cast<std::size_t>(count), file.content_type,
      [read = file.read, first](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
        const std::string bytes = read(first + offset, length);
        if (bytes.empty()) return false;
        sink.write(bytes.data(), bytes.size());
        return true;
      });
}

void delete_recording(ServerContext& server, const Call& call, httplib::Response& res) {
  if (server.recordings.cancel_or_delete(call.id)) {
    send_json(res, server.recordings.describe(call.id));
    return;
  }
  res.status = 204;
}

}  // namespace

std::vector<Route> recording_routes(const Limits& limits) {
  ordered_json formats = ordered_json::array();
  for (const record::FormatInfo& f : record::kFormats) formats.push_back(std::string(f.name));
  ordered_json properties{
      {"t_start", {{"type", "number"}, {"minimum", 0}, {"default", 0}, {"x-unit", "time"}}},
      {"t_end",
       {{"type", "number"}, {"x-unit", "time"}, {"description", "end of the window (excluded), > t_start"}}},
      {"fps",
       {{"type", "number"}, {"minimum", record::kMinFps}, {"maximum", record::kMaxFps}, {"default", 30}}},
      {"speed",
       {{"type", "number"}, {"default", 1}, {"description", "simulated time per second of the file"}}},
      {"format", {{"type", "string"}, {"enum", formats}}}};
  // The picture: the frame's query parameters, the same table's rows (render/view_parameters.h).
  for (const QueryParam& p : frame_params(limits)) {
    properties[p.name] = parameter_schema(p);
    properties[p.name]["description"] = p.description;
  }
  const ordered_json body_schema{{"type", "object"},
                                 {"required", {"t_end", "format"}},
                                 {"additionalProperties", false},
                                 {"properties", properties}};
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
                     {429, "over max_recordings_per_client, max_recordings or max_recording_disk_bytes"},
                     {503, "the session store is away (nothing started)"}}},
      {.method = "GET",
       .path = kRecordings + "/{id}",
       .operation_id = "get_recording",
       .handler = get_recording,
       .summary = "A recording's status (queued, running, done, failed with a reason, cancelled) and "
                  "progress 0…1",
       .responses = {{200, "the recording"}, {404, "unknown recording"}, {503, "the session store is away"}}},
      {.method = "GET",
       .path = kRecordings + "/{id}/file",
       .operation_id = "get_recording_file",
       .handler = get_recording_file,
       .summary = "The recorded file, with its content type and a download file name",
       .responses = {{200, "image/gif, video/webm, video/mp4 or application/zip"},
                     {404, "unknown recording"},
                     {409, "not done yet, or failed"},
                     {503, "the session store is away"}}},
      {.method = "DELETE",
       .path = kRecordings + "/{id}",
       .operation_id = "delete_recording",
       .handler = delete_recording,
       .summary = "Cancels a queued or running recording (200, status cancelled), or deletes a "
                  "finished one and its file (204)",
       .responses = {{200, "cancelled"},
                     {204, "deleted"},
                     {404, "unknown recording"},
                     {503, "the session store is away (nothing changed)"}}}};
}

}  // namespace spinfold::server
