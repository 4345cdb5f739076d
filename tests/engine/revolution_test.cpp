// The surface table (engine/revolution.h) against physics-surfaces.md §1 and §11 WS3: every surface's
// profile and implicit equation describe the same surface with the same orientation and curvature.
#include "engine/revolution.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace spinfold {
namespace {

struct Case {
  RevolutionSurface surface;
  std::vector<double> u;  // sample points inside the domain
};

std::vector<Case> cases() {
  std::vector<Case> out;
  RevolutionSurface torus{.kind = SurfaceKind::torus, .tube_radius = 1.0, .center_radius = 2.5};
  out.push_back({torus, {0.0, 0.7, 1.5707963267948966, -1.2, 2.9, 3.14159, -2.5}});
  RevolutionSurface oblate{.kind = SurfaceKind::spheroid, .equatorial_radius = 2.0, .polar_radius = 1.0};
  out.push_back({oblate, {0.05, 0.7, 1.5707963267948966, 2.4, 3.1}});
  RevolutionSurface prolate = oblate;
  prolate.equatorial_radius = 0.6;
  prolate.polar_radius = 1.7;
  out.push_back({prolate, {0.05, 0.9, 2.0, 3.0}});
  RevolutionSurface bump{.kind = SurfaceKind::bump, .height = 1.5, .width = 0.7};
  out.push_back({bump, {0.01, 0.35, 0.7, 1.4, 3.0}});
  RevolutionSurface dent = bump;
  dent.height = -0.8;
  dent.width = 1.3;
  out.push_back({dent, {0.2, 1.3, 2.5}});
  RevolutionSurface catenoid;
  catenoid.kind = SurfaceKind::catenoid;
  catenoid.neck_radius = 0.8;
  out.push_back({catenoid, {-2.0, -0.3, 0.0, 0.6, 1.8}});
  return out;
}

TEST(Revolution, ProfileAndImplicitAreOneSurface) {
  for (const Case& c : cases()) {
    const RevolutionEntry& entry = revolution_entry(c.surface.kind);
    for (const double u : c.u)
      for (const double phi : {0.0, 1.1, -2.7}) {
        SCOPED_TRACE(std::string(entry.name) + " u=" + std::to_string(u) + " phi=" + std::to_string(phi));
        const RevolutionFrame frame = revolution_frame(c.surface, u, phi);
        const ImplicitPoint ip = entry.implicit(c.surface, frame.X);
        const double scale = ip.gradient.norm() * (1.0 + frame.X.norm());
        EXPECT_LT(std::abs(ip.F), 1e-13 * scale);                       // X(u, φ) lies on F = 0
        EXPECT_LT((ip.gradient.normalized() - frame.n).norm(), 1e-13);  // n = E₁ × E₂ = ∇F/|∇F|
        EXPECT_LT((frame.E1.cross(frame.E2) - frame.n).norm(), 1e-15);
        EXPECT_LT(std::abs(frame.E1.dot(frame.n)), 1e-15);
        const ProfilePoint p = entry.profile(c.surface, u);
        // The closed-form K (table of §1), the intrinsic −C_u/(fρ) and the extrinsic bordered Hessian.
        const ProfileMetric m = profile_metric(p);
        EXPECT_NEAR(bordered_hessian_curvature(ip), p.K, 1e-12 * (1.0 + std::abs(p.K)));
        EXPECT_NEAR(-m.C_u / (m.f * p.rho), p.K, 1e-12 * (1.0 + std::abs(p.K)));
        EXPECT_NEAR(m.C, frame.n.z(), 1e-15);  // C = dρ/ds = n_z
        EXPECT_NEAR(p.zu_over_rho, p.z_u / p.rho, 1e-13 * (1.0 + std::abs(p.zu_over_rho)));
        // The inverse map gives u back (mod 2π on the torus).
        double off = entry.u_of(c.surface, frame.X) - u;
        if (entry.domain(c.surface).periodic) off = std::remainder(off, 2.0 * M_PI);
        EXPECT_NEAR(off, 0.0, 1e-12);
      }
  }
}

// The derivatives the profile gives are the derivatives of its ρ and z (central differences).
TEST(Revolution, ProfileDerivativesMatchDifferences) {
  const double h = 1e-5;
  for (const Case& c : cases()) {
    const RevolutionEntry& entry = revolution_entry(c.surface.kind);
    for (const double u : c.u) {
      SCOPED_TRACE(std::string(entry.name) + " u=" + std::to_string(u));
      const ProfilePoint p = entry.profile(c.surface, u);
      const ProfilePoint a = entry.profile(c.surface, u - h), b = entry.profile(c.surface, u + h);
      EXPECT_NEAR((b.rho - a.rho) / (2 * h), p.rho_u, 1e-8);
      EXPECT_NEAR((b.z - a.z) / (2 * h), p.z_u, 1e-8);
      EXPECT_NEAR((b.rho_u - a.rho_u) / (2 * h), p.rho_uu, 1e-8);
      EXPECT_NEAR((b.z_u - a.z_u) / (2 * h), p.z_uu, 1e-8);
    }
  }
}

// ∇F and Hess F are the derivatives of F (central differences at points off the surface too).
TEST(Revolution, ImplicitDerivativesMatchDifferences) {
  const double h = 1e-6;
  const Vec3 points[] = {{0.7, -0.4, 0.3}, {2.1, 1.3, -0.6}, {-0.2, 0.9, 1.1}};
  for (const Case& c : cases()) {
    const RevolutionEntry& entry = revolution_entry(c.surface.kind);
    for (const Vec3& X : points) {
      SCOPED_TRACE(std::string(entry.name));
      const ImplicitPoint p = entry.implicit(c.surface, X);
      for (int i = 0; i < 3; ++i) {
        const Vec3 d = h * Vec3::Unit(i);
        const ImplicitPoint a = entry.implicit(c.surface, X - d), b = entry.implicit(c.surface, X + d);
        EXPECT_NEAR((b.F - a.F) / (2 * h), p.gradient(i), 1e-6 * (1 + std::abs(p.gradient(i))));
        const Vec3 column = (b.gradient - a.gradient) / (2 * h);
        EXPECT_LT((column - p.hessian.col(i)).norm(), 1e-6 * (1 + p.hessian.norm()));
      }
    }
  }
}

// physics-surfaces.md §11 WS3: the bump h = 1.5, w = 0.7.
TEST(Revolution, WorkedNumbersWS3) {
  RevolutionSurface bump{.kind = SurfaceKind::bump, .height = 1.5, .width = 0.7};
  const double u[] = {0.0, 0.35, 0.7, 1.4};
  const double K[] = {9.371095376926283, 1.525821045282344, 0.0, -0.2883065112090633};
  const double C[] = {1.0, 0.7266184146004692, 0.609796644864093, 0.8650280519307838};
  const double f[] = {1.0, 1.376238173856149, 1.639890951225015, 1.156031874073855};
  for (int i = 0; i < 4; ++i) {
    const ProfilePoint p = bump_entry.profile(bump, u[i]);
    const ProfileMetric m = profile_metric(p);
    EXPECT_NEAR(p.K, K[i], 1e-14 * (1 + std::abs(K[i])));
    EXPECT_NEAR(m.C, C[i], 1e-15);
    EXPECT_NEAR(m.f, f[i], 1e-15);
  }
  // The top is an axis point where the chart-free curvature is still defined: K(0) = h²/w⁴.
  EXPECT_NEAR(bordered_hessian_curvature(bump_entry.implicit(bump, Vec3(0, 0, 1.5))), K[0], 1e-13);
}

TEST(Revolution, CatalogNamesEverySurfaceOnce) {
  EXPECT_EQ(revolution_catalog().size(), 4u);
  for (const RevolutionEntry& entry : revolution_catalog()) {
    EXPECT_EQ(find_revolution(entry.name), &revolution_entry(entry.kind));
    EXPECT_FALSE(entry.summary.empty());
  }
  EXPECT_EQ(find_revolution("sphere"), nullptr);  // the constant-curvature surfaces keep their own path
}

}  // namespace
}  // namespace spinfold
