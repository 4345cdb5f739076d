// What the API describes about itself: health, the presets, the integrators, the scene schema,
// this API (OpenAPI), and the browser UI's files.
#include <cctype>
#include <string_view>

#include "codec/presets.h"
#include "codec/provenance.h"
#include "codec/scene_json.h"
#include "codec/scene_schema.h"
#include "engine/integrator.h"
#include "engine/scene_fields.h"
#include "record/recorder.h"
#include "render/gl_context.h"
#include "render/view.h"
#include "render/view_parameters.h"
#include "server/context.h"
#include "server/http/problem.h"
#include "server/http/web_assets.h"
#include "server/routes/routes.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

namespace {

using nlohmann::json;
using nlohmann::ordered_json;

void get_health(ServerContext& server, const Call&, httplib::Response& res) {
  const render::GlInUse gl = render::gl_in_use();
  // A replica whose store is away cannot take changes: 503, so that a readiness probe (Kubernetes)
  // takes it out of the Service until the store answers again.
  const bool store_ok = !server.db || server.db->reachable();
  send_json(res,
            {{"status", store_ok ? "ok" : "store unavailable"},
             {"version", server_version()},
             {"commit", std::string(build_commit())},
             {"sessions", server.sessions.size()},
             {"streams", server.open_streams.load()},
             {"render_threads", server.renderer.threads()},
             {"render_threads_started", server.renderer.started()},
             // The render threads' GL backend and GL_RENDERER ("" until one has made its context).
             {"gl", {{"backend", gl.backend}, {"renderer", gl.renderer}}},
             {"store",
              {{"kind", server.db ? std::string(server.db->kind()) : "memory"},
               {"where", server.db ? server.db->path() : ""},
               {"reachable", store_ok}}}},
            store_ok ? 200 : 503);
}

void get_scenes(ServerContext&, const Call&, httplib::Response& res) {
  // In the lesson sequence (codec/presets.h), each with its chapter and the preset after it.
  ordered_json list = ordered_json::array();
  const std::span<const LessonPlace> sequence = lesson_sequence();
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    const PresetSource& p = *find_preset(sequence[i].preset);
    const SceneParse parsed = parse_scene_text(p.json);
    list.push_back(
        {{"name", std::string(p.name)},
         {"chapter", std::string(sequence[i].chapter)},
         {"next", i + 1 < sequence.size() ? json(std::string(sequence[i + 1].preset)) : json(nullptr)},
         {"default", p.name == kDefaultPreset},
         {"description", parsed.scene ? parsed.scene->description : ""},
         {"look_for", std::string(p.look_for)},
         {"scene", json::parse(p.json)}});
  }
  send_json(res, list);
}

void get_integrators(ServerContext&, const Call&, httplib::Response& res) {
  ordered_json list = ordered_json::array();
  for (const CatalogEntry& e : integrator_catalog())
    list.push_back({{"name", std::string(e.info.name)},
                    {"order", e.info.order},
                    {"symplectic", e.info.symplectic},
                    {"adaptive", e.info.adaptive},
                    {"exact", e.info.exact},
                    {"summary", std::string(e.info.summary)}});
  send_json(res, list);
}

void get_views(ServerContext&, const Call&, httplib::Response& res) {
  ordered_json list = ordered_json::array();
  for (const render::ViewInfo& v : render::views()) {
    ordered_json surfaces = ordered_json::array();
    for (const EnumName<SurfaceKind>& kind : kSurfaceKindNames)
      if (render::shows(v, kind.value)) surfaces.push_back(std::string(kind.name));
    list.push_back({{"name", std::string(v.name)},
                    {"title", std::string(v.title)},
                    {"surfaces", surfaces},
                    {"three_d", v.three_d},
                    {"description", std::string(v.description)}});
  }
  send_json(res, list);
}

// The view-parameter, layer and recording-format tables (render/view_parameters.h,
// record/recorder.h), as the UI builds its view controls from them.
void get_view_parameters(ServerContext& server, const Call&, httplib::Response& res) {
  send_json(res, view_parameters_json(server.options.limits));
}

void get_schema(ServerContext&, const Call&, httplib::Response& res) {
  send_json(res, scene_schema());
}

void get_openapi(ServerContext& server, const Call&, httplib::Response& res) {
  send_json(res, openapi_document(route_table(server.options.limits)));
}

void get_web_asset(ServerContext&, const Call& call, httplib::Response& res) {
  const WebAsset* asset = web_asset(call.http.path);
  if (!asset) throw bad(404, "Not found", "path", call.http.path, "no such file");
  res.body.assign(asset->body.begin(), asset->body.end());
  res.set_header("Content-Type", std::string(asset->content_type));
}

// "/" → get_web_index, "/vendor/uPlot.esm.js" → get_web_vendor_uplot_esm_js.
std::string asset_operation_id(std::string_view path) {
  std::string id = "get_web";
  for (const char c : path == "/" ? std::string_view("/index") : path)
    id += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(c)) : '_';
  return id;
}

}  // namespace

ordered_json view_parameters_json(const Limits& limits) {
  ordered_json parameters = ordered_json::array();
  for (const render::ViewParameter& p : render::view_parameters()) {
    ordered_json row{{"name", std::string(p.name)}};
    const Range range = render::allowed_range(p, limits.max_image_side);
    switch (render::parameter_type(p)) {
      case render::ParameterType::integer: row["type"] = "integer"; break;
      case render::ParameterType::number: row["type"] = "number"; break;
      case render::ParameterType::enumeration: row["type"] = "enum"; break;
      case render::ParameterType::list: row["type"] = "list"; break;
    }
    if (!p.unit.empty()) row["unit"] = std::string(p.unit);
    if (range.has_min()) row["min"] = range.min;
    if (range.min_open) row["exclusive_min"] = true;
    if (range.has_max()) row["max"] = range.max;
    if (range.max_open) row["exclusive_max"] = true;
    if (const std::vector<std::string_view> choices = render::choices(p); !choices.empty()) {
      row["choices"] = ordered_json::array();
      for (const std::string_view c : choices) row["choices"].push_back(std::string(c));
    }
    const auto fallback = render::default_value(p);
    row["default"] = !fallback ? ordered_json(nullptr)
                     : std::holds_alternative<double>(*fallback)
                         ? ordered_json(std::get<double>(*fallback))
                         : ordered_json(std::get<std::string>(*fallback));
    row["help"] = std::string(p.help);
    parameters.push_back(row);
  }
  ordered_json layers = ordered_json::array();
  for (const render::LayerInfo& l : render::kLayerTable)
    layers.push_back(
        {{"name", std::string(l.name)}, {"default", l.on_by_default}, {"help", std::string(l.help)}});
  ordered_json formats = ordered_json::array();
  for (const record::FormatInfo& f : record::kFormats)
    formats.push_back({{"name", std::string(f.name)},
                       {"extension", std::string(f.extension)},
                       {"content_type", std::string(f.content_type)},
                       {"help", std::string(f.help)}});
  // width × height at most: a raster frame's (frame.png, frame.jpg, live) and a recording's.
  const ordered_json max_pixels{{"frame", limits.max_image_pixels},
                                {"recording", limits.max_recording_pixels}};
  return {{"parameters", parameters}, {"layers", layers}, {"formats", formats}, {"max_pixels", max_pixels}};
}

std::vector<Route> catalog_routes(const Limits&) {
  std::vector<Route> routes = {
      {.method = "GET",
       .path = "/api/v1/health",
       .operation_id = "get_health",
       .handler = get_health,
       .summary = "Readiness, version, sessions, open streams, render threads and their GL backend, the "
                  "session store",
       .responses =
           {{200,
             "{\"status\": \"ok\", \"version\", \"sessions\", \"streams\", \"render_threads\", "
             "\"render_threads_started\", \"gl\": {\"backend\", \"renderer\"}, \"store\": {\"kind\", "
             "\"where\", \"reachable\"}}"},
            {503,
             "the same, with \"status\": \"store unavailable\": the session store does not "
             "answer (the replica is not ready)"}}},
      {.method = "GET",
       .path = "/api/v1/scenes",
       .operation_id = "list_scenes",
       .handler = get_scenes,
       .summary = "The preset scenes, in the lesson sequence",
       .responses = {{200,
                      "name, chapter (its part of the lesson sequence), next (the preset after it, or null), "
                      "default (the scene a new page opens), "
                      "description, look_for (what to look for, in plain words), scene"}}},
      {.method = "GET",
       .path = "/api/v1/integrators",
       .operation_id = "list_integrators",
       .handler = get_integrators,
       .summary = "The integrator catalog",
       .responses = {{200, "name, order, symplectic, adaptive, exact, summary"}}},
      {.method = "GET",
       .path = "/api/v1/views",
       .operation_id = "list_views",
       .handler = get_views,
       .summary = "The views a frame can be drawn in, the surfaces each shows, in the UI's order",
       .responses = {{200, "name, title, surfaces, three_d, description"}}},
      {.method = "GET",
       .path = "/api/v1/view-parameters",
       .operation_id = "list_view_parameters",
       .handler = get_view_parameters,
       .summary = "The parameters of a picture (frame query, recording body, CLI options) with their units, "
                  "ranges, defaults and help; the layers; the recording formats",
       .responses = {{200,
                      "{\"parameters\": [name, type, unit, min, max, default, choices, help], \"layers\": "
                      "[name, default, help], \"formats\": [name, extension, content_type, help]}"}}},
      {.method = "GET",
       .path = "/api/v1/schema",
       .operation_id = "get_scene_schema",
       .handler = get_schema,
       .summary = "The scene format as JSON Schema (defaults, units, limits)",
       .responses = {{200, "JSON Schema"}}},
      {.method = "GET",
       .path = "/api/v1/openapi.json",
       .operation_id = "get_openapi_document",
       .handler = get_openapi,
       .summary = "This document",
       .responses = {{200, "OpenAPI 3.1"}}},
  };
  // The browser UI, embedded at build time: every file of web/ (the build's glob), each described
  // by its own opening comment.
  for (const auto& [path, asset] : web_assets())
    routes.push_back({.method = "GET",
                      .path = path,
                      .operation_id = asset_operation_id(path),
                      .handler = get_web_asset,
                      .summary = std::string(asset.summary),
                      .ignores_unknown_query = true,
                      .responses = {{200, "the file"}}});
  return routes;
}

}  // namespace spinfold::server
