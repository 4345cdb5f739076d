// Frames: a session's state as a PNG (lossless) or a JPEG (motion frames: a third of the bytes),
// rendered in the render pool and cached by ETag (server/frames.h).
#include "render/jpeg_encoder.h"
#include "server/context.h"
#include "server/frames.h"
#include "server/problem.h"
#include "server/route_table.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

namespace {

void send_frame(ServerContext& server, const Call& call, httplib::Response& res, bool jpeg) {
  const auto s = find_session(server, call.id);
  FrameRequest f;
  std::string etag;
  {
    const std::lock_guard lock(s->mutex);
    f = frame_request(call.query, s->run.scene.surface.kind, jpeg);
    etag = frame_etag(call.id, state_tag(*s), f);
    res.set_header("X-Spinfold-Provenance", provenance(*s));
  }
  res.set_header("Cache-Control", "no-cache");
  if (etag_matches(call.http.get_header_value("If-None-Match"), etag)) {
    res.set_header("ETag", etag);
    res.status = 304;
    return;
  }
  const FrameBytes frame = session_frame(server, call.id, *s, f, etag);  // the state may have moved on
  res.set_header("ETag", etag);
  res.body.assign(frame->begin(), frame->end());
  res.set_header("Content-Type", jpeg ? "image/jpeg" : "image/png");
}

void get_frame(ServerContext& server, const Call& call, httplib::Response& res) {
  send_frame(server, call, res, false);
}

void get_frame_jpeg(ServerContext& server, const Call& call, httplib::Response& res) {
  send_frame(server, call, res, true);
}

}  // namespace

std::vector<Route> frame_routes(const Limits& limits) {
  Route png{.method = "GET",
            .path = "/api/v1/sessions/{id}/frame.png",
            .operation_id = "get_frame",
            .handler = get_frame,
            .summary = "A PNG frame of the session's state; ETag, If-None-Match → 304",
            .query = frame_params(limits),
            .responses = {{200, "image/png"},
                          {304, "unchanged (If-None-Match)"},
                          {422, "an invalid parameter, or a view that cannot show this surface"},
                          {503, "rendering unavailable; Retry-After"}}};
  Route jpeg = png;
  jpeg.path = "/api/v1/sessions/{id}/frame.jpg";
  jpeg.operation_id = "get_frame_jpeg";
  jpeg.handler = get_frame_jpeg;
  jpeg.summary =
      "The same frame as a JPEG (motion frames: a third of the PNG's bytes); ETag, If-None-Match → 304";
  jpeg.query.push_back(quality_param());
  jpeg.responses.front() = {200, "image/jpeg"};
  return {png, jpeg};
}

}  // namespace spinfold::server
