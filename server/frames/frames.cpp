#include "server/frames/frames.h"

#include <cstdio>
#include <future>
#include <limits>
#include <stdexcept>
#include <vector>

#include "codec/provenance.h"
#include "engine/number_text.h"
#include "engine/timeline.h"
#include "render/jpeg_encoder.h"
#include "render/png_encoder.h"
#include "render/snapshot.h"
#include "render/view_parameters.h"
#include "server/frames/render_pool.h"
#include "server/http/problem.h"
#include "server/http/route_table.h"
#include "server/options.h"
#include "server/sessions/session.h"

namespace spinfold::server {

namespace {

// The snapshot and camera of a frame not yet made (null when the cache has or is making it).
struct FrameJob {
  std::string etag;
  FrameInfo info;
  std::optional<render::Snapshot> snapshot;
  render::ViewOptions view;
  std::vector<render::PngText> texts;  // the provenance of the state shown (PNG only)
  // With FrameRequest::at: what the replay starts from (the snapshot is made by replaying).
  struct Replay {
    Scene scene;
    std::vector<ParameterChange> changes;
    Trail trail;  // the spacing and cap at t = 0, no points
  };
  std::optional<Replay> replay;
};

FrameJob frame_job(FrameCache& cache, const std::string& id, Session& s, const FrameRequest& f) {
  const std::lock_guard lock(s.mutex);
  FrameJob job{frame_etag(id, state_tag(s), f),
               {s.version, f.at.value_or(s.run.state.t), {}, false},
               std::nullopt,
               f.view,
               {},
               std::nullopt};
  if (f.at && !cache.contains(job.etag)) {
    job.view = render::view_options(view_request(f), s.run.scene.surface);
    Trail trail;  // sampled from t = 0 as the session's was (its spacing has doubled since, if long)
    trail.max_points = s.trail.max_points;
    job.replay = FrameJob::Replay{s.scene, s.changes, std::move(trail)};
    return job;
  }
  if (f.follow || !cache.contains(job.etag)) {  // a followed camera is placed from the snapshot
    job.view = render::view_options(view_request(f), s.run.scene.surface);
    job.snapshot = frame_snapshot(s.run, s.trail, f);
    if (!f.jpeg_quality)
      job.texts = picture_texts(s.run.scene, "", s.run.state.t, render::view_name(f.view.kind));
  }
  return job;
}

// Thrown by a maker without a snapshot (the frame left the cache after it was looked up): ask again.
struct Evicted {};

}  // namespace

std::vector<QueryParam> frame_params(const Limits& limits) {
  std::vector<QueryParam> params;
  for (const render::ViewParameter& p : render::view_parameters()) {
    const Range range = render::allowed_range(p, limits.max_image_side);
    QueryParam q{
        .name = std::string(p.name), .unit = std::string(p.unit), .description = std::string(p.help)};
    switch (render::parameter_type(p)) {
      case render::ParameterType::integer: q.type = ParamType::integer; break;
      case render::ParameterType::number: q.type = ParamType::number; break;
      case render::ParameterType::enumeration: q.type = ParamType::enumeration; break;
      case render::ParameterType::list: q.type = ParamType::list; break;
    }
    if (range.has_min()) q.minimum = range.min;
    if (range.has_max()) q.maximum = range.max;
    q.exclusive_minimum = range.min_open;
    for (const std::string_view c : render::choices(p)) q.values.emplace_back(c);
    // Built in place (GCC 12 at -O1 with ThreadSanitizer warns, wrongly, of an uninitialised
    // string when a temporary variant is moved into the optional).
    if (const auto d = render::default_value(p)) {
      const double* x = std::get_if<double>(&*d);
      if (!x)
        q.default_value.emplace(std::in_place_type<std::string>, std::get<std::string>(*d));
      else if (q.type == ParamType::integer)
        q.default_value.emplace(std::in_place_type<long long>, static_cast<long long>(*x));
      else
        q.default_value.emplace(std::in_place_type<double>, *x);
    }
    params.push_back(std::move(q));
  }
  return params;
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

QueryParam at_param() {
  return {.name = "at",
          .type = ParamType::number,
          .unit = "time",
          .minimum = 0.0,
          .description =
              "the picture of the run at this earlier time (at most the session's t: a "
              "scrubber's), replayed from t = 0 through the timeline; default: now"};
}

void apply_at(const Query& q, FrameRequest& f, double t, long max_steps) {
  f.at = q.number("at");
  f.max_attempts = static_cast<std::uint64_t>(max_steps);
  if (f.at && *f.at > t)
    throw bad(422, "Invalid value", "at", shortest(*f.at),
              "must be <= the session's time t = " + shortest(t) + " (a picture of the run so far)");
}

render::Snapshot frame_snapshot(const Simulation& run, const Trail& trail, const FrameRequest& f) {
  static const Trail kNoTrail;
  return render::make_snapshot(run, f.view.layers & render::kTrail ? trail : kNoTrail,
                               f.trail.value_or(-1.0));
}

render::ViewRequest view_request(const FrameRequest& f) {
  return {.width = f.view.width,
          .height = f.view.height,
          .view = f.view.kind,
          .layers = f.view.layers,
          .scale = f.scale,
          .yaw = f.yaw,
          .pitch = f.pitch,
          .distance = f.distance,
          .trail = f.trail,
          .motion = f.motion,
          .shown_width = f.view.shown_width > 0 ? std::optional<double>(f.view.shown_width) : std::nullopt};
}

void apply_view_query(const Query& q, FrameRequest& f, SurfaceKind surface) {
  render::ViewRequest r = view_request(f);
  for (const render::ViewParameter& p : render::view_parameters()) {
    const std::string name(p.name);
    std::optional<render::GivenValue> given;
    if (render::parameter_type(p) == render::ParameterType::integer ||
        render::parameter_type(p) == render::ParameterType::number) {
      if (const auto x = q.number(name)) given = *x;
    } else if (const auto text = q.text(name)) {
      given = *text;
    }
    // Checked already by parse_query against the same table (frame_params): a refusal here is a bug.
    if (given)
      if (const auto why = render::set_parameter(r, p, *given, std::numeric_limits<int>::max()))
        throw std::logic_error("query parameter " + name + " passed the route's check: " + *why);
  }
  f.view.kind = r.view.value_or(render::default_view(surface));
  f.view.width = r.width;
  f.view.height = r.height;
  f.view.layers = r.layers;
  f.scale = r.scale;
  f.yaw = r.yaw;
  f.pitch = r.pitch;
  f.distance = r.distance;
  f.trail = r.trail;
  f.motion = r.motion;
  f.view.shown_width = r.shown_width ? static_cast<int>(std::lround(*r.shown_width)) : 0;
}

FrameRequest frame_request(const Query& q, SurfaceKind surface, bool jpeg, long long max_pixels) {
  FrameRequest f;
  f.view.kind = render::default_view(surface);
  apply_view_query(q, f, surface);
  if (jpeg) f.jpeg_quality = static_cast<int>(*q.integer("quality"));
  check_view(f, surface, max_pixels);
  return f;
}

void check_view(const FrameRequest& f, SurfaceKind surface, long long max_pixels) {
  if (const auto why = render::view_unsupported_reason(f.view.kind, surface))
    throw bad(422, "Invalid value", "view", std::string(render::view_name(f.view.kind)), *why);
  const long long pixels = static_cast<long long>(f.view.width) * f.view.height;
  if (max_pixels > 0 && pixels > max_pixels)
    throw bad(422, "Invalid value", "width", std::to_string(f.view.width),
              "width × height = " + std::to_string(pixels) + " pixels; a frame has at most " +
                  std::to_string(max_pixels) + " (limits.max_image_pixels: the memory one frame takes)");
}

std::string frame_etag_prefix(const std::string& id) {
  return "W/\"" + id + "-";
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
  std::string tag = text;
  if (f.at) tag.insert(tag.size() - 1, "-at" + camera(f.at));
  // The overlay is sized for the width shown: another shown width is another picture.
  if (f.view.shown_width > 0) tag.insert(tag.size() - 1, "-shown" + std::to_string(f.view.shown_width));
  return tag;
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

namespace {

// Places a followed frame's camera (FrameRequest::follow) in the order frames are asked for.
render::CameraPlaced place_followed(const FrameRequest& f, render::ViewOptions& view,
                                    const render::Snapshot& snapshot) {
  const std::lock_guard lock(f.follow->mutex);
  const auto now = std::chrono::steady_clock::now();
  const double seconds =
      f.still || !f.follow->last ? 0.0 : std::chrono::duration<double>(now - *f.follow->last).count();
  if (!f.still) f.follow->last = now;
  return f.follow->follower.place(view, view_request(f), snapshot, seconds);
}

// The snapshot of FrameRequest::at, replayed outside the session's lock; 422 naming `at` when the
// step attempts run out first.
void replay_snapshot(const FrameRequest& f, FrameJob& job) {
  TimelineReplay replay(job.replay->scene, job.replay->changes, job.replay->trail);
  if (!replay.advance_to(*f.at, f.max_attempts))
    throw bad(422, "Invalid value", "at", shortest(*f.at),
              "the replay to this time ran out of step attempts (limits.max_steps = " +
                  std::to_string(f.max_attempts) + ")");
  job.snapshot = frame_snapshot(replay.run(), replay.trail(), f);
  if (!f.jpeg_quality)
    job.texts = picture_texts(replay.run().scene, "", replay.run().state.t, render::view_name(f.view.kind));
}

}  // namespace

FrameBytes session_frame(FrameCache& cache, RenderPool& renderer, const std::string& id, Session& s,
                         const FrameRequest& f, std::string& etag, FrameInfo* info) {
  for (int attempt = 0;; ++attempt) {
    FrameJob job = frame_job(cache, id, s, f);
    const auto encode = [&](const render::Image& image) {
      return std::make_shared<const std::vector<std::uint8_t>>(
          f.jpeg_quality ? render::encode_jpeg(image.rgba.data(), image.width, image.height, *f.jpeg_quality)
                         : render::encode_png(image.rgba.data(), image.width, image.height, job.texts));
    };
    std::optional<render::ViewOptions> placed;
    bool own_camera = false;
    if (f.follow) {
      placed = job.view;
      const render::CameraPlaced where = place_followed(f, *placed, *job.snapshot);
      job.info.on_way = where == render::CameraPlaced::on_way;
      own_camera = where != render::CameraPlaced::aimed;
      if (render::view_info(placed->kind).three_d)
        job.info.camera = std::array<double, 3>{placed->yaw, placed->pitch, placed->distance};
    }
    etag = job.etag;
    if (info) *info = job.info;
    try {
      if (own_camera) {  // this stream's alone (on its way, or held): rendered, not cached
        etag.insert(etag.size() - 1, "-following");
        return encode(renderer.render(id, std::move(*job.snapshot), *placed).get());
      }
      return cache.get(job.etag, [&]() -> FrameBytes {
        if (job.replay) replay_snapshot(f, job);
        if (!job.snapshot) throw Evicted{};
        if (!placed) render::place_camera(job.view, view_request(f), *job.snapshot);
        return encode(renderer.render(id, std::move(*job.snapshot), placed ? *placed : job.view).get());
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
