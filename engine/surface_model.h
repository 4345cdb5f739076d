// The scene's surface resolved once into one model: what its catalog row offers, and the pieces
// that serve those offers, so that code outside the catalog asks the model (a chart, an implicit F,
// a formula, the drawn piece) and never which kind it is. On S², H² and the plane the polar chart
// (engine/chart.h) is the model and K = σ/R²; on every surface whose curvature varies the implicit
// F with ∇F and Hess F (a profile's RevolutionImplicit or a person's formula), its profile chart
// (u, φ) where it has one, and the piece a picture draws. Immutable, resolved once per surface and
// shared: Simulation and the render snapshot hold it, equal surfaces give the same object.
#pragma once

#include <memory>
#include <optional>

#include "engine/revolution.h"
#include "engine/surface.h"

namespace spinfold {

class FormulaSurface;

struct SurfaceModel {
  Surface surface;     // the parameters it was resolved from
  unsigned offered{};  // its catalog row's offers (offer_bit of each Offer)
  bool offers(Offer offer) const { return (offered & offer_bit(offer)) != 0; }
  // K [1/length²] where the curvature is constant (σ/R², the polar chart); NaN where it varies.
  double curvature = 0.0;
  // F, ∇F, Hess F where the chart-free equations run (Offer::implicit_equation); null on S², H², the
  // plane.
  std::shared_ptr<const ImplicitSurface> implicit;
  std::optional<RevolutionSurface> profile;       // the profile chart (u, φ) where it is offered
  std::shared_ptr<const FormulaSurface> formula;  // the person's formula where it is offered
  // F alone (a mesher's many evaluations): the formula's flat program, or `implicit`'s F.
  double value(const Vec3& X) const;
  // The drawn piece (where `implicit` is set; on S², H², the plane the sphere of radius R, closed
  // only on S²). [length] the picture's unit: the drawn piece lies within a ball of about this radius about
  // `centre`; the smallest feature (a torus's tube, a bump's width; on a formula surface 1/√max|K|,
  // at most a third of `length`): a body's scale and a trail's chord.
  double length = 1.0;
  double feature = 1.0;
  Vec3 centre = Vec3::Zero();  // [length] the centre of the drawn box
  SurfaceBounds box{};         // [length] the drawn piece: surface.bounds, or the one chosen (below)
  bool closed = false;         // the zero set lies inside the box (a closed surface drawn whole)
};

// The model of a surface the validator accepts (std::invalid_argument for a formula it refuses, naming
// why). On a formula
// surface without surface.bounds the box is chosen from the formula (docs/architecture.md): the zero set is
// sampled on 24³ points in the cubes [−h, h]³, h = 1, 2, 4, …, 64; the first whose sign changes stay clear of
// its faces is a closed surface, boxed with an eighth of its size to spare; a surface that reaches every
// cube's faces is unbounded and drawn in the cube of h = 2 (a graph's z to the range its height takes there,
// on a square halved while that range is over twice its side); none found, the cube of h = 2. The same
// surface, the same model: resolved once per surface (a cache of kSurfaceModelCacheSize, thread-safe).
inline constexpr std::size_t kSurfaceModelCacheSize = 64;
std::shared_ptr<const SurfaceModel> surface_model_of(const Surface& surface);
// Whether two surfaces have one model (the cache's identity): the kind, R, every profile's
// parameters, and a formula's text, parameters and box.
bool same_model(const Surface& a, const Surface& b);

}  // namespace spinfold
