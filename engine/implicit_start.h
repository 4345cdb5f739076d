// Starting a body on a surface known only by F(X) = 0 (physics-anysurface.md §5, §6): a guess brought
// onto the surface by Newton along ∇F, the start frame of the convention there, and the chart-free
// state (embedded_dynamics.h) built in that frame. Nothing here asks what the surface is.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/embedded_dynamics.h"

namespace spinfold {

// Newton's iterations at most, and the distance from the surface that ends them: |F|/|∇F| below
// kSurfaceFootTolerance × the length scale (a start 0.1 away needs about 5, WF1).
inline constexpr int kMaxSurfaceFootIterations = 40;
inline constexpr double kSurfaceFootTolerance = 1e-15;
// A point nearer than this × the length scale to where ∇F = 0 (|∇F| < this × L ‖Hess F‖) is taken as
// singular: no tangent plane, n and K undefined (§7).
inline constexpr double kSingularDistance = 1e-8;

// The foot of a guess on F = 0, or why there is none.
struct SurfaceFoot {
  std::optional<Vec3> X;           // on the surface [length]
  std::string refusal;             // when X is empty: singular point, undefined formula, no convergence
  int iterations = 0;              // Newton steps taken
  std::vector<double> F_iterates;  // F at the guess and after each step
};

// X_{k+1} = X_k − F ∇F/|∇F|² from `guess` until |F|/|∇F| < kSurfaceFootTolerance × length (§6).
// Refused where ∇F vanishes on the way (kSingularDistance), where F or ∇F is not finite (the formula
// is undefined there), without convergence, or farther than max_move from the guess (it may have
// jumped to another component).
SurfaceFoot project_onto_surface(const ImplicitSurface& surface, const Vec3& guess, double length,
                                 double max_move);

// The start frame of §5 at a point of the surface: n = ∇F/|∇F|; E₁ the normalised tangential part of
// the world x-axis, or of the y-axis where that part is shorter than 0.1; E₂ = n × E₁.
struct StartFrame {
  Vec3 n = Vec3::UnitZ();
  Vec3 E1 = Vec3::UnitX();
  Vec3 E2 = Vec3::UnitY();
  double x_projection = 1.0;  // |x̂ − n_x n|: below 0.1 the y-axis was used
};
StartFrame start_frame(const ImplicitSurface& surface, const Vec3& X);

// The affine body's [X, V, e₁, e₂, W₁, W₂] at X: V = v(cos ψ E₁ + sin ψ E₂), e_A = E_B L_BA and
// W_A = E_B L̇_BA, the rates relative to a parallel-transported frame (§5.6).
Embedded affine_start_in_frame(const StartFrame& frame, const Vec3& X, double speed, double heading,
                               const Mat2& L, const Mat2& L_dot);
// The rigid body's [X, V, e₁, s] (§5.7): e₁ = E_B L_B1, L = λ₀U(θ).
EmbeddedRigid rigid_start_in_frame(const StartFrame& frame, const Vec3& X, double speed, double heading,
                                   const Mat2& L, double spin);

}  // namespace spinfold
