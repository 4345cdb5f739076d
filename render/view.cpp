#include "render/view.h"

#include <array>
#include <utility>

#include "engine/scene_fields.h"
#include "render/view_table.h"
#include "render/views/view_model.h"

namespace spinfold::render {

ViewKind default_view(SurfaceKind surface) {
  switch (surface) {
    case SurfaceKind::sphere: return ViewKind::sphere;
    case SurfaceKind::pseudosphere: return ViewKind::disk;
    case SurfaceKind::plane: return ViewKind::plane;
    default: return ViewKind::sphere;  // no view draws it yet: view_unsupported_reason says so
  }
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

namespace {
bool shows(const ViewInfo& v, SurfaceKind surface) {
  switch (surface) {
    case SurfaceKind::sphere: return v.sphere;
    case SurfaceKind::pseudosphere: return v.pseudosphere;
    case SurfaceKind::plane: return v.plane;
    default: return false;
  }
}
}  // namespace

std::optional<std::string> view_unsupported_reason(ViewKind view, SurfaceKind surface) {
  if (shows(view_info(view), surface)) return std::nullopt;
  if (curvature_varies(surface))
    return "no view draws the " + std::string(enum_name(surface)) +
           " yet (its 3-D and chart views are the next step of the surfaces whose curvature varies): "
           "simulate, sweep, work-precision, Python and the API's trajectory run it";
  std::string names;
  for (const ViewInfo& v : views())
    if (shows(v, surface)) names += (names.empty() ? "" : ", ") + std::string(v.name);
  const char* what = surface == SurfaceKind::sphere         ? "the sphere"
                     : surface == SurfaceKind::pseudosphere ? "the pseudosphere"
                                                            : "the plane";
  return std::string(what) + " is shown in these views: " + names;
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
