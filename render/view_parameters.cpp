#include "render/view_parameters.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "engine/number_rule.h"
#include "engine/overloaded.h"
#include "render/scene_builder.h"
#include "render/view_table.h"
#include "render/views/camera.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

std::string joined(const std::vector<std::string_view>& items, std::string_view last) {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) text += i + 1 == items.size() ? last : std::string_view(", ");
    text += items[i];
  }
  return text;
}

std::vector<std::string_view> layer_choices() {
  std::vector<std::string_view> names;
  for (const LayerInfo& l : kLayerTable) names.push_back(l.name);
  return names;
}

}  // namespace

std::span<const ViewParameter> view_parameters() {
  return kViewParameters;
}

std::optional<CameraMotion> parse_camera_motion(std::string_view name) {
  for (std::size_t i = 0; i < std::size(kCameraMotionNames); ++i)
    if (kCameraMotionNames[i] == name) return static_cast<CameraMotion>(i);
  return std::nullopt;
}

const ViewParameter& view_parameter(std::string_view name) {
  for (const ViewParameter& p : kViewParameters)
    if (p.name == name) return p;
  throw std::logic_error("no view parameter named " + std::string(name));
}

ParameterType parameter_type(const ViewParameter& p) {
  return std::visit(
      Overloaded{[](int ViewRequest::*) { return ParameterType::integer; },
                 [](double ViewRequest::*) { return ParameterType::number; },
                 [](std::optional<double> ViewRequest::*) { return ParameterType::number; },
                 [](std::optional<ViewKind> ViewRequest::*) { return ParameterType::enumeration; },
                 [](unsigned ViewRequest::*) { return ParameterType::list; },
                 [](CameraMotion ViewRequest::*) { return ParameterType::enumeration; }},
      p.member);
}

std::vector<std::string_view> choices(const ViewParameter& p) {
  switch (parameter_type(p)) {
    case ParameterType::enumeration: {
      if (std::holds_alternative<CameraMotion ViewRequest::*>(p.member))
        return {std::begin(kCameraMotionNames), std::end(kCameraMotionNames)};
      std::vector<std::string_view> names;
      for (const ViewInfo& v : views()) names.push_back(v.name);
      return names;
    }
    case ParameterType::list: return layer_choices();
    case ParameterType::integer:
    case ParameterType::number: break;
  }
  return {};
}

Range allowed_range(const ViewParameter& p, int max_image_side) {
  Range range = p.range;
  if (p.unit == "pixels") range.max = std::min(range.max, static_cast<double>(max_image_side));
  return range;
}

NumberRule number_rule(const ViewParameter& p, int max_image_side) {
  return {.whole = parameter_type(p) == ParameterType::integer,
          .range = allowed_range(p, max_image_side),
          .unit = p.unit};
}

std::optional<std::variant<double, std::string>> default_value(const ViewParameter& p) {
  const ViewRequest defaults;
  return std::visit(
      Overloaded{
          [&](int ViewRequest::*m) -> std::optional<std::variant<double, std::string>> {
            return static_cast<double>(defaults.*m);
          },
          [&](double ViewRequest::*m) -> std::optional<std::variant<double, std::string>> {
            return defaults.*m;
          },
          [&](std::optional<double> ViewRequest::*m) -> std::optional<std::variant<double, std::string>> {
            if (!(defaults.*m)) return std::nullopt;
            return *(defaults.*m);
          },
          [&](std::optional<ViewKind> ViewRequest::*m) -> std::optional<std::variant<double, std::string>> {
            if (!(defaults.*m)) return std::nullopt;
            return std::string(view_name(*(defaults.*m)));
          },
          [&](unsigned ViewRequest::*m) -> std::optional<std::variant<double, std::string>> {
            return layer_list(defaults.*m);
          },
          [&](CameraMotion ViewRequest::*m) -> std::optional<std::variant<double, std::string>> {
            return std::string(kCameraMotionNames[static_cast<int>(defaults.*m)]);
          }},
      p.member);
}

std::string default_layer_list() {
  return layer_list(default_layers());
}

std::string layer_list(unsigned layers) {
  std::string list;
  for (const LayerInfo& l : kLayerTable)
    if (layers & l.bit) {
      if (!list.empty()) list += ',';
      list += l.name;
    }
  return list;
}

std::string expectation(const ViewParameter& p, int max_image_side) {
  const ParameterType type = parameter_type(p);
  switch (type) {
    case ParameterType::integer:
    case ParameterType::number: return must_be(number_rule(p, max_image_side));
    case ParameterType::enumeration: return "must be " + joined(choices(p), " or ");
    case ParameterType::list: return "must be a comma-separated list of " + joined(choices(p), ", ");
  }
  return "must be text";
}

std::optional<std::string> set_parameter(ViewRequest& request, const ViewParameter& p,
                                         const GivenValue& value, int max_image_side) {
  const ParameterType type = parameter_type(p);
  if (type == ParameterType::integer || type == ParameterType::number) {
    const std::optional<double> x = std::holds_alternative<double>(value)
                                        ? std::optional(std::get<double>(value))
                                        : number_from_text(std::get<std::string>(value));
    if (!x || !allows(number_rule(p, max_image_side), *x)) return expectation(p, max_image_side);
    std::visit(Overloaded{[&](int ViewRequest::*m) { request.*m = static_cast<int>(*x); },
                          [&](double ViewRequest::*m) { request.*m = *x; },
                          [&](std::optional<double> ViewRequest::*m) { request.*m = *x; }, [](auto) {}},
               p.member);
    return std::nullopt;
  }
  if (!std::holds_alternative<std::string>(value)) return expectation(p);
  const std::string& text = std::get<std::string>(value);
  if (type == ParameterType::enumeration && std::holds_alternative<CameraMotion ViewRequest::*>(p.member)) {
    const std::optional<CameraMotion> motion = parse_camera_motion(text);
    if (!motion) return expectation(p);
    request.*std::get<CameraMotion ViewRequest::*>(p.member) = *motion;
    return std::nullopt;
  }
  if (type == ParameterType::enumeration) {
    const std::optional<ViewKind> kind = parse_view(text);
    if (!kind) return expectation(p);
    std::visit(Overloaded{[&](std::optional<ViewKind> ViewRequest::*m) { request.*m = *kind; }, [](auto) {}},
               p.member);
    return std::nullopt;
  }
  std::string unknown;
  const std::optional<unsigned> mask = parse_layers(text, &unknown);
  if (!mask) return "'" + unknown + "' is not one of " + joined(choices(p), ", ");
  std::visit(Overloaded{[&](unsigned ViewRequest::*m) { request.*m = *mask; }, [](auto) {}}, p.member);
  return std::nullopt;
}

std::optional<GivenValue> parameter_value(const ViewRequest& request, const ViewParameter& p) {
  return std::visit(
      Overloaded{
          [&](int ViewRequest::*m) -> std::optional<GivenValue> { return static_cast<double>(request.*m); },
          [&](double ViewRequest::*m) -> std::optional<GivenValue> { return request.*m; },
          [&](std::optional<double> ViewRequest::*m) -> std::optional<GivenValue> {
            if (!(request.*m)) return std::nullopt;
            return *(request.*m);
          },
          [&](std::optional<ViewKind> ViewRequest::*m) -> std::optional<GivenValue> {
            if (!(request.*m)) return std::nullopt;
            return std::string(view_name(*(request.*m)));
          },
          [&](unsigned ViewRequest::*m) -> std::optional<GivenValue> { return layer_list(request.*m); },
          [&](CameraMotion ViewRequest::*m) -> std::optional<GivenValue> {
            return std::string(kCameraMotionNames[static_cast<int>(request.*m)]);
          }},
      p.member);
}

// ---- the layer names (render/view.h), from the table ---------------------------------------------

namespace {
constexpr auto kLayerNames = [] {
  std::array<std::string_view, std::size(kLayerTable)> names{};
  for (std::size_t i = 0; i < names.size(); ++i) names[i] = kLayerTable[i].name;
  return names;
}();
}  // namespace

std::span<const std::string_view> layer_names() {
  return kLayerNames;
}

std::optional<unsigned> parse_layers(std::string_view list, std::string* unknown) {
  unsigned mask = 0;
  while (!list.empty()) {
    const std::size_t comma = list.find(',');
    const std::string_view item = list.substr(0, comma);
    bool found = item.empty();
    for (const LayerInfo& l : kLayerTable)
      if (l.name == item) mask |= l.bit, found = true;
    if (!found) {
      if (unknown) *unknown = std::string(item);
      return std::nullopt;
    }
    if (comma == std::string_view::npos) break;
    list.remove_prefix(comma + 1);
  }
  return mask;
}

// ---- resolving a request (the one place) --------------------------------------------------------

std::optional<std::string> view_refusal(const ViewRequest& request, SurfaceKind surface) {
  return view_unsupported_reason(request.view.value_or(default_view(surface)), surface);
}

ViewOptions view_options(const ViewRequest& request, const Surface& surface) {
  ViewOptions view;
  view.kind = request.view.value_or(default_view(surface.kind));
  if (const auto why = view_unsupported_reason(view.kind, surface.kind))
    throw ViewRefused("view", std::string(view_name(view.kind)), *why);
  view.width = request.width;
  view.height = request.height;
  view.layers = request.layers;
  if (request.shown_width) view.shown_width = static_cast<int>(std::lround(*request.shown_width));
  view.scale = request.scale * body_scale_length(view.kind, surface);
  return view;
}

void place_camera(ViewOptions& view, const ViewRequest& request, const Snapshot& snapshot, Picture picture) {
  const unsigned layers = view.layers;
  if (picture == Picture::figure) view.layers &= ~static_cast<unsigned>(kHud);
  aim_camera_at_body(view, snapshot);
  view.layers = layers;
  if (!request.yaw && !request.pitch && !request.distance) return;
  const ViewOptions aimed = view;
  if (request.yaw) view.yaw = *request.yaw;
  if (request.pitch) view.pitch = *request.pitch;
  if (request.distance) view.distance = *request.distance;
  // The viewer's own angles about the aimed target, which follows the bodies, can land on the
  // surface's dark side (the hyperboloid from under its sheet once a body moved across the bowl):
  // tilted up as little as brings it to the lit side, else the aimed camera.
  const ViewModel& model = view_model(view.kind);
  const auto lit = [&] { return model.on_lit_side(eye_of(model.camera(view))); };
  while (!lit() && view.pitch < 1.3) view.pitch = std::min(1.3, view.pitch + 0.05);
  if (!lit()) view = aimed;
}

ViewOptions resolve_view(const ViewRequest& request, const Snapshot& snapshot, Picture picture) {
  ViewOptions view = view_options(request, snapshot.surface);
  place_camera(view, request, snapshot, picture);
  return view;
}

}  // namespace spinfold::render
