// Frames: a session's state as a PNG (lossless) or a JPEG (motion frames: a third of the bytes),
// rendered in the render pool and cached by ETag (server/frames/frames.h); or as an SVG or PDF figure for a
// paper (render/figure.h), drawn without GL on the request's thread.
#include "server/frames/frames.h"

#include <cstdio>
#include <optional>

#include "codec/provenance.h"
#include "render/figure.h"
#include "render/jpeg_encoder.h"
#include "render/snapshot.h"
#include "server/context.h"
#include "server/http/problem.h"
#include "server/routes/routes.h"
#include "server/sessions/session_store.h"

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
    f = frame_request(call.query, s->run.scene.surface.kind, jpeg, server.options.limits.max_image_pixels);
    apply_at(call.query, f, s->run.state.t, server.options.limits.max_steps);
    etag = frame_etag(call.id, state_tag(*s), f);
    res.set_header("X-Spinfold-Provenance", provenance(*s));
  }
  res.set_header("Cache-Control", "no-cache");
  if (etag_matches(call.http.get_header_value("If-None-Match"), etag)) {
    res.set_header("ETag", etag);
    res.status = 304;
    return;
  }
  const FrameBytes frame =
      session_frame(server.frames, server.renderer, call.id, *s, f, etag);  // the state may have moved on
  res.set_header("ETag", etag);
  res.body.assign(frame->begin(), frame->end());
  res.set_header("Content-Type", jpeg ? "image/jpeg" : "image/png");
}

// frame.svg / frame.pdf: the same picture as a vector figure for a paper (render/figure.h), drawn
// on the calling thread (no GL, no render pool); the caption replaces the HUD.
void send_figure(ServerContext& server, const Call& call, httplib::Response& res,
                 render::FigureFormat format) {
  const auto s = find_session(server, call.id);
  FrameRequest f;
  std::string etag;
  std::optional<render::Snapshot> snapshot;
  render::FigureCaption caption;
  {
    const std::lock_guard lock(s->mutex);
    f = frame_request(call.query, s->run.scene.surface.kind, false, 0);  // a vector figure
    etag = frame_etag(call.id, state_tag(*s), f);
    std::string suffix(1, '-');  // the format in the ETag, before its closing quote
    suffix.append(render::figure_format_name(format));
    etag.insert(etag.size() - 1, suffix);
    res.set_header("X-Spinfold-Provenance", provenance(*s));
    if (!etag_matches(call.http.get_header_value("If-None-Match"), etag)) {
      snapshot = frame_snapshot(s->run, s->trail, f);
      const Scene& scene = s->run.scene;
      caption.title = scene.name.empty() ? std::string("Spinfold session ") : scene.name;
      if (scene.name.empty()) caption.title.append(call.id);
      caption.description = scene.description;
      char at[48];
      std::snprintf(at, sizeof at, "; t=%.17g; view=", s->run.state.t);
      caption.provenance = provenance(*s) + at + std::string(render::view_name(f.view.kind));
      for (const auto& [key, value] :
           picture_texts(scene, "", s->run.state.t, render::view_name(f.view.kind)))
        if (key == "Source") caption.metadata = value;
    }
  }
  res.set_header("Cache-Control", "no-cache");
  res.set_header("ETag", etag);
  if (!snapshot) {
    res.status = 304;
    return;
  }
  // The caption is below the figure: no HUD box for the camera to keep clear of.
  const render::ViewOptions view = render::resolve_view(view_request(f), *snapshot, render::Picture::figure);
  const std::vector<std::uint8_t> bytes =
      render::draw_figure(render::figure_page(*snapshot, view, caption), format);
  res.body.assign(bytes.begin(), bytes.end());
  res.set_header("Content-Type", std::string(render::figure_content_type(format)));
}

void get_frame(ServerContext& server, const Call& call, httplib::Response& res) {
  send_frame(server, call, res, false);
}

void get_frame_svg(ServerContext& server, const Call& call, httplib::Response& res) {
  send_figure(server, call, res, render::FigureFormat::svg);
}

void get_frame_pdf(ServerContext& server, const Call& call, httplib::Response& res) {
  send_figure(server, call, res, render::FigureFormat::pdf);
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
  png.query.push_back(at_param());
  Route jpeg = png;
  jpeg.path = "/api/v1/sessions/{id}/frame.jpg";
  jpeg.operation_id = "get_frame_jpeg";
  jpeg.handler = get_frame_jpeg;
  jpeg.summary =
      "The same frame as a JPEG (motion frames: a third of the PNG's bytes); ETag, If-None-Match → 304";
  jpeg.query.push_back(quality_param());
  jpeg.responses.front() = {200, "image/jpeg"};
  Route svg = png;
  svg.query.pop_back();  // `at`: the raster frames' (a scrubber's)
  svg.path = "/api/v1/sessions/{id}/frame.svg";
  svg.operation_id = "get_frame_svg";
  svg.handler = get_frame_svg;
  svg.summary =
      "The same picture as a vector figure for a paper (SVG): outline, grid, labels or scale bar, legend, "
      "a caption with the provenance instead of the HUD; ETag, If-None-Match → 304";
  svg.responses = {{200, "image/svg+xml"},
                   {304, "unchanged (If-None-Match)"},
                   {422, "an invalid parameter, or a view that cannot show this surface"}};
  Route pdf = svg;
  pdf.path = "/api/v1/sessions/{id}/frame.pdf";
  pdf.operation_id = "get_frame_pdf";
  pdf.handler = get_frame_pdf;
  pdf.summary = "The vector figure as a PDF (as frame.svg); ETag, If-None-Match → 304";
  pdf.responses.front() = {200, "application/pdf"};
  return {png, jpeg, svg, pdf};
}

}  // namespace spinfold::server
