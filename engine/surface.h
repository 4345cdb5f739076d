// The surfaces a body moves on. Sphere, pseudosphere and plane have constant curvature and the polar
// chart of physics.md §1 (the functions below); the torus, spheroid, bump and catenoid are surfaces of
// revolution whose curvature varies (engine/revolution.h, physics-surfaces.md §1), and implicit and
// graph surfaces are given by a formula (engine/formula_surface.h, physics-anysurface.md); every
// surface whose curvature varies is run by the chart-free equations (engine/embedded_dynamics.h).
#pragma once

#include <Eigen/Dense>
#include <array>
#include <functional>
#include <iterator>
#include <map>
#include <optional>
#include <string>

namespace spinfold {

using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;

// The three constant-curvature surfaces differ only in the sign σ of the curvature, so one struct
// with a kind serves every formula (K = σ/R²) without a visitor per function. The four after them
// are the surfaces of revolution of engine/revolution.h, one file each behind its table, and the last
// two are given by a formula (engine/formula_surface.h); the constant-curvature functions below are not
// defined on them (std::logic_error).
enum class SurfaceKind { sphere, pseudosphere, plane, torus, spheroid, bump, catenoid, implicit, graph };

// What a surface offers. Code outside the catalog below asks what the surface offers (a chart, a
// closed form, a formula), never which kind it is, so that a new kind is one row and its own file.
enum class Offer : unsigned {
  polar_chart,         // K = σ/R² constant: the polar chart (r, φ), the closed forms of physics.md §1 and
                       // the chart state; without it the chart-free equations run on the implicit F
  positive_curvature,  // σ = +1: S² ⊂ ℝ³ (r ≤ πR, the antipode a second pole)
  negative_curvature,  // σ = −1: H² ⊂ ℝ^{2,1} (the Minkowski product, the recentring)
  zero_curvature,      // σ = 0: the plane (the normal ẑ, translations)
  profile_chart,       // the chart (u, φ) of a surface of revolution and its closed forms (revolution.h)
  implicit_equation,   // F, ∇F and Hess F in ℝ³: the chart-free equations, the shape and the mesh
  formula,             // a person's text F or z with parameters: the start is a point initial.X, no chart
};

constexpr unsigned offer_bit(Offer offer) {
  return 1u << static_cast<unsigned>(offer);
}

// A surface of revolution's profile chart and implicit F (engine/revolution.h), one file each.
struct RevolutionEntry;
extern const RevolutionEntry torus_entry;
extern const RevolutionEntry spheroid_entry;
extern const RevolutionEntry bump_entry;
extern const RevolutionEntry catenoid_entry;

// The one catalog of surfaces: what each kind offers, in the enumeration's order, and the file that
// gives its profile chart where it offers one.
struct SurfaceRow {
  SurfaceKind kind;
  unsigned offers;  // offer_bit of each Offer
  const RevolutionEntry* profile = nullptr;
};
inline constexpr SurfaceRow kSurfaceCatalog[] = {
    {SurfaceKind::sphere, offer_bit(Offer::polar_chart) | offer_bit(Offer::positive_curvature)},
    {SurfaceKind::pseudosphere, offer_bit(Offer::polar_chart) | offer_bit(Offer::negative_curvature)},
    {SurfaceKind::plane, offer_bit(Offer::polar_chart) | offer_bit(Offer::zero_curvature)},
    {SurfaceKind::torus, offer_bit(Offer::profile_chart) | offer_bit(Offer::implicit_equation), &torus_entry},
    {SurfaceKind::spheroid, offer_bit(Offer::profile_chart) | offer_bit(Offer::implicit_equation),
     &spheroid_entry},
    {SurfaceKind::bump, offer_bit(Offer::profile_chart) | offer_bit(Offer::implicit_equation), &bump_entry},
    {SurfaceKind::catenoid, offer_bit(Offer::profile_chart) | offer_bit(Offer::implicit_equation),
     &catenoid_entry},
    {SurfaceKind::implicit, offer_bit(Offer::implicit_equation) | offer_bit(Offer::formula)},
    {SurfaceKind::graph, offer_bit(Offer::implicit_equation) | offer_bit(Offer::formula)},
};

// The rows in the enumeration's order (a row offers a profile chart exactly when it names its entry:
// tests/engine/surface_test.cpp, as an address is not a constant under the sanitizers).
static_assert([] {
  for (unsigned i = 0; i < std::size(kSurfaceCatalog); ++i)
    if (static_cast<unsigned>(kSurfaceCatalog[i].kind) != i) return false;
  return true;
}());

// The bit of one surface kind in a set of kinds (a scene field's or a view's).
constexpr unsigned surface_bit(SurfaceKind kind) {
  return 1u << static_cast<unsigned>(kind);
}

// What `kind` offers (offer_bit of each; none for a value outside the enumeration, which the
// validator names).
constexpr unsigned offers_of(SurfaceKind kind) {
  const auto i = static_cast<unsigned>(kind);
  return i < std::size(kSurfaceCatalog) ? kSurfaceCatalog[i].offers : 0u;
}
// Whether `kind` offers `offer`.
constexpr bool offers(SurfaceKind kind, Offer offer) {
  return (offers_of(kind) & offer_bit(offer)) != 0;
}
// The set of kinds (surface_bit) that offer `offer`.
constexpr unsigned surfaces_offering(Offer offer) {
  unsigned set = 0;
  for (const SurfaceRow& row : kSurfaceCatalog)
    if ((row.offers & offer_bit(offer)) != 0) set |= surface_bit(row.kind);
  return set;
}

// A formula's named numbers ({"a": 2, "b": 1.3}), sweepable as surface.parameters.a.
using SurfaceParameters = std::map<std::string, double, std::less<>>;
// The drawn piece of a formula surface: [[x₀, x₁], [y₀, y₁], [z₀, z₁]] [length].
using SurfaceBounds = std::array<std::array<double, 2>, 3>;

// Farthest a body may go on H², in units of R: the global embedding grows as R e^{r/R}/2 and the
// outputs built from it (X, p_φ, the paper's frame) must stay finite in double (e^250 ≈ 1e108).
inline constexpr double kMaxHyperbolicDistance = 250.0;

struct Surface {
  Surface() = default;
  Surface(SurfaceKind kind_, double radius_) : kind(kind_), radius(radius_) {}

  SurfaceKind kind = SurfaceKind::sphere;
  double radius = 1.0;  // R [length]; on the plane only the length scale for charts and display
  // The surfaces of revolution's parameters (physics-surfaces.md §1) [length]; each kind reads its own.
  double tube_radius = 1.0;        // torus: a
  double center_radius = 2.5;      // torus: c > a
  double equatorial_radius = 1.0;  // spheroid: a (oblate a > b, prolate a < b)
  double polar_radius = 0.6;       // spheroid: b
  double height = 1.0;             // bump: h, either sign (z = h exp(−ρ²/(2w²)))
  double width = 1.0;              // bump: w > 0
  double neck_radius = 1.0;        // catenoid: c
  // Formula surfaces (physics-anysurface.md §9, docs/formula-language.md): implicit F(x, y, z) = 0
  // or graph z = f(x, y), the formula's parameters, and the box drawn (none: the model chooses).
  std::string F = "x^2 + y^2 + z^2 - 1";  // implicit
  std::string z = "0";                    // graph
  SurfaceParameters parameters;
  std::optional<SurfaceBounds> bounds;
  // K [1/length²] when the scene gave the curvature instead of kind and radius (a dial through 0):
  // resolve_curvature sets kind and radius from it; kept to write the scene back as given.
  std::optional<double> curvature_given;
};

// What the scene's surface offers (the catalog above).
inline bool offers(const Surface& surface, Offer offer) {
  return offers(surface.kind, offer);
}
// Whether the chart-free equations run on the implicit F (engine/embedded_dynamics.h): the surfaces
// whose curvature varies; false for S², H², the plane (the polar chart) and a kind the validator refuses.
inline bool chart_free(const Surface& surface) {
  return offers(surface.kind, Offer::implicit_equation);
}

// Below this |K| [1/length²] a given curvature is the plane: R > 1e12, and over any distance r up to
// 1e4 lengths K r² < 1e-16 is below double round-off (the plane and the surface are one picture).
inline constexpr double kFlatCurvature = 1e-24;

// Sets kind and radius from surface.curvature_given when it is set (else leaves the surface as it
// is): K > 0 the sphere of radius 1/√K, K < 0 H² of radius 1/√−K, |K| < kFlatCurvature the plane
// (length scale 1). The formulas of every kind are then used as they are: R sin(r/R), cos(r/R),
// R sinh(r/R), … are accurate to round-off for R up to 1e12 (no division by a vanishing K, no
// series needed), so a run at K = ±1e-12 agrees with the plane's (tests/codec/curvature_dial_test).
void resolve_curvature(Surface& surface);

// σ: +1 sphere, −1 pseudosphere, 0 plane.
double curvature_sign(const Surface& surface);
// K = σ/R² [1/length²].
double curvature(const Surface& surface);
// S(r): R sin(r/R), R sinh(r/R) or r [length]; the circumference of a geodesic circle is 2πS.
double polar_S(const Surface& surface, double r);
// C(r) = S′(r): cos(r/R), cosh(r/R) or 1.
double polar_C(const Surface& surface, double r);

// ⟨a, b⟩ = aᵀηb, η = diag(1, 1, −1) on the pseudosphere (Minkowski ℝ^{2,1}), I otherwise.
double dot(const Surface& surface, const Vec3& a, const Vec3& b);
// Unit normal n at an embedded point X: X/R on S² and H², ẑ on the plane.
Vec3 unit_normal(const Surface& surface, const Vec3& X);
// j v = η(n × v): the +90° rotation in the tangent plane at X (j E₁ = E₂).
Vec3 rotate_quarter(const Surface& surface, const Vec3& X, const Vec3& v);
// P(w) = w − k⟨w, X⟩X with k = 1/⟨X, X⟩: the tangential part of an ambient vector at X.
Vec3 tangential(const Surface& surface, const Vec3& X, const Vec3& w);
// η w: raises the index of an ambient covector (a gradient) into a vector.
Vec3 raise(const Surface& surface, const Vec3& w);

// Embedding of the chart point (r, φ) and the paper's frame E₁ = ∂/∂r, E₂ = (1/S)∂/∂φ there.
// Valid for any real r (r < 0 is the point (|r|, φ + π)), including the pole r = 0.
struct ChartPoint {
  Vec3 X;   // position [length], embedding coordinates
  Vec3 E1;  // unit radial vector
  Vec3 E2;  // unit angular vector (= j E₁)
};
ChartPoint chart_point(const Surface& surface, double r, double phi);

// Polar coordinates of an embedded point: r ≥ 0 (distance from the chart pole) and
// ρ = √(X₁² + X₂²) (= |S(r)|); φ = atan2(X₂, X₁) is meaningful only when ρ > 0.
struct PolarCoordinates {
  double r;
  double phi;
  double rho;
};
PolarCoordinates polar_coordinates(const Surface& surface, const Vec3& X);

}  // namespace spinfold
