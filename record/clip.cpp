#include "record/clip.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/integer_cast.h"
#include "engine/number_text.h"
#include "render/camera_follow.h"
#include "render/scene_builder.h"
#include "render/view_parameters.h"

namespace spinfold::record {

namespace {

// ⌈(t_end − t_start)·fps/speed⌉ as a double (inf or NaN for a window out of range). The 1e-9 keeps
// a window of a whole number of frames from gaining one to rounding.
double frames_exact(const Clip& c) {
  return std::ceil((c.t_end - c.t_start) * c.fps / c.speed - 1e-9);
}

}  // namespace

std::vector<FieldError> clip_errors(const Clip& c) {
  std::vector<FieldError> errors;
  const auto refuse = [&](const char* field, double value, const std::string& reason) {
    errors.push_back({field, shortest(value), reason});
  };
  if (!std::isfinite(c.t_start) || c.t_start < 0.0)
    refuse("t_start", c.t_start, "must be a finite number >= 0");
  if (!std::isfinite(c.t_end) || !(c.t_end > c.t_start))
    refuse("t_end", c.t_end, "must be a finite number > t_start");
  if (const auto why = refusal(kFpsRule, c.fps)) refuse("fps", c.fps, *why);
  if (!std::isfinite(c.speed) || !(c.speed > 0.0))
    refuse("speed", c.speed, "must be a finite number > 0 [simulated time per second]");
  if (errors.empty()) {
    const double n = frames_exact(c);
    if (!(n <= kMaxClipFrames)) {
      const bool window = (c.t_end - c.t_start) * c.fps > kMaxClipFrames;
      const std::string reason = "the window would take " + shortest(n) + " frames at fps " +
                                 shortest(c.fps) + " and speed " + shortest(c.speed) +
                                 "; at most 1e7 in one clip";
      errors.push_back({window ? "t_end" : "speed", shortest(window ? c.t_end : c.speed), reason});
    }
  }
  return errors;
}

long long frame_count(const Clip& c) {
  const double n = frames_exact(c);
  if (!(n <= kMaxClipFrames)) throw std::logic_error("frame_count of a clip with errors");
  return n < 1.0 ? 1 : *integer_within<long long>(n);
}

double frame_time(const Clip& c, long long k) {
  return c.t_start + static_cast<double>(k) * c.speed / c.fps;
}

namespace {

// `follower`: the clip's frames in order, each 1/fps of the file after the last (a camera aimed at
// the bodies stays put or glides: f.camera); null for a frame alone (a GIF's palette sample).
render::Image draw(const ClipFrames& f, const TimelineReplay& replay, const RenderFrame& render,
                   render::CameraFollower* follower = nullptr, double seconds = 0.0) {
  static const Trail kNoTrail;  // trails are copied only when drawn
  render::Snapshot snapshot = render::make_snapshot(
      replay.run(), f.view.layers & render::kTrail ? replay.trail() : kNoTrail, f.trail_span.value_or(-1.0));
  render::ViewOptions view = f.view;
  render::ViewRequest camera;  // the parts given; the rest aimed at the body
  camera.yaw = f.yaw;
  camera.pitch = f.pitch;
  camera.distance = f.distance;
  camera.motion = f.motion;
  if (follower)
    follower->place(view, camera, snapshot, seconds);
  else
    render::place_camera(view, camera, snapshot);
  render::Image image = render(std::move(snapshot), view);
  if (image.width != f.view.width || image.height != f.view.height ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4)
    throw RecordError("the renderer returned no frame");
  return image;
}

// Advances the replay to a frame's time: false when the run stopped (its status) or the step
// attempts per frame ran out on the way.
bool reached(TimelineReplay& replay, double t, std::uint64_t max_attempts) {
  return replay.advance_to(t, max_attempts) && replay.run().state.status == Status::ok;
}

[[noreturn]] void stopped(const TimelineReplay& replay, double t) {
  const Simulation& run = replay.run();
  throw RecordError("the run stopped at t = " + shortest(run.state.t) +
                    " before the frame at t = " + shortest(t) + ": " +
                    (run.state.status == Status::ok ? std::string("the step limit per frame ran out")
                                                    : std::string(status_description(run.state.status))));
}

}  // namespace

bool record_clip(const Clip& clip, const ClipFrames& f, ClipWriter& writer, const RenderFrame& render,
                 const Progress& progress) {
  const long long n = frame_count(clip);
  // Palette samples (GIF): frames spread evenly over the clip, first and last included.
  std::vector<long long> samples;
  const int wanted = writer.palette_samples();
  for (int j = 0; j < wanted; ++j) {
    const long long k = wanted == 1 ? 0 : (n - 1) * j / (wanted - 1);
    if (samples.empty() || samples.back() != k) samples.push_back(k);
  }
  const long long total = static_cast<long long>(samples.size()) + n;
  long long done = 0;
  const auto step = [&] { return !progress || progress(++done, total); };
  if (!samples.empty()) {
    TimelineReplay replay(f.scene, f.changes, f.trail);
    for (const long long k : samples) {
      const double t = frame_time(clip, k);
      if (!reached(replay, t, f.max_attempts)) stopped(replay, t);
      writer.add_palette_sample(draw(f, replay, render).rgba.data());
      if (!step()) return false;
    }
  }
  TimelineReplay replay(f.scene, f.changes, f.trail);
  render::CameraFollower follower;
  for (long long k = 0; k < n; ++k) {
    const double t = frame_time(clip, k);
    if (!reached(replay, t, f.max_attempts)) stopped(replay, t);
    writer.add(draw(f, replay, render, &follower, 1.0 / clip.fps).rgba.data());
    if (!step()) return false;
  }
  writer.finish();
  return true;
}

}  // namespace spinfold::record
