#include "render/view.h"

#include <array>
#include <utility>

namespace spinfold::render {

namespace {

constexpr std::array<std::pair<std::string_view, ViewKind>, 4> kViews{{{"sphere", ViewKind::sphere},
                                                                       {"hyperboloid", ViewKind::hyperboloid},
                                                                       {"disk", ViewKind::disk},
                                                                       {"plane", ViewKind::plane}}};
constexpr std::array<std::pair<std::string_view, unsigned>, 6> kLayers{{{"surface", kSurface},
                                                                        {"grid", kGrid},
                                                                        {"body", kBody},
                                                                        {"frame", kFrame},
                                                                        {"trail", kTrail},
                                                                        {"hud", kHud}}};

}  // namespace

ViewKind default_view(SurfaceKind surface) {
  switch (surface) {
    case SurfaceKind::sphere: return ViewKind::sphere;
    case SurfaceKind::pseudosphere: return ViewKind::disk;
    case SurfaceKind::plane: return ViewKind::plane;
  }
  return ViewKind::sphere;
}

std::optional<std::string> view_unsupported_reason(ViewKind view, SurfaceKind surface) {
  const bool ok = (view == ViewKind::sphere && surface == SurfaceKind::sphere) ||
                  (view == ViewKind::hyperboloid && surface == SurfaceKind::pseudosphere) ||
                  (view == ViewKind::disk && surface != SurfaceKind::plane) ||
                  (view == ViewKind::plane && surface == SurfaceKind::plane);
  if (ok) return std::nullopt;
  switch (surface) {
    case SurfaceKind::sphere: return "the sphere is shown in the sphere or disk (stereographic) view";
    case SurfaceKind::pseudosphere:
      return "the pseudosphere is shown in the hyperboloid or disk (Poincare) view";
    case SurfaceKind::plane: return "the plane is shown in the plane view";
  }
  return "unsupported view";
}

std::optional<ViewKind> parse_view(std::string_view name) {
  for (const auto& [n, v] : kViews)
    if (n == name) return v;
  return std::nullopt;
}

std::string_view view_name(ViewKind view) {
  for (const auto& [n, v] : kViews)
    if (v == view) return n;
  return "sphere";
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

}  // namespace spinfold::render
