#include "render/view.h"

#include <array>
#include <utility>

#include "render/view_table.h"
#include "render/views/view_model.h"

namespace spinfold::render {

ViewKind default_view(SurfaceKind surface) {
  switch (surface) {
    case SurfaceKind::sphere: return ViewKind::sphere;
    case SurfaceKind::pseudosphere: return ViewKind::disk;
    case SurfaceKind::plane: return ViewKind::plane;
  }
  return ViewKind::sphere;
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
  }
  return false;
}
}  // namespace

std::optional<std::string> view_unsupported_reason(ViewKind view, SurfaceKind surface) {
  if (shows(view_info(view), surface)) return std::nullopt;
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
