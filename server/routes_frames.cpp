// Frames: a session's state as a PNG (lossless) or a JPEG (motion frames: a third of the bytes),
// rendered on the one render thread and cached by ETag.
#include <cstdio>

#include "engine/chart.h"
#include "engine/trail.h"
#include "render/jpeg_encoder.h"
#include "render/snapshot.h"
#include "render/view.h"
#include "server/context.h"
#include "server/problem.h"
#include "server/route_table.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

namespace {

// What the picture shows, from the query (checked by the table; the view against the surface here).
struct FrameRequest {
  render::ViewOptions view;
  double scale = 0.25;                         // [surface radii per unit of e_A]
  std::optional<double> yaw, pitch, distance;  // absent: the camera is aimed at the body
  std::optional<double> trail;                 // [time] span of the trail; absent: the whole run
  std::optional<int> jpeg_quality;             // frame.jpg: 1..100; absent: a PNG
};

FrameRequest frame_request(const Query& q, SurfaceKind surface) {
  FrameRequest f;
  f.view.kind = render::default_view(surface);
  f.view.width = static_cast<int>(*q.integer("width"));
  f.view.height = static_cast<int>(*q.integer("height"));
  if (const auto v = q.text("view")) f.view.kind = *render::parse_view(*v);
  if (const auto v = q.text("layers")) f.view.layers = *render::parse_layers(*v);
  f.scale = *q.number("scale");
  f.yaw = q.number("yaw");
  f.pitch = q.number("pitch");
  f.distance = q.number("distance");
  f.trail = q.number("trail");
  return f;
}

FrameRequest jpeg_request(const Query& q, SurfaceKind surface) {
  FrameRequest f = frame_request(q, surface);
  f.jpeg_quality = static_cast<int>(*q.integer("quality"));
  return f;
}

// The ETag names the state and every parameter of the picture: a match renders nothing.
std::string frame_etag(const std::string& id, std::uint64_t version, const FrameRequest& f) {
  const auto camera = [](const std::optional<double>& v) {
    char text[32] = "auto";  // aimed at the body
    if (v) std::snprintf(text, sizeof text, "%.17g", *v);
    return std::string(text);
  };
  char text[256];
  std::snprintf(text, sizeof text, "\"%s-%llu-%d-%dx%d-%u-%.17g-%s-%s-%s-%s-%s%d\"", id.c_str(),
                static_cast<unsigned long long>(version), static_cast<int>(f.view.kind), f.view.width,
                f.view.height, f.view.layers, f.scale, camera(f.yaw).c_str(), camera(f.pitch).c_str(),
                camera(f.distance).c_str(), camera(f.trail).c_str(), f.jpeg_quality ? "jpeg" : "png",
                f.jpeg_quality.value_or(0));
  return text;
}

void send_frame(ServerContext& server, const Call& call, httplib::Response& res, bool jpeg) {
  const auto s = find_session(server, call.id);
  const std::string if_none_match = call.http.get_header_value("If-None-Match");
  FrameRequest f;
  std::string etag;
  Png png;
  std::optional<render::Snapshot> snapshot;
  {
    const std::lock_guard lock(s->mutex);
    const SurfaceKind surface = s->run.scene.surface.kind;
    f = jpeg ? jpeg_request(call.query, surface) : frame_request(call.query, surface);
    if (const auto why = render::view_unsupported_reason(f.view.kind, surface))
      throw bad(422, "Invalid value", "view", std::string(render::view_name(f.view.kind)), *why);
    etag = frame_etag(call.id, s->version, f);
    png = server.frames.find(etag);
    if (!png && if_none_match != etag) {
      f.view.scale = f.scale * s->run.scene.surface.radius;
      static const Trail kNoTrail;  // trails are copied only when drawn
      snapshot = render::make_snapshot(s->run, f.view.layers & render::kTrail ? s->trail : kNoTrail,
                                       f.trail.value_or(-1.0));
    }
    res.set_header("X-Spinfold-Provenance", provenance(*s));
  }
  res.set_header("ETag", etag);
  res.set_header("Cache-Control", "no-cache");
  if (if_none_match == etag) {
    res.status = 304;
    return;
  }
  if (!png) {
    render::aim_camera_at_body(f.view, *snapshot);
    if (f.yaw) f.view.yaw = *f.yaw;
    if (f.pitch) f.view.pitch = *f.pitch;
    if (f.distance) f.view.distance = *f.distance;
    try {
      png = std::make_shared<const std::vector<std::uint8_t>>(
          server.renderer.render(std::move(*snapshot), f.view, f.jpeg_quality).get());
    } catch (const std::exception& e) {
      throw ApiError{503, "Rendering unavailable", {{"", "", e.what()}}, "5"};
    }
    server.frames.insert(etag, png);
  }
  res.body.assign(png->begin(), png->end());
  res.set_header("Content-Type", jpeg ? "image/jpeg" : "image/png");
}

void get_frame(ServerContext& server, const Call& call, httplib::Response& res) {
  send_frame(server, call, res, false);
}

void get_frame_jpeg(ServerContext& server, const Call& call, httplib::Response& res) {
  send_frame(server, call, res, true);
}

std::vector<std::string> view_names() {
  std::vector<std::string> names;
  for (const auto kind : {render::ViewKind::sphere, render::ViewKind::hyperboloid, render::ViewKind::disk,
                          render::ViewKind::plane})
    names.emplace_back(render::view_name(kind));
  return names;
}

}  // namespace

std::vector<Route> frame_routes(const Limits& limits) {
  const render::ViewOptions defaults;
  const auto side = [&](const char* name, int fallback, const char* what) {
    return QueryParam{.name = name,
                      .type = ParamType::integer,
                      .unit = "pixels",
                      .minimum = 16,
                      .maximum = limits.max_image_side,
                      .default_value = static_cast<long long>(fallback),
                      .description = what};
  };
  Route png{
      .method = "GET",
      .path = "/api/v1/sessions/{id}/frame.png",
      .handler = get_frame,
      .summary = "A PNG frame of the session's state; ETag, If-None-Match → 304",
      .query = {side("width", defaults.width, "image width"),
                side("height", defaults.height, "image height"),
                {.name = "view",
                 .type = ParamType::enumeration,
                 .values = view_names(),
                 .description = "the picture: the 3-D sphere or hyperboloid, the Poincaré disk (or "
                                "stereographic plane) or the flat plane; default: the surface's own"},
                {.name = "layers",
                 .type = ParamType::list,
                 .values = {"surface", "grid", "body", "frame", "trail", "hud"},
                 .default_value = "surface,grid,body,frame,trail,hud",
                 .description = "what is drawn: the shaded surface, its geodesic grid, the body's "
                                "ellipse, the frame arrows, the trail, the text overlay"},
                {.name = "scale",
                 .type = ParamType::number,
                 .minimum = 0.0,
                 .maximum = 10.0,
                 .exclusive_minimum = true,
                 .default_value = 0.25,
                 .description = "the body's ellipse: the image of this many surface radii of the unit "
                                "circle under e_A"},
                {.name = "yaw",
                 .type = ParamType::number,
                 .unit = "rad",
                 .minimum = -100.0,
                 .maximum = 100.0,
                 .description = "camera azimuth (3-D views); default: aimed at the body"},
                {.name = "pitch",
                 .type = ParamType::number,
                 .unit = "rad",
                 .minimum = -1.55,
                 .maximum = 1.55,
                 .description = "camera elevation (3-D views); default: aimed at the body"},
                {.name = "distance",
                 .type = ParamType::number,
                 .unit = "radii",
                 .minimum = 1.2,
                 .maximum = 100.0,
                 .description = "camera distance from the centre in surface radii (3-D views); default: "
                                "aimed at the body"},
                {.name = "trail",
                 .type = ParamType::number,
                 .unit = "time",
                 .minimum = 0.0,
                 .description = "the trail's span: the path over this much simulated time before now; "
                                "default: the whole run (sampled every 0.01, the spacing doubling past "
                                "8192 samples)"}},
      .responses = {{200, "image/png"},
                    {304, "unchanged (If-None-Match)"},
                    {422, "an invalid parameter, or a view that cannot show this surface"},
                    {503, "rendering unavailable; Retry-After"}}};
  Route jpeg = png;
  jpeg.path = "/api/v1/sessions/{id}/frame.jpg";
  jpeg.handler = get_frame_jpeg;
  jpeg.summary =
      "The same frame as a JPEG (motion frames: a third of the PNG's bytes); ETag, If-None-Match → 304";
  jpeg.query.push_back({.name = "quality",
                        .type = ParamType::integer,
                        .minimum = 1,
                        .maximum = 100,
                        .default_value = static_cast<long long>(render::kDefaultJpegQuality),
                        .description = "JPEG quality (libjpeg-turbo, 4:2:0); the default is chosen from "
                                       "the size/quality table in docs/performance.md"});
  jpeg.responses.front() = {200, "image/jpeg"};
  return {png, jpeg};
}

}  // namespace spinfold::server
