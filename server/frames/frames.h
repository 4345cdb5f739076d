// Frames of a session, shared by the frame routes and the live stream: what a request asks to see,
// the ETag naming it, and the frame itself (rendered in the pool, encoded on the caller's thread,
// kept in the frame cache).
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "engine/surface.h"
#include "engine/trail.h"
#include "render/camera_follow.h"
#include "render/snapshot.h"
#include "render/view.h"
#include "render/view_parameters.h"
#include "server/frames/frame_cache.h"

namespace spinfold::server {

struct Limits;
struct QueryParam;
class RenderPool;
struct Session;
class Query;

// A live stream's camera (render::CameraFollower): its frames in the order they are placed, each
// the stream's clock after the last.
struct FollowedCamera {
  std::mutex mutex;
  render::CameraFollower follower;
  std::optional<std::chrono::steady_clock::time_point> last;
};

// What the picture shows (checked by the route table; the view against the surface by frame_request).
struct FrameRequest {
  render::ViewOptions view;                    // kind, width, height, layers; the rest is set per frame
  double scale = 0.25;                         // [surface radii per unit of e_A]
  std::optional<double> yaw, pitch, distance;  // absent: the camera is aimed at the body
  std::optional<double> trail;                 // [time] span of the trail; absent: the whole run
  render::CameraMotion motion = render::CameraMotion::steady;  // with `follow`: how it moves
  std::optional<int> jpeg_quality;                             // 1..100: a JPEG; absent: a PNG
  // A live stream's: the camera stays put (steady) or glides over the aim's jumps. A frame on its
  // way or held is made for this stream alone (never cached); the aimed frame is cached and shared.
  std::shared_ptr<FollowedCamera> follow;
  // frame.png and frame.jpg's `at` [time]: the run at this earlier time (0 ≤ at ≤ the session's t),
  // replayed from t = 0 through the timeline in at most `max_attempts` step attempts (the session's
  // own run, bit for bit: engine/timeline.h); absent: the state now.
  std::optional<double> at;
  std::uint64_t max_attempts = 0;
  bool still = false;  // with `follow`: the same state again (no time passes for the camera)
};

// The query parameters of a frame (width … trail: one per row of render::view_parameters(), a side
// at most limits.max_image_side), and the JPEG quality's.
std::vector<QueryParam> frame_params(const Limits& limits);
QueryParam quality_param();
// `at`: an earlier time of the run (a scrubber's picture).
QueryParam at_param();
// The query's `at` into `f` (limits.max_steps for the replay); 422 naming `at` past the session's
// time `t`.
void apply_at(const Query& q, FrameRequest& f, double t, long max_steps);

// The snapshot a frame of `f` draws of a run: the trail copied only when drawn (what the camera
// aims at depends on it, so the drag handles take theirs from here too).
render::Snapshot frame_snapshot(const Simulation& run, const Trail& trail, const FrameRequest& f);

// The view parameters of a frame request (its view as given).
render::ViewRequest view_request(const FrameRequest& f);
// Sets the view parameters the query gives (checked by the route table against frame_params), the
// others staying as they are in `f`; the view, when given none before, is the surface's own.
void apply_view_query(const Query& q, FrameRequest& f, SurfaceKind surface);

// From a query of frame_params (with quality when `jpeg`); ApiError 422 when the view cannot show
// the surface.
// `max_pixels`: the picture's width × height at most (limits.max_image_pixels for a raster frame; 0
// for none: a vector figure), else 422 naming `width`.
FrameRequest frame_request(const Query& q, SurfaceKind surface, bool jpeg, long long max_pixels);
void check_view(const FrameRequest& f, SurfaceKind surface, long long max_pixels);

// Names the session's state (state_tag) and every parameter of the picture: a weak ETag, since
// replicas on other CPUs render the same state within the golden frames' tolerance, not to the same
// bytes (on one CPU class: equal ETags, equal bytes).
std::string frame_etag(const std::string& id, const std::string& state, const FrameRequest& f);
// What every frame_etag of session `id` starts with (FrameCache::drop on the session's deletion).
std::string frame_etag_prefix(const std::string& id);
// Whether an If-None-Match value names this ETag (weak comparison, RFC 9110 §8.8.3.2; "*" or a list).
bool etag_matches(const std::string& if_none_match, const std::string& etag);

// The state a frame shows.
struct FrameInfo {
  std::uint64_t version = 0;  // Session::version
  double t = 0;               // [time]
  // A 3-D view's camera as drawn: yaw, pitch [rad], distance [surface radii] (the page orbits from it).
  std::optional<std::array<double, 3>> camera;
  bool on_way = false;  // a followed camera not yet at the aim (FrameRequest::follow)
};

// The frame of the session as it is now. Takes the session's lock only to read it; waits for the
// render (ApiError 503 when rendering is unavailable). `etag` gets the frame's ETag; `info`, when
// given, the state it shows.
FrameBytes session_frame(FrameCache& cache, RenderPool& renderer, const std::string& id, Session& s,
                         const FrameRequest& f, std::string& etag, FrameInfo* info = nullptr);

}  // namespace spinfold::server
