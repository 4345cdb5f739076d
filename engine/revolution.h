// Surfaces of revolution whose curvature varies: the torus, the spheroid, a Gaussian bump on the
// plane and the catenoid (physics-surfaces.md §1). Each is one file, surface_<name>.cpp, behind the
// table below: its profile (ρ(u), z(u) and their derivatives) for the chart of §4, and its implicit
// equation F(X) = 0 with ∇F and Hess F for the chart-free equations of §7, which use nothing else
// and so hold on any implicit surface, with or without a symmetry.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "engine/surface.h"

namespace spinfold {

// One surface, its parameters named as the scene format names them [length]. Only the kind's own
// parameters are read: torus (tube_radius a, center_radius c > a), spheroid (equatorial_radius a,
// polar_radius b; oblate a > b, prolate a < b, a = b the sphere), bump (height h of either sign,
// width w > 0), catenoid (neck_radius c).
// The defaults are the scene's (engine/surface.h).
struct RevolutionSurface {
  SurfaceKind kind = SurfaceKind::torus;
  double tube_radius = 1.0;
  double center_radius = 2.5;
  double equatorial_radius = 1.0;
  double polar_radius = 0.6;
  double height = 1.0;
  double width = 1.0;
  double neck_radius = 1.0;
};

// The profile at u: X(u, φ) = (ρ cos φ, ρ sin φ, z), ds² = f² du² + ρ² dφ².
struct ProfilePoint {
  double rho = 0.0, rho_u = 0.0, rho_uu = 0.0;  // ρ [length], dρ/du, d²ρ/du²
  double z = 0.0, z_u = 0.0, z_uu = 0.0;        // z [length], dz/du, d²z/du²
  double K = 0.0;  // Gaussian curvature [1/length²], closed form (finite at an axis point)
  // z_u/ρ (finite at an axis point, where both vanish): §8's regularised chart
  double zu_over_rho = 0.0;
};

// F, ∇F and Hess F at an ambient point X; n = ∇F/|∇F| is the surface's orientation (§1).
struct ImplicitPoint {
  double F = 0.0;
  Vec3 gradient = Vec3::Zero();
  Mat3 hessian = Mat3::Zero();
};

// A surface F(X) = 0 as the chart-free equations (embedded_dynamics.h) see it: nothing but F, ∇F and
// Hess F, so that a surface with no symmetry (a user's formula) is a new implementation of this.
class ImplicitSurface {
 public:
  virtual ~ImplicitSurface() = default;
  virtual ImplicitPoint at(const Vec3& X) const = 0;
};

// Where u lives: [u_min, u_max], or the circle when periodic (u mod 2π). Axis points (ρ = 0) are at
// the finite ends of a non-periodic range, listed in `axis`.
struct ProfileDomain {
  double u_min = 0.0, u_max = 0.0;
  bool periodic = false;
  bool axis_at_min = false, axis_at_max = false;
};

// The part of the surface a picture shows and its lengths: the whole of a closed surface, a finite
// piece of an unbounded one (the bump's plane to ρ = 4w, the catenoid to |z| = 2c).
struct ProfilePicture {
  double u_min = 0.0, u_max = 0.0;  // the drawn range of u
  // [length] the picture's unit: the drawn piece lies within a ball of about this radius
  double length = 1.0;
  // [length] the smallest feature (the torus's tube, the bump's width): a body's scale
  double feature = 1.0;
  // The spacing of the parallels a picture draws, in u: 30° of the torus's tube angle, 15° of the
  // spheroid's polar angle, w/2 on the bump, c/2 along the catenoid.
  double grid_step = 1.0;
};

// A rule that ties a kind's parameters together, broken: the field named and why.
struct ParameterProblem {
  std::string_view field;  // under surface.
  double value = 0.0;
  std::string reason;
};

// One table row per surface: the functions its file defines.
struct RevolutionEntry {
  SurfaceKind kind;
  std::string_view name;  // the scene format's surface.kind
  std::string_view summary;
  ProfilePoint (*profile)(const RevolutionSurface& surface, double u);
  ImplicitPoint (*implicit)(const RevolutionSurface& surface, const Vec3& X);
  // u of an embedded point on the surface (the inverse maps of §1); φ = atan2(y, x) for every kind.
  double (*u_of)(const RevolutionSurface& surface, const Vec3& X);
  ProfileDomain (*domain)(const RevolutionSurface& surface);
  ProfilePicture (*picture)(const RevolutionSurface& surface);
  // What u is, in a refusal of initial.u (" (the distance from the axis)"); empty where u's name says it.
  std::string_view u_meaning = {};
  // The rule tying the parameters together, where there is one (the torus's c > a), else null.
  std::optional<ParameterProblem> (*parameter_problem)(const RevolutionSurface& surface) = nullptr;
};

// The scene's surface (engine/surface.h) as these functions read it; std::logic_error for a
// constant-curvature kind.
RevolutionSurface revolution_surface(const Surface& surface);

// The rows of the surface catalog (engine/surface.h) that offer a profile chart, in its order.
std::span<const std::reference_wrapper<const RevolutionEntry>> revolution_catalog();
const RevolutionEntry& revolution_entry(SurfaceKind kind);
const RevolutionEntry* find_revolution(std::string_view name);

// The rows, one per surface_<name>.cpp, are declared in engine/surface.h's catalog.

// A RevolutionSurface seen through its implicit equation.
class RevolutionImplicit final : public ImplicitSurface {
 public:
  explicit RevolutionImplicit(const RevolutionSurface& surface)
      : surface_(surface), implicit_(revolution_entry(surface.kind).implicit) {}
  ImplicitPoint at(const Vec3& X) const override { return implicit_(surface_, X); }

 private:
  RevolutionSurface surface_;
  ImplicitPoint (*implicit_)(const RevolutionSurface&, const Vec3&);
};

// What every formula of §1 derives from the profile: f = √(ρ_u² + z_u²), f_u, C = ρ_u/f, C_u.
struct ProfileMetric {
  double f = 1.0, f_u = 0.0;  // [length per unit u]
  double C = 1.0, C_u = 0.0;  // dρ/ds (= n_z) and its u-derivative
};
ProfileMetric profile_metric(const ProfilePoint& p);

// The chart point (u, φ): X, the orthonormal frame E₁ = X_u/f, E₂ = X_φ/ρ and n = E₁ × E₂ (§1).
// At an axis point (ρ = 0) E₂ = (−sin φ, cos φ, 0) still: the frame of the limit along φ.
struct RevolutionFrame {
  Vec3 X, E1, E2, n;
};
RevolutionFrame revolution_frame(const RevolutionSurface& surface, double u, double phi);

// The local geometry at u that converting rates needs: ρ, C = ρ_u/f, f, and whether u is an axis
// point (ρ = 0: an end of the domain marked as one), where φ and E₂'s rates are undefined.
struct ProfilePlace {
  double rho = 0.0, C = 1.0, f = 1.0;
  bool axis = false;
};
ProfilePlace profile_place(const RevolutionSurface& surface, double u);

// K = −det[[Hess F, ∇F], [∇Fᵀ, 0]] / |∇F|⁴ at X: the chart-free Gaussian curvature (§1), for any F.
double bordered_hessian_curvature(const ImplicitPoint& p);

}  // namespace spinfold
