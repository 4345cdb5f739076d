#include "engine/implicit_start.h"

#include <cmath>
#include <cstdio>

namespace spinfold {

namespace {

std::string point_text(const Vec3& X) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.9g, %.9g, %.9g)", X.x(), X.y(), X.z());
  return text;
}

bool finite(const ImplicitPoint& p) {
  return std::isfinite(p.F) && p.gradient.allFinite() && p.hessian.allFinite();
}

}  // namespace

SurfaceFoot project_onto_surface(const ImplicitSurface& surface, const Vec3& guess, double length,
                                 double max_move) {
  SurfaceFoot foot;
  Vec3 X = guess;
  for (;;) {
    const ImplicitPoint p = surface.at(X);
    foot.F_iterates.push_back(p.F);
    if (!finite(p)) {
      foot.refusal =
          "the surface's formula is undefined at X = " + point_text(X) + " (F or its derivatives not finite)";
      return foot;
    }
    const double g = p.gradient.norm();
    if (g <= kSingularDistance * length * p.hessian.norm() || g == 0.0) {
      char text[64];
      std::snprintf(text, sizeof text, "%.3e", g);
      foot.refusal = std::string("singular point of the surface: |grad F| = ") + text +
                     " at X = " + point_text(X) + " (no tangent plane there)";
      return foot;
    }
    if (std::abs(p.F) / g < kSurfaceFootTolerance * length) break;
    if (foot.iterations == kMaxSurfaceFootIterations) {
      foot.refusal = "Newton's projection onto the surface did not converge from " + point_text(guess) +
                     " in " + std::to_string(kMaxSurfaceFootIterations) + " steps";
      return foot;
    }
    X -= (p.F / (g * g)) * p.gradient;
    ++foot.iterations;
  }
  if ((X - guess).norm() > max_move) {
    foot.refusal = "the start " + point_text(guess) + " projects onto the surface at " + point_text(X) +
                   ", farther than " + std::to_string(max_move) + " from it: give a start nearer the surface";
    return foot;
  }
  foot.X = X;
  return foot;
}

StartFrame start_frame(const ImplicitSurface& surface, const Vec3& X) {
  StartFrame f;
  f.n = surface.at(X).gradient.normalized();
  Vec3 e = Vec3::UnitX() - f.n.x() * f.n;
  f.x_projection = e.norm();
  if (f.x_projection < 0.1) e = Vec3::UnitY() - f.n.y() * f.n;
  f.E1 = e.normalized();
  f.E1 = (f.E1 - f.E1.dot(f.n) * f.n).normalized();  // once more: tangent to round-off when e was short
  f.E2 = f.n.cross(f.E1);
  return f;
}

Embedded affine_start_in_frame(const StartFrame& frame, const Vec3& X, double speed, double heading,
                               const Mat2& L, const Mat2& L_dot) {
  Embedded Y;
  Y.segment<3>(embedded::X) = X;
  Y.segment<3>(embedded::V) = speed * (std::cos(heading) * frame.E1 + std::sin(heading) * frame.E2);
  for (int A = 0; A < 2; ++A) {
    Y.segment<3>(embedded::e1 + 3 * A) = L(0, A) * frame.E1 + L(1, A) * frame.E2;
    Y.segment<3>(embedded::W1 + 3 * A) = L_dot(0, A) * frame.E1 + L_dot(1, A) * frame.E2;
  }
  return Y;
}

EmbeddedRigid rigid_start_in_frame(const StartFrame& frame, const Vec3& X, double speed, double heading,
                                   const Mat2& L, double spin) {
  EmbeddedRigid Y;
  Y << X, speed * (std::cos(heading) * frame.E1 + std::sin(heading) * frame.E2),
      L(0, 0) * frame.E1 + L(1, 0) * frame.E2, spin;
  return Y;
}

}  // namespace spinfold
