#include "render/view.h"

#include <array>
#include <utility>

namespace spinfold::render {

namespace {

constexpr std::array<ViewInfo, 8> kViews{{
    {"sphere", ViewKind::sphere, true, true, false, false, "3-D sphere",
     "the sphere in space, seen by an orbiting camera"},
    {"disk", ViewKind::disk, false, true, true, false, "disk (flat map)",
     "the Poincaré disk (H²) or the stereographic plane (S²): angles true, geodesics circular arcs"},
    {"hyperboloid", ViewKind::hyperboloid, true, false, true, false, "3-D hyperboloid",
     "H² as the upper sheet of the hyperboloid x₃² − x₁² − x₂² = R² in Minkowski space"},
    {"klein", ViewKind::klein, false, false, true, false, "Klein disk (straight geodesics)",
     "the Beltrami–Klein disk: geodesics are straight chords, angles and shapes are not true"},
    {"halfplane", ViewKind::halfplane, false, false, true, false, "upper half-plane",
     "the Poincaré upper half-plane: angles true, geodesics semicircles on the boundary or vertical lines"},
    {"tractricoid", ViewKind::tractricoid, true, false, true, false, "3-D pseudosphere (tractricoid)",
     "Beltrami's surface of curvature −1/R² in space: a strip of H² wrapped round its axis, ending at its "
     "rim"},
    {"plane", ViewKind::plane, false, false, false, true, "flat plane",
     "the Euclidean plane, following the body"},
    {"conformal", ViewKind::conformal, false, true, true, true, "conformal (continuous in K)",
     "any curvature K in one flat map, angles true: stereographic (K > 0), the plane itself (K = 0), the "
     "Poincaré disk (K < 0), in lengths and following the body, so the picture changes continuously with K"},
}};

}  // namespace

ViewKind default_view(SurfaceKind surface) {
  switch (surface) {
    case SurfaceKind::sphere: return ViewKind::sphere;
    case SurfaceKind::pseudosphere: return ViewKind::disk;
    case SurfaceKind::plane: return ViewKind::plane;
  }
  return ViewKind::sphere;
}

std::span<const ViewInfo> views() {
  return kViews;
}

std::string joined_view_names(std::string_view separator) {
  std::string names;
  for (const ViewInfo& v : kViews)
    names += (names.empty() ? "" : std::string(separator)) + std::string(v.name);
  return names;
}

const ViewInfo& view_info(ViewKind view) {
  for (const ViewInfo& v : kViews)
    if (v.kind == view) return v;
  return kViews.front();
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
  for (const ViewInfo& v : kViews)
    if (shows(v, surface)) names += (names.empty() ? "" : ", ") + std::string(v.name);
  const char* what = surface == SurfaceKind::sphere         ? "the sphere"
                     : surface == SurfaceKind::pseudosphere ? "the pseudosphere"
                                                            : "the plane";
  return std::string(what) + " is shown in these views: " + names;
}

std::optional<ViewKind> parse_view(std::string_view name) {
  for (const ViewInfo& v : kViews)
    if (v.name == name) return v.kind;
  return std::nullopt;
}

std::string_view view_name(ViewKind view) {
  return view_info(view).name;
}

double body_scale_length(ViewKind view, const Surface& surface) {
  return view == ViewKind::conformal ? 1.0 : surface.radius;
}

}  // namespace spinfold::render
