// Direct manipulation (render/drag.h): where a frame draws the main body's drag handles, and what a
// drop at a pixel of that frame sets of the scene's initial state. The page sends the answer back
// as it sends its form, in the session's PATCH: a drop is a restart like any edit, refused alike.
#include "render/drag.h"

#include <optional>
#include <string>
#include <string_view>

#include "engine/number_text.h"
#include "engine/readout.h"
#include "engine/scene_fields.h"
#include "render/snapshot.h"
#include "render/view_parameters.h"
#include "server/context.h"
#include "server/frames/frames.h"
#include "server/http/problem.h"
#include "server/routes/routes.h"
#include "server/sessions/session.h"

// After Eigen: httplib.h pulls in <resolv.h>, whose `_res` macro breaks Eigen's parameter names.
#include <httplib.h>

namespace spinfold::server {

namespace {

// What the frame of this query shows now: the snapshot its camera was placed on, the camera, and
// the main body's place.
struct DragFrame {
  render::Snapshot snapshot;
  render::ViewOptions view;
  render::BodyPlace body;
  std::optional<Scene> scene;  // with_scene: the parameters in force (a drop keeps their start's motion)
  double t = 0.0;
  std::uint64_t version = 0;
};

DragFrame drag_frame(ServerContext& server, const Call& call, bool with_scene) {
  const auto s = find_session(server, call.id);
  DragFrame d;
  FrameRequest f;
  {
    const std::lock_guard lock(s->mutex);
    f = frame_request(call.query, s->run.scene.surface.kind, false, server.options.limits.max_image_pixels);
    d.snapshot = frame_snapshot(s->run, s->trail, f);  // the frame's own: the camera aims at it
    d.body = render::body_place(readout(s->run));
    if (with_scene) d.scene = s->run.scene;
    d.t = s->run.state.t;
    d.version = s->version;
  }
  if (const auto why = render::drag_unsupported_reason(d.snapshot.surface))
    throw bad(422, "Invalid value", "surface.kind", std::string(enum_name(d.snapshot.surface.kind)), *why);
  d.view = render::resolve_view(view_request(f), d.snapshot);
  return d;
}

// A field of the scene's initial state into its JSON: "X.1" is component 1 of the array X.
void put(nlohmann::ordered_json& object, std::string_view name, double value) {
  const std::size_t dot = name.find('.');
  if (dot == std::string_view::npos) {
    object[std::string(name)] = value;
    return;
  }
  nlohmann::ordered_json& array = object[std::string(name.substr(0, dot))];
  array[std::stoul(std::string(name.substr(dot + 1)))] = value;
}

nlohmann::ordered_json point(const glm::dvec2& p) {
  return {{"x", p.x}, {"y", p.y}};
}

void get_handles(ServerContext& server, const Call& call, httplib::Response& res) {
  const DragFrame d = drag_frame(server, call, false);
  const auto handles = render::drag_handles(d.snapshot, d.view, d.body);
  nlohmann::ordered_json out = {{"t", d.t}, {"version", d.version}};
  out["body"] = handles ? point(handles->body) : nlohmann::ordered_json(nullptr);
  out["arrow"] = handles && handles->arrow ? point(*handles->arrow) : nlohmann::ordered_json(nullptr);
  nlohmann::ordered_json place = nlohmann::ordered_json::object();
  for (const auto& [name, value] : render::place_fields(d.snapshot.surface, d.body)) put(place, name, value);
  place["speed"] = d.body.speed;
  place["heading"] =
      d.body.heading ? nlohmann::ordered_json(*d.body.heading) : nlohmann::ordered_json(nullptr);
  out["place"] = place;
  res.set_header("Cache-Control", "no-store");
  send_json(res, out);
}

void get_drop(ServerContext& server, const Call& call, httplib::Response& res) {
  const DragFrame d = drag_frame(server, call, true);
  const auto x = call.query.number("x"), y = call.query.number("y");
  if (!x)
    throw bad(422, "Invalid value", "x", "null",
              "is required: the pixel's column from the frame's left [pixels]");
  if (!y)
    throw bad(422, "Invalid value", "y", "null",
              "is required: the pixel's row from the frame's top [pixels]");
  if (*x > d.view.width)
    throw bad(422, "Invalid value", "x", shortest(*x), "must be <= width = " + std::to_string(d.view.width));
  if (*y > d.view.height)
    throw bad(422, "Invalid value", "y", shortest(*y),
              "must be <= height = " + std::to_string(d.view.height));
  const glm::dvec2 pixel(*x, *y);
  // The motion the run starts with (its t = 0 with the parameters in force), outside the lock.
  const render::StartMotion start = render::start_motion(readout(start_simulation(*d.scene)));
  render::InitialFields fields;
  const bool arrow = *call.query.text("handle") == "arrow";
  if (!arrow) {
    const auto dropped = render::body_drop_at_pixel(d.snapshot, d.view, pixel, d.body, start);
    if (!dropped)
      throw bad(422, "Invalid value", "x", shortest(*x),
                "shows no part of the surface (the pixel (" + shortest(*x) + ", " + shortest(*y) +
                    ") of this frame): drop the body on the surface");
    fields = *dropped;
  } else {
    const auto velocity = render::velocity_at_pixel(d.snapshot, d.view, pixel, d.body);
    if (!velocity)
      throw bad(422, "Invalid value", "x", shortest(*x),
                "cannot set a velocity here: the body is seen edge-on (its tangent plane is drawn as a "
                "line); turn the view first");
    fields = render::arrow_drop_fields(d.snapshot.surface, d.body, velocity->first, velocity->second, start);
  }
  nlohmann::ordered_json initial = nlohmann::ordered_json::object();
  for (const auto& [name, value] : fields) put(initial, name, value);
  res.set_header("Cache-Control", "no-store");
  send_json(res, {{"initial", initial},
                  {"text", render::drop_text(fields, arrow)},
                  {"plain", render::drop_plain_text(fields, arrow)}});
}

}  // namespace

std::vector<Route> drag_routes(const Limits& limits) {
  Route handles{.method = "GET",
                .path = "/api/v1/sessions/{id}/handles",
                .operation_id = "get_drag_handles",
                .handler = get_handles,
                .summary =
                    "Where the frame of these view parameters draws the main body and the tip of its "
                    "velocity arrow (null where it does not), and its place and velocity now",
                .query = frame_params(limits),
                .responses = {{200,
                               "{\"t\", \"version\", \"body\": {\"x\", \"y\"} | null, \"arrow\": {\"x\", "
                               "\"y\"} | null, \"place\": {\"r\" or \"u\", \"phi\", \"speed\", \"heading\"}} "
                               "[pixels from the frame's top left]"},
                              {422, "an invalid parameter, or a view that cannot show this surface"}}};
  Route drop = handles;
  drop.path = "/api/v1/sessions/{id}/drop";
  drop.operation_id = "get_drop";
  drop.handler = get_drop;
  drop.summary =
      "What a drop at pixel (x, y) of that frame sets: the body's start there (handle=body), or the velocity "
      "whose arrow ends there, from where the body is (handle=arrow); send `initial` in the session's PATCH";
  for (const char* axis : {"x", "y"})
    drop.query.push_back(
        {.name = axis,
         .type = ParamType::number,
         .unit = "pixels",
         .minimum = 0.0,
         .description = std::string("the drop's ") +
                        (axis[0] == 'x' ? "column from the frame's left" : "row from its top") +
                        " (required; at most the frame's width or height)"});
  drop.query.push_back({.name = "handle",
                        .type = ParamType::enumeration,
                        .values = {"body", "arrow"},
                        .default_value = std::string("body"),
                        .description = "what was dragged: the body (its start) or its velocity arrow"});
  drop.responses = {
      {200,
       "{\"initial\": {the fields a drop sets}, \"text\": what it changes (\"r = 1.2, phi = "
       "0.5\", \"speed = 0.75, heading = 90°\"), \"plain\": the same for a class, no coordinate "
       "names (\"start here, 1.2 from the pole\")}"},
      {422, "an invalid parameter, a pixel off the surface, or a body seen edge-on"}};
  return {handles, drop};
}

}  // namespace spinfold::server
