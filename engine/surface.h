// The surfaces a body moves on. Sphere, pseudosphere and plane have constant curvature and the polar
// chart of physics.md §1 (the functions below); the torus, spheroid, bump and catenoid are surfaces of
// revolution whose curvature varies (engine/revolution.h, physics-surfaces.md §1), and implicit and
// graph surfaces are given by a formula (engine/formula_surface.h, physics-anysurface.md); every
// surface whose curvature varies is run by the chart-free equations (engine/embedded_dynamics.h).
#pragma once

#include <Eigen/Dense>
#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>

namespace spinfold {

using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;

// The three constant-curvature surfaces differ only in the sign σ of the curvature, so one struct
// with a kind serves every formula (K = σ/R²) without a visitor per function. The four after them
// are the surfaces of revolution of engine/revolution.h, one file each behind its table; the
// constant-curvature functions below are not defined on them (std::logic_error).
enum class SurfaceKind { sphere, pseudosphere, plane, torus, spheroid, bump, catenoid, implicit, graph };

// The bit of one surface kind in a set of kinds (a scene field's or a view's), and the two families.
constexpr unsigned surface_bit(SurfaceKind kind) {
  return 1u << static_cast<unsigned>(kind);
}
inline constexpr unsigned kConstantCurvatureSurfaces = surface_bit(SurfaceKind::sphere) |
                                                       surface_bit(SurfaceKind::pseudosphere) |
                                                       surface_bit(SurfaceKind::plane);
// The surfaces of revolution: the profile chart (u, φ) of engine/revolution.h.
inline constexpr unsigned kProfileSurfaces =
    surface_bit(SurfaceKind::torus) | surface_bit(SurfaceKind::spheroid) | surface_bit(SurfaceKind::bump) |
    surface_bit(SurfaceKind::catenoid);
// The surfaces given by a formula: no chart, no symmetry (physics-anysurface.md).
inline constexpr unsigned kFormulaSurfaces =
    surface_bit(SurfaceKind::implicit) | surface_bit(SurfaceKind::graph);
inline constexpr unsigned kVaryingCurvatureSurfaces = kProfileSurfaces | kFormulaSurfaces;

constexpr bool in_surface_set(SurfaceKind kind, unsigned set) {
  return static_cast<unsigned>(kind) < 32 && (surface_bit(kind) & set) != 0;
}
// True where the chart-free equations run (the surfaces of revolution and formula surfaces), false
// for S², H², the plane. (A value outside the enumeration, which the validator names, is neither.)
constexpr bool curvature_varies(SurfaceKind kind) {
  return in_surface_set(kind, kVaryingCurvatureSurfaces);
}
// Whether the surface has the profile chart (u, φ) of a surface of revolution.
constexpr bool has_profile_chart(SurfaceKind kind) {
  return in_surface_set(kind, kProfileSurfaces);
}
// Whether the surface is given by a formula (implicit F = 0, or a graph z = f(x, y)).
constexpr bool given_by_formula(SurfaceKind kind) {
  return in_surface_set(kind, kFormulaSurfaces);
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
