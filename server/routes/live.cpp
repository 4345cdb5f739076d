// The live view: one connection per viewer carrying frames as they happen (multipart/x-mixed-replace:
// an <img> shows it as is; the UI parses it to count and time frames). While the session plays or
// the viewer's camera moves, frames are JPEG (motion frames, a third of the bytes); kStillDelay after
// the last change a lossless PNG of the same state replaces the last one. Nothing is sent while
// nothing changes (a heartbeat part every kHeartbeat finds clients that left: the second write to
// a closed connection fails). A frame is rendered only when the client has taken the previous one,
// so a slow client gets fewer, newer frames and the server holds one frame per viewer at most.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <deque>
#include <future>
#include <thread>

#include "server/context.h"
#include "server/frames/frames.h"
#include "server/http/problem.h"
#include "server/routes/routes.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

namespace {

using Clock = std::chrono::steady_clock;

constexpr auto kStillDelay =
    std::chrono::milliseconds(70);  // motion stopped → lossless frame (≤ 150 ms on screen)
// While the session plays, a pause between its steps is not the motion stopping: a busy machine can
// space the player's ticks beyond kStillDelay, and a lossless frame then would only slow the
// stream. A playing run that stopped (its status) still gets its still frame after this.
constexpr auto kPlayingStillDelay = std::chrono::seconds(1);
constexpr auto kHeartbeat = std::chrono::seconds(5);  // a client gone is found within two
constexpr const char* kBoundary = "spinfold-frame";

// A viewer name: 1..64 of [A-Za-z0-9_-] (the client picks a random one).
std::string viewer_name(const Query& q) {
  const auto given = q.text("viewer");
  if (!given) throw bad(422, "Invalid value", "viewer", "", "is required: the name of the stream to steer");
  const std::string name = *given;
  const bool ok =
      !name.empty() && name.size() <= 64 &&
      name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-") ==
          std::string::npos;
  if (!ok) throw bad(422, "Invalid value", "viewer", name, "must be 1 to 64 letters, digits, '_' or '-'");
  return name;
}

// A frame asked for: rendered and encoded on its own thread while the stream writes the one before.
struct MadeFrame {
  FrameBytes bytes;
  FrameInfo info;
  bool motion = false;
};

// Frames in flight per stream: the next one renders while the last one is encoded and written, so
// one viewer gets render and encode in parallel (two cores), and the queue stays this short.
constexpr std::size_t kInFlight = 2;
// Failed frames in a row that end a stream (render unavailable: the client reconnects).
constexpr int kMaxFailedFrames = 3;

// What a stream has asked for and sent, and what it waits for.
struct LiveStream {
  std::string id;
  std::shared_ptr<Viewer> viewer;
  std::shared_ptr<void> slot;
  int motion_quality = 60;
  Clock::duration min_interval;  // 1/fps
  std::uint64_t asked_version = ~std::uint64_t{0}, asked_camera = ~std::uint64_t{0};
  bool still_due = false;  // the last frame asked for was a motion frame
  // The stream's camera glides over the aim's jumps (render/camera_follow.h); while it is on its
  // way (the last frame written says so) frames are asked for as if the session changed.
  std::shared_ptr<FollowedCamera> follow = std::make_shared<FollowedCamera>();
  bool gliding = false;
  Clock::time_point last_change, last_ask, last_write;
  std::deque<std::future<MadeFrame>> in_flight;  // in the order asked for
  std::uint64_t seq = 0;                         // frames written
  int failed = 0;                                // frames in a row whose render failed
  ServerContext* server = nullptr;
  ~LiveStream();
};

LiveStream::~LiveStream() {
  if (!server) return;
  const std::lock_guard lock(server->viewers_mutex);
  // Forget this stream's viewer, and any other whose stream is gone.
  for (auto it = server->viewers.begin(); it != server->viewers.end();)
    it = it->second.expired() || it->second.lock() == viewer ? server->viewers.erase(it) : std::next(it);
}

bool write_part(httplib::DataSink& sink, const char* type, const std::string& headers,
                const std::vector<std::uint8_t>& bytes) {
  char head[512];
  std::snprintf(head, sizeof head, "--%s\r\nContent-Type: %s\r\nContent-Length: %zu\r\n%s\r\n", kBoundary,
                type, bytes.size(), headers.c_str());
  return sink.write(head, std::strlen(head)) &&
         (bytes.empty() || sink.write(reinterpret_cast<const char*>(bytes.data()), bytes.size())) &&
         sink.write("\r\n", 2);
}

// One step of the stream: ask for a frame, write one, a heartbeat, or wait for the next change.
// False: stop.
bool live_step(ServerContext& server, LiveStream& live, httplib::DataSink& sink) {
  if (server.stopping) return false;
  const std::uint64_t seen = server.changes.generation();
  const auto s = server.sessions.find(live.id);
  if (!s) {
    sink.done();  // the session is gone: end the stream
    return true;
  }
  std::uint64_t version;
  bool playing;
  SurfaceKind surface;
  {
    const std::lock_guard lock(s->mutex);
    version = s->version;
    playing = s->playing;
    surface = s->run.scene.surface.kind;
  }
  FrameRequest f;
  std::uint64_t camera;
  {
    const std::lock_guard lock(live.viewer->mutex);
    f = live.viewer->request;
    camera = live.viewer->generation;
  }
  // The session changed surface under the viewer: its own view until the viewer picks another.
  if (render::view_unsupported_reason(f.view.kind, surface)) f.view.kind = render::default_view(surface);
  // A surface no view draws gets no frames (every kind has a view now; kept for the next kind).
  const bool drawable = !render::view_unsupported_reason(f.view.kind, surface);
  const auto now = Clock::now();
  const bool first = live.asked_version == ~std::uint64_t{0};
  const bool changed = version != live.asked_version || camera != live.asked_camera || live.gliding;
  const auto next_ask = live.last_ask + live.min_interval;  // paced to `fps`
  const bool still =
      !changed && live.still_due && now >= live.last_change + (playing ? kPlayingStillDelay : kStillDelay);
  if (drawable && ((changed && now >= next_ask) || still) && live.in_flight.size() < kInFlight) {
    if (changed) live.last_change = now;
    // Motion frames while things move; the first frame of a paused session is its still frame.
    const bool motion = changed && !(first && !playing);
    if (motion) f.jpeg_quality = live.motion_quality;
    f.follow = live.follow;
    f.still = !changed;    // the lossless copy of the last motion frame: the same camera
    live.gliding = false;  // until a frame on its way is written
    live.in_flight.push_back(std::async(std::launch::async, [&server, id = live.id, s, f, motion] {
      MadeFrame made{nullptr, {}, motion};
      std::string etag;
      made.bytes = session_frame(server.frames, server.renderer, id, *s, f, etag, &made.info);
      return made;
    }));
    live.asked_version = version;
    live.asked_camera = camera;
    live.still_due = motion;
    live.last_ask = now;
    return true;
  }
  if (!live.in_flight.empty()) {
    // The oldest frame, written when made; meanwhile, when the next one is due, ask for it first.
    auto& oldest = live.in_flight.front();
    const bool due = changed && live.in_flight.size() < kInFlight;
    if (due && oldest.wait_until(next_ask) != std::future_status::ready) return true;
    MadeFrame made;
    try {
      made = oldest.get();
      live.failed = 0;
    } catch (const std::exception&) {
      // A frame that failed is dropped and asked again: one can race a change of the session's
      // surface (its view read before, the surface at the render). Three in a row end the stream
      // (the client reconnects).
      live.in_flight.pop_front();
      if (++live.failed >= kMaxFailedFrames) throw;
      live.asked_version = ~std::uint64_t{0};  // ask again
      return true;
    }
    live.in_flight.pop_front();
    live.gliding = made.info.on_way;
    char camera_text[128] = "";
    if (const auto& c = made.info.camera)
      std::snprintf(camera_text, sizeof camera_text, "; yaw=%.9g; pitch=%.9g; distance=%.9g; glide=%d",
                    (*c)[0], (*c)[1], (*c)[2], made.info.on_way ? 1 : 0);
    char headers[384];
    std::snprintf(headers, sizeof headers, "X-Spinfold-Frame: seq=%llu; version=%llu; t=%.17g; kind=%s%s\r\n",
                  static_cast<unsigned long long>(++live.seq),
                  static_cast<unsigned long long>(made.info.version), made.info.t,
                  made.motion ? "motion" : "still", camera_text);
    if (!write_part(sink, made.motion ? "image/jpeg" : "image/png", headers, *made.bytes)) return false;
    live.last_write = Clock::now();
    return true;
  }
  if (changed) {
    std::this_thread::sleep_until(next_ask);
    return true;
  }
  if (now >= live.last_write + kHeartbeat) {
    if (!write_part(sink, "text/plain", "X-Spinfold-Heartbeat: 1\r\n", {})) return false;  // the client left?
    live.last_write = now;
  }
  const auto deadline = live.still_due ? live.last_change + (playing ? kPlayingStillDelay : kStillDelay)
                                       : live.last_write + kHeartbeat;
  server.changes.wait(seen, std::min(deadline, now + std::chrono::seconds(1)));  // and check `stopping`
  return true;
}

void get_live(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto s = find_session(server, call.id);
  auto live = std::make_shared<LiveStream>();
  live->id = call.id;
  live->viewer = std::make_shared<Viewer>();
  {
    const std::lock_guard lock(s->mutex);
    live->viewer->request =
        frame_request(call.query, s->run.scene.surface.kind, false, server.options.limits.max_image_pixels);
  }
  live->motion_quality = static_cast<int>(*call.query.integer("quality"));
  live->min_interval = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / *call.query.number("fps")));
  const std::string key = call.id + "/" + viewer_name(call.query);
  live->slot = open_stream(server, call.client);  // 429 over the server's or the client's limit
  {
    const std::lock_guard lock(server.viewers_mutex);
    const auto it = server.viewers.find(key);
    if (it != server.viewers.end() && !it->second.expired())
      throw bad(409, "Viewer in use", "viewer", key.substr(call.id.size() + 1),
                "another live stream of this session has this viewer name");
    server.viewers[key] = live->viewer;
    live->server = &server;
  }
  res.set_header("Cache-Control", "no-cache, no-store");
  res.set_chunked_content_provider(
      std::string("multipart/x-mixed-replace; boundary=") + kBoundary,
      [&server, live](std::size_t, httplib::DataSink& sink) {
        try {
          return live_step(server, *live, sink);
        } catch (const std::exception&) {
          return false;  // rendering failed: end the stream (the client reconnects)
        }
      });
}

// Merges the given parameters into the viewer's picture (absent ones stay as they are).
void patch_live(ServerContext& server, const Call& call, httplib::Response& res) {
  const auto s = find_session(server, call.id);
  const std::string name = viewer_name(call.query);
  std::shared_ptr<Viewer> viewer;
  {
    const std::lock_guard lock(server.viewers_mutex);
    if (const auto it = server.viewers.find(call.id + "/" + name); it != server.viewers.end())
      viewer = it->second.lock();
  }
  if (!viewer)
    throw bad(404, "Not found", "viewer", name, "no live stream of this session has this viewer name");
  SurfaceKind surface;
  {
    const std::lock_guard lock(s->mutex);
    surface = s->run.scene.surface.kind;
  }
  const Query& q = call.query;
  const std::lock_guard lock(viewer->mutex);
  FrameRequest f = viewer->request;
  apply_view_query(q, f, surface);
  if (q.text("aim")) f.yaw = f.pitch = f.distance = std::nullopt;
  check_view(f, surface, server.options.limits.max_image_pixels);  // 422, nothing changed
  viewer->request = f;
  ++viewer->generation;
  res.status = 204;
}

}  // namespace

std::vector<Route> live_routes(const Limits& limits) {
  const QueryParam viewer{.name = "viewer",
                          .type = ParamType::string,
                          .default_value = "default",
                          .description =
                              "the viewer's name, 1-64 of [A-Za-z0-9_-], unique per session: PATCH "
                              "…/live?viewer= steers this stream"};
  Route get{.method = "GET",
            .path = "/api/v1/sessions/{id}/live",
            .operation_id = "stream_live",
            .handler = get_live,
            .summary =
                "A live stream of frames (multipart/x-mixed-replace): JPEG while the session plays or the "
                "camera moves (an aimed 3-D camera glides over the aim's jumps), a PNG 70 ms after the last "
                "change, nothing while nothing changes; part header X-Spinfold-Frame: seq, version, t, kind "
                "(motion|still), and in a 3-D view the camera drawn: yaw, pitch, distance, glide (1: on its "
                "way to the aimed camera)",
            .query = frame_params(limits),
            .responses = {{200, "multipart/x-mixed-replace"},
                          {409, "another stream of this session has this viewer name"},
                          {422, "an invalid parameter, or a view that cannot show this surface"},
                          {429, "stream limit (of the server or the client); Retry-After"}}};
  get.query.push_back(quality_param());
  get.query.back().description = "the motion frames' JPEG quality (libjpeg-turbo, 4:2:0)";
  get.query.push_back({.name = "fps",
                       .type = ParamType::number,
                       .unit = "Hz",
                       .minimum = 1.0,
                       .maximum = 120.0,
                       .default_value = 60.0,
                       .description = "the most frames a second (a slow client gets fewer)"});
  get.query.push_back(viewer);

  Route patch{.method = "PATCH",
              .path = "/api/v1/sessions/{id}/live",
              .operation_id = "steer_live",
              .handler = patch_live,
              .summary =
                  "Steers a live stream: the frame parameters given replace the stream's (the others "
                  "stay); `aim` puts the camera back on the body",
              .query = frame_params(limits),
              .responses = {{204, "the stream shows the new picture from its next frame"},
                            {404, "no such session, or no live stream with this viewer name"},
                            {422, "an invalid parameter, or a view that cannot show this surface"}}};
  for (auto& p : patch.query) p.default_value.reset();  // absent: unchanged
  patch.query.push_back(viewer);
  patch.query.back().default_value.reset();
  patch.query.back().description = "the stream to steer (its GET's viewer)";
  patch.query.push_back(
      {.name = "aim",
       .type = ParamType::enumeration,
       .values = {"body"},
       .description = "body: aim the camera at the body again (drops yaw, pitch, distance)"});
  return {get, patch};
}

}  // namespace spinfold::server
