#include "render/view.h"

#include <array>
#include <utility>

#include "engine/scene_fields.h"
#include "render/view_table.h"
#include "render/views/view_model.h"

namespace spinfold::render {

ViewKind default_view(SurfaceKind surface) {
  // The table lists each surface's own view before the maps it shares with others.
  for (const ViewInfo& v : views())
    if (shows(v, surface)) return v.kind;
  return ViewKind::revolution;  // a kind the validator refuses
}

std::string joined_view_names(std::string_view separator) {
  std::string names;
  for (const ViewInfo& v : views())
    names += (names.empty() ? "" : std::string(separator)) + std::string(v.name);
  return names;
}

const ViewInfo& view_info(ViewKind view) {
  for (const ViewInfo& v : views())
    if (v.kind == view) return v;
  return views().front();
}

bool shows(const ViewInfo& v, SurfaceKind surface) {
  return (v.needs & offers_of(surface)) != 0;
}

std::optional<std::string> view_unsupported_reason(ViewKind view, SurfaceKind surface) {
  if (shows(view_info(view), surface)) return std::nullopt;
  std::string names;
  for (const ViewInfo& v : views())
    if (shows(v, surface)) names += (names.empty() ? "" : ", ") + std::string(v.name);
  if (names.empty()) return "no view draws a surface of kind " + std::string(enum_name(surface));
  return "the " + std::string(enum_name(surface)) + " is shown in these views: " + names;
}

std::optional<ViewKind> parse_view(std::string_view name) {
  for (const ViewInfo& v : views())
    if (v.name == name) return v.kind;
  return std::nullopt;
}

std::string_view view_name(ViewKind view) {
  return view_info(view).name;
}

double body_scale_length(ViewKind view, const Surface& surface) {
  return view_model(view).body_scale_length(surface);
}

}  // namespace spinfold::render
