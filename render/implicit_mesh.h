// A triangle mesh of a surface F = 0 within a box, for pictures of a surface given by a formula:
// F sampled on a grid of cubes, meshed by OpenVDB's volume-to-mesh (docs/licences.md says why), each
// vertex then brought onto F = 0 by Newton and given the exact normal ∇F/|∇F| and K from F.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "engine/surface_model.h"

namespace spinfold::render {

struct ImplicitMesh {
  std::vector<Vec3> points;   // on F = 0 [length]
  std::vector<Vec3> normals;  // ∇F/|∇F| there
  std::vector<double> K;      // the Gaussian curvature there [1/length²]
  // Triangles of point indices, each wound so that its face normal agrees with the normals.
  std::vector<std::array<std::uint32_t, 3>> triangles;
  double cell = 0.0;  // the grid's cube side [length]
};

// The default resolution: cubes along the box's longest side. The mesh of an ellipsoid at it has no
// open edge, and a torus's tube (a third of the box) ~25 cubes across (tests/render/implicit_mesh_test).
inline constexpr int kMeshCells = 72;
// Never more than this many cubes along a side (a caller's resolution is clamped to it).
inline constexpr int kMaxMeshCells = 256;

// How much the mesher merges cubes where the surface is nearly flat (OpenVDB's adaptivity): none. At
// 0.02 the torus's frame costs a third less, but a gently curved graph (the egg crate) is merged into
// a few large triangles, and its colours and K = 0 curves turn polygonal.
inline constexpr double kMeshAdaptivity = 0.0;

// The resolution a picture meshes a surface at: cubes along the box's longest side such that the
// surface's feature spans kCubesPerFeature of them, within [kLeastMeshCells, kMostMeshCells] (the torus
// of c = 2.5, a = 1: 49 cubes, ~8k triangles, as fine as the revolution view's 48 × 72 quads).
inline constexpr double kCubesPerFeature = 6.0;
inline constexpr int kLeastMeshCells = 40, kMostMeshCells = 96;
int mesh_cells(const SurfaceModel& shape);

// The mesh of `shape`'s F = 0 within `box`, `cells` cubes along its longest side. Where F is not
// finite (outside a logarithm's or a square root's domain) nothing is drawn; a vertex that Newton does
// not bring onto F = 0 within one cube of where the mesher put it (a sign change across a pole, or the
// box's face where F < 0) is left out with its triangles.
ImplicitMesh mesh_implicit_surface(const SurfaceModel& shape, const SurfaceBounds& box,
                                   int cells = kMeshCells, double adaptivity = kMeshAdaptivity);

}  // namespace spinfold::render
