#include "server/frames.h"

#include <cstdio>
#include <future>
#include <vector>

#include "codec/provenance.h"
#include "render/jpeg_encoder.h"
#include "render/png_encoder.h"
#include "render/snapshot.h"
#include "server/context.h"
#include "server/problem.h"
#include "server/route_table.h"

namespace spinfold::server {

namespace {

std::vector<std::string> layer_names() {
  std::vector<std::string> names;
  for (const std::string_view name : render::layer_names()) names.emplace_back(name);
  return names;
}

std::vector<std::string> view_names() {
  std::vector<std::string> names;
  for (const render::ViewInfo& v : render::views()) names.emplace_back(v.name);
  return names;
}

// The snapshot and camera of a frame not yet made (null when the cache has or is making it).
struct FrameJob {
  std::string etag;
  FrameInfo info;
  std::optional<render::Snapshot> snapshot;
  render::ViewOptions view;
  std::vector<render::PngText> texts;  // the provenance of the state shown (PNG only)
};

FrameJob frame_job(ServerContext& server, const std::string& id, Session& s, const FrameRequest& f) {
  const std::lock_guard lock(s.mutex);
  FrameJob job{frame_etag(id, state_tag(s), f), {s.version, s.run.state.t}, std::nullopt, f.view, {}};
  if (!server.frames.contains(job.etag)) {
    job.view.scale = f.scale * render::body_scale_length(f.view.kind, s.run.scene.surface);
    static const Trail kNoTrail;  // trails are copied only when drawn
    job.snapshot = render::make_snapshot(s.run, f.view.layers & render::kTrail ? s.trail : kNoTrail,
                                         f.trail.value_or(-1.0));
    if (!f.jpeg_quality)
      job.texts = picture_texts(s.run.scene, "", s.run.state.t, render::view_name(f.view.kind));
  }
  return job;
}

// Thrown by a maker without a snapshot (the frame left the cache after it was looked up): ask again.
struct Evicted {};

}  // namespace

std::vector<QueryParam> frame_params(const Limits& limits) {
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
  return {side("width", defaults.width, "image width"),
          side("height", defaults.height, "image height"),
          {.name = "view",
           .type = ParamType::enumeration,
           .values = view_names(),
           .description = "the picture (GET /api/v1/views lists each with the surfaces it shows); "
                          "default: the surface's own"},
          {.name = "layers",
           .type = ParamType::list,
           .values = layer_names(),
           .default_value = "surface,grid,body,frame,trail,hud",
           .description = "what is drawn: the shaded surface, its geodesic grid, the body's "
                          "ellipse, the frame arrows, the trail, the text overlay, and (not by "
                          "default) the action variables and frequencies in the text overlay"},
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
                          "8192 samples)"}};
}

QueryParam quality_param() {
  return {.name = "quality",
          .type = ParamType::integer,
          .minimum = 1,
          .maximum = 100,
          .default_value = static_cast<long long>(render::kDefaultJpegQuality),
          .description =
              "JPEG quality (libjpeg-turbo, 4:2:0); the default is chosen from "
              "the size/quality table in docs/performance.md"};
}

FrameRequest frame_request(const Query& q, SurfaceKind surface, bool jpeg) {
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
  if (jpeg) f.jpeg_quality = static_cast<int>(*q.integer("quality"));
  check_view(f, surface);
  return f;
}

void check_view(const FrameRequest& f, SurfaceKind surface) {
  if (const auto why = render::view_unsupported_reason(f.view.kind, surface))
    throw bad(422, "Invalid value", "view", std::string(render::view_name(f.view.kind)), *why);
}

std::string frame_etag(const std::string& id, const std::string& state, const FrameRequest& f) {
  const auto camera = [](const std::optional<double>& v) {
    char text[32] = "auto";  // aimed at the body
    if (v) std::snprintf(text, sizeof text, "%.17g", *v);
    return std::string(text);
  };
  char text[256];
  std::snprintf(text, sizeof text, "W/\"%s-%s-%d-%dx%d-%u-%.17g-%s-%s-%s-%s-%s%d\"", id.c_str(),
                state.c_str(), static_cast<int>(f.view.kind), f.view.width, f.view.height, f.view.layers,
                f.scale, camera(f.yaw).c_str(), camera(f.pitch).c_str(), camera(f.distance).c_str(),
                camera(f.trail).c_str(), f.jpeg_quality ? "jpeg" : "png", f.jpeg_quality.value_or(0));
  return text;
}

bool etag_matches(const std::string& if_none_match, const std::string& etag) {
  const auto opaque = [](std::string_view tag) {
    while (!tag.empty() && (tag.front() == ' ' || tag.front() == '\t')) tag.remove_prefix(1);
    while (!tag.empty() && (tag.back() == ' ' || tag.back() == '\t')) tag.remove_suffix(1);
    if (tag.starts_with("W/")) tag.remove_prefix(2);
    return tag;
  };
  std::string_view rest = if_none_match;
  while (!rest.empty()) {
    const std::size_t comma = rest.find(',');
    const std::string_view one = opaque(rest.substr(0, comma));
    if (one == "*" || (!one.empty() && one == opaque(etag))) return true;
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return false;
}

FrameBytes session_frame(ServerContext& server, const std::string& id, Session& s, const FrameRequest& f,
                         std::string& etag, FrameInfo* info) {
  for (int attempt = 0;; ++attempt) {
    FrameJob job = frame_job(server, id, s, f);
    etag = job.etag;
    if (info) *info = job.info;
    try {
      return server.frames.get(job.etag, [&]() -> FrameBytes {
        if (!job.snapshot) throw Evicted{};
        render::aim_camera_at_body(job.view, *job.snapshot);
        if (f.yaw) job.view.yaw = *f.yaw;
        if (f.pitch) job.view.pitch = *f.pitch;
        if (f.distance) job.view.distance = *f.distance;
        const render::Image image = server.renderer.render(id, std::move(*job.snapshot), job.view).get();
        return std::make_shared<const std::vector<std::uint8_t>>(
            f.jpeg_quality
                ? render::encode_jpeg(image.rgba.data(), image.width, image.height, *f.jpeg_quality)
                : render::encode_png(image.rgba.data(), image.width, image.height, job.texts));
      });
    } catch (const Evicted&) {
      if (attempt == 3)
        throw ApiError{503, "Rendering unavailable", {{"", "", "the frame cache is too busy"}}, "1"};
    } catch (const ApiError&) {
      throw;
    } catch (const std::exception& e) {
      throw ApiError{503, "Rendering unavailable", {{"", "", e.what()}}, "5"};
    }
  }
}

}  // namespace spinfold::server
