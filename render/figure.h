// A frame as a vector figure for a paper (SVG or PDF, render/figure_page.h): the scene that
// build_scene makes for the GL frame, projected by its own camera, drawn as paths: the surface's
// fill and outline (the silhouette in the 3-D views, the boundary circle or line in the flat ones),
// the grid, the trails, the bodies' ellipses and frame arrows; in the flat views labels on the
// geodesic circles ("r = 0.5 R") or a scale bar in lengths; and beneath the picture, instead of the
// HUD, a caption (scene, t, integrator, energy error, provenance) beside a legend of the bodies.
// No GL: the 3-D views' hidden lines are found in a depth buffer rasterised in software from the
// surface's own mesh.
#pragma once

#include <string>
#include <vector>

#include "render/figure_page.h"
#include "render/scene_builder.h"
#include "render/snapshot.h"
#include "render/view.h"
#include "render/views/view_model.h"

namespace spinfold::render {

// The text under the picture.
struct FigureCaption {
  std::string title;        // the scene's name (bold; the file's title)
  std::string description;  // the scene's one line
  std::string provenance;   // one line (codec/provenance.h's provenance_header)
  std::string metadata;     // written into the file (the provenance JSON)
};

// The page of the frame `view` shows of `snapshot`: view.width × view.height pixels become a
// picture of kPointsPerPixel points each, the caption beneath: the title, the snapshot's read-out
// (its HUD lines: t, energy error, integrator, …; the action lines with the actions layer), what
// the grid shows, and the provenance. The HUD is not drawn over the picture: the hud layer asks
// for the caption (without it the page is the picture and the legend); the camera is the one
// `view` holds (aim it first, as for a frame, with the hud layer off: there is no box to clear).
FigurePage figure_page(const Snapshot& snapshot, const ViewOptions& view, const FigureCaption& caption);

// Whether the view labels its geodesic circles (disk, Klein, half-plane) or shows a scale bar
// (plane, conformal); the 3-D views do neither.
// (The view says which: ViewModel::figure_scale.)
FigureScale figure_scale(ViewKind view);

// The scale bar's length: 1, 2 or 5 × 10ᵏ lengths, the largest not over `most` [length].
double scale_bar_length(double most);

// A geodesic circle's label: "r = 0.5 R", or on the sphere's stereographic disk, where the grid's
// circles are parallels every 15°, "r = πR/12".
std::string circle_label(double r_over_R, bool sphere);

}  // namespace spinfold::render
