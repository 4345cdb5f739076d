#include "render/view_table.h"

#include <array>
#include <iterator>

#include "render/views/view_model.h"

namespace spinfold::render {

// The views' instances, one per file in render/views/.
const ViewModel& sphere_view();
const ViewModel& disk_view();
const ViewModel& hyperboloid_view();
const ViewModel& klein_view();
const ViewModel& halfplane_view();
const ViewModel& tractricoid_view();
const ViewModel& plane_view();
const ViewModel& conformal_view();

const ViewModel& revolution_view();
const ViewModel& chart_view();
const ViewModel& formula_view();

namespace {

// What a surface must offer for each view to show it: S², H² and the plane's own models.
constexpr unsigned kS = offer_bit(Offer::positive_curvature), kH = offer_bit(Offer::negative_curvature),
                   kE = offer_bit(Offer::zero_curvature);

// name, kind, three_d, what a surface it shows offers (one of), title, description; implementation. A
// surface's default view is the first row that shows it (render/view.h's default_view).
constexpr ViewRow kViews[] = {
    {{"sphere", ViewKind::sphere, true, kS, "3-D sphere", "the sphere in space, seen by an orbiting camera"},
     &sphere_view},
    {{"disk", ViewKind::disk, false, kS | kH, "disk (flat map)",
      "the Poincaré disk (H²) or the stereographic plane (S²): angles true, geodesics circular arcs"},
     &disk_view},
    {{"hyperboloid", ViewKind::hyperboloid, true, kH, "3-D hyperboloid",
      "H² as the upper sheet of the hyperboloid x₃² − x₁² − x₂² = R² in Minkowski space"},
     &hyperboloid_view},
    {{"klein", ViewKind::klein, false, kH, "Klein disk (straight geodesics)",
      "the Beltrami–Klein disk: geodesics are straight chords, angles and shapes are not true"},
     &klein_view},
    {{"halfplane", ViewKind::halfplane, false, kH, "upper half-plane",
      "the Poincaré upper half-plane: angles true, geodesics semicircles on the boundary or vertical lines"},
     &halfplane_view},
    {{"tractricoid", ViewKind::tractricoid, true, kH, "3-D pseudosphere (tractricoid)",
      "Beltrami's surface of curvature −1/R² in space: a strip of H² wrapped round its axis, ending at its "
      "rim"},
     &tractricoid_view},
    {{"plane", ViewKind::plane, false, kE, "flat plane", "the Euclidean plane, following the body"},
     &plane_view},
    {{"conformal", ViewKind::conformal, false, kS | kH | kE, "conformal (continuous in K)",
      "any curvature K in one flat map, angles true: stereographic (K > 0), the plane itself (K = 0), the "
      "Poincaré disk (K < 0), in lengths and following the body, so the picture changes continuously with K"},
     &conformal_view},
    {{"revolution", ViewKind::revolution, true, offer_bit(Offer::profile_chart), "3-D surface of revolution",
      "the torus, spheroid, bump or catenoid in space, with its meridians and parallels, its K = 0 "
      "circles marked, and the curvature layer colouring it by K"},
     &revolution_view},
    {{"chart", ViewKind::chart, false, offer_bit(Offer::profile_chart), "chart (u, φ) with K",
      "the surface's chart unrolled: φ across, u down, the background coloured by the curvature K (warm "
      "> 0, cool < 0) with the K = 0 parallels dark; lengths and angles are not true"},
     &chart_view},
    {{"formula", ViewKind::formula, true, offer_bit(Offer::formula), "3-D surface F = 0",
      "a surface given by a formula in space, its drawn box meshed and shaded by the exact normal, with "
      "the level curves of x, y and z as its grid, its K = 0 curves marked, and the curvature layer "
      "colouring it by K"},
     &formula_view},
};

constexpr auto kInfos = [] {
  std::array<ViewInfo, std::size(kViews)> infos{};
  for (std::size_t i = 0; i < std::size(kViews); ++i) infos[i] = kViews[i].info;
  return infos;
}();

}  // namespace

std::span<const ViewRow> view_table() {
  return kViews;
}

std::span<const ViewInfo> views() {
  return kInfos;
}

const ViewModel& view_model(ViewKind view) {
  for (const ViewRow& row : kViews)
    if (row.info.kind == view) return row.model();
  return kViews[0].model();
}

}  // namespace spinfold::render
