// A clip: the frames of a recording and what each shows. Frame k shows simulated time
// t_k = t_start + k·speed/fps, for k = 0 … n−1 with t_k < t_end, so n = ⌈(t_end − t_start)·fps/speed⌉
// frames play for n/fps seconds. The run is replayed in a copy from t = 0 through the timeline's
// parameter changes by the engine's TimelineReplay (engine/timeline.h: the same run, bit for bit, as
// the session or `spinfold render`), and each
// frame is drawn like a frame of the session: every body, legend, HUD and trail. A camera aimed at
// the bodies follows them as the live view's does (render/camera_follow.h: it glides over the aim's
// jumps, 1/fps of the file between frames).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "engine/number_rule.h"
#include "engine/timeline.h"
#include "engine/trail.h"
#include "engine/validation.h"
#include "record/recorder.h"
#include "render/renderer.h"
#include "render/snapshot.h"
#include "render/view.h"
#include "render/view_parameters.h"

namespace spinfold::record {

struct Clip {
  double t_start = 0.0;  // [time] the first frame's simulated time, ≥ 0
  double t_end = 10.0;   // [time] the window's end (excluded), > t_start
  double fps = 30.0;     // frames per second of the file, from kMinFps to kMaxFps
  double speed = 1.0;    // simulated time per second of the file, > 0
};

inline constexpr double kMaxFps = 120.0;
// A GIF's delay is 16-bit hundredths of a second (at most 655 s a frame) and FFmpeg's frame rate a
// fraction of integers: 0.01 frames/s (100 s a frame) keeps both exact.
inline constexpr double kMinFps = 0.01;
// fps as a rule (engine/number_rule.h): "must be a number from 0.01 to 120 [frames/s]".
inline constexpr NumberRule kFpsRule{.range = {.min = kMinFps, .max = kMaxFps}, .unit = "frames/s"};
// Frames in one clip, whoever records it (the server's limits.max_recording_frames is lower): the
// count is computed in double and checked against this before it becomes an integer.
inline constexpr double kMaxClipFrames = 1e7;

// Refusals of a clip, each naming the field ("t_start", "t_end", "fps", "speed"), value and reason;
// among them a window of more than kMaxClipFrames frames, which names t_end when the window is too
// long at speed 1 and speed otherwise (a slow speed is what makes it long).
std::vector<FieldError> clip_errors(const Clip& clip);
// n = ⌈(t_end − t_start)·fps/speed⌉, from 1 to kMaxClipFrames; std::logic_error for a clip with
// errors (never a conversion out of range).
long long frame_count(const Clip& clip);
// t_k = t_start + k·speed/fps [time].
double frame_time(const Clip& clip, long long k);

// What every frame of a clip shows, and how.
struct ClipFrames {
  Scene scene{};                                     // the parameters at t = 0
  std::vector<ParameterChange> changes{};            // the timeline after t = 0
  Trail trail{};                                     // the trail's spacing and cap (empty of points)
  render::ViewOptions view{};                        // kind, size, layers, scale [length]
  std::optional<double> yaw{}, pitch{}, distance{};  // absent: aimed at the body in every frame
  render::CameraMotion motion = render::CameraMotion::steady;  // aimed: how it moves (camera_follow.h)
  std::optional<double> trail_span{};         // [time] the trail's span; absent: the whole run
  std::uint64_t max_attempts = kNoStepLimit;  // step attempts per frame
};

// Draws a snapshot in a view: the caller's renderer (its own, or the server's render pool).
using RenderFrame = std::function<render::Image(render::Snapshot, const render::ViewOptions&)>;
// Told after each frame drawn (palette samples included): frames done, frames in all. Returns false
// to cancel.
using Progress = std::function<bool(long long done, long long total)>;

// Records the clip into `writer` and finishes it; false when cancelled (the file is then
// incomplete). RecordError with the reason when the run stops before the end, or the writer fails.
bool record_clip(const Clip& clip, const ClipFrames& frames, ClipWriter& writer, const RenderFrame& render,
                 const Progress& progress = {});

}  // namespace spinfold::record
