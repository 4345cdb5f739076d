#include "render/view.h"

#include <array>
#include <utility>

#include "render/view_table.h"
#include "render/views/view_model.h"

namespace spinfold::render {

namespace {

constexpr std::array<std::pair<std::string_view, unsigned>, 7> kLayers{{{"surface", kSurface},
                                                                        {"grid", kGrid},
                                                                        {"body", kBody},
                                                                        {"frame", kFrame},
                                                                        {"trail", kTrail},
                                                                        {"hud", kHud},
                                                                        {"actions", kActions}}};
constexpr auto kLayerNames = [] {
  std::array<std::string_view, kLayers.size()> names{};
  for (std::size_t i = 0; i < kLayers.size(); ++i) names[i] = kLayers[i].first;
  return names;
}();

}  // namespace

ViewKind default_view(SurfaceKind surface) {
  switch (surface) {
    case SurfaceKind::sphere: return ViewKind::sphere;
    case SurfaceKind::pseudosphere: return ViewKind::disk;
    case SurfaceKind::plane: return ViewKind::plane;
  }
  return ViewKind::sphere;
}

std::span<const std::string_view> layer_names() {
  return kLayerNames;
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

std::optional<unsigned> parse_layers(std::string_view list, std::string* unknown) {
  unsigned mask = 0;
  while (!list.empty()) {
    const std::size_t comma = list.find(',');
    const std::string_view item = list.substr(0, comma);
    bool found = item.empty();
    for (const auto& [n, bit] : kLayers)
      if (n == item) mask |= bit, found = true;
    if (!found) {
      if (unknown) *unknown = std::string(item);
      return std::nullopt;
    }
    if (comma == std::string_view::npos) break;
    list.remove_prefix(comma + 1);
  }
  return mask;
}

double body_scale_length(ViewKind view, const Surface& surface) {
  return view_model(view).body_scale_length(surface);
}

}  // namespace spinfold::render
