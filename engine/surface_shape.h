// What a picture or a drawing of a surface whose curvature varies needs, whatever gives the surface
// (a profile's table row or a user's formula): its implicit F, the picture's lengths and the box it
// draws. Asked as one capability, so that code drawing bodies, trails and meshes never asks which
// kind the surface is. Plain data, resolved once per surface and shared.
#pragma once

#include <memory>

#include "engine/revolution.h"
#include "engine/surface.h"

namespace spinfold {

struct SurfaceShape {
  std::shared_ptr<const ImplicitSurface> implicit;  // F, ∇F, Hess F
  // F alone (a mesher's many evaluations): the formula's flat program, or `implicit`'s F.
  double value(const Vec3& X) const;
  // [length] the picture's unit: the drawn piece lies within a ball of about this radius about
  // `centre`; the smallest feature (a torus's tube, a bump's width; on a formula surface 1/√max|K|,
  // at most a third of `length`): a body's scale and a trail's chord.
  double length = 1.0;
  double feature = 1.0;
  Vec3 centre = Vec3::Zero();  // [length] the centre of the drawn box
  SurfaceBounds box{};         // [length] the drawn piece: surface.bounds, or the one chosen (below)
  bool closed = false;         // the zero set lies inside the box (a closed surface drawn whole)
  const class FormulaSurface* formula = nullptr;  // the formula's surface (for value()), else null
};

// The shape of a surface whose curvature varies (std::logic_error for S², H², the plane). On a formula
// surface without surface.bounds the box is chosen from the formula (docs/architecture.md): the zero set is
// sampled on 24³ points in the cubes [−h, h]³, h = 1, 2, 4, …, 64; the first whose sign changes stay clear of
// its faces is a closed surface, boxed with an eighth of its size to spare; a surface that reaches every
// cube's faces is unbounded and drawn in the cube of h = 2 (a graph's z to the range its height takes there,
// on a square halved while that range is over twice its side); none found, the cube of h = 2. The same
// surface, the same shape: resolved once per surface (a cache of kSurfaceShapeCacheSize, thread-safe).
inline constexpr std::size_t kSurfaceShapeCacheSize = 64;
std::shared_ptr<const SurfaceShape> surface_shape_of(const Surface& surface);

}  // namespace spinfold
