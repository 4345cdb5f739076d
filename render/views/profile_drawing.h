// What the two pictures of a surface of revolution share (the revolution view in space, the chart
// view flat): the surface's table row and picture, the parallels drawn, the K = 0 parallels, the
// largest |K| drawn (the curvature colour's full scale).
#pragma once

#include <string_view>
#include <vector>

#include "engine/revolution.h"
#include "render/scene_builder.h"

namespace spinfold::render {

// The K = 0 parallels: darker than the grid, so that the sign change is seen without the layer.
inline const glm::vec4 kZeroCurvatureColor{0.20f, 0.18f, 0.30f, 1.0f};

struct ProfileShape {
  RevolutionSurface surface;
  const RevolutionEntry* entry;
  ProfilePicture picture;
  double K(double u) const { return entry->profile(surface, u).K; }
};
ProfileShape profile_shape(const Surface& surface);

// Whether X lies on the drawn range of u (the bump to 4w, the catenoid to |z| = 2c), and what the
// HUD says of a main body beyond it (round which the revolution view draws a patch of the surface,
// within the drawing range).
bool on_drawn_piece(const Surface& surface, const Vec3& X);
inline constexpr std::string_view kOffDrawnPieceNote =
    "body 1 is beyond the surface drawn whole: a patch is drawn round it";
inline constexpr std::string_view kBeyondDrawingNote =
    "body 1 is too far out to draw (over 10^4 picture sizes away)";
std::string_view off_drawn_piece_note(const Surface& surface, const Vec3& X);

// How far from the centre a point may be drawn, in the picture's length: the GL draws in floats
// (24-bit mantissa), so at 10⁴ lengths a vertex is placed to ~6e-4 of a length, a hundredth of the
// patch's quads (kPatchQuads); farther out the patch's grid and the body's ellipse would be noise.
inline constexpr double kMaxDrawnDistance = 1e4;
// Whether X is finite and within kMaxDrawnDistance picture lengths of the centre: where the
// revolution view draws bodies, trails and the patch round a main body.
bool within_drawing_range(const Surface& surface, const Vec3& X);

// The parallels where K changes sign within the drawn range (bisected to rounding from 1024 steps).
std::vector<double> zero_curvature_parallels(const ProfileShape& shape);
// The grid's parallels: whole multiples of the picture's grid_step within the drawn range, leaving
// out the axis points (ρ = 0).
std::vector<double> grid_parallels(const ProfileShape& shape);
// The largest |K| at `samples` + 1 points of the drawn range (1 where K is 0 throughout).
double largest_curvature(const ProfileShape& shape, int samples);

}  // namespace spinfold::render
