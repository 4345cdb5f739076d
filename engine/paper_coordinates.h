// The paper's coordinates (r, φ, α, β, λ, μ), their rates and momenta, computed from a state.
// They are outputs only; the state never uses them (physics.md §2 lists where they are singular).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/scene.h"
#include "engine/state.h"

namespace spinfold {

struct UndefinedValue {
  std::string field;   // e.g. "alpha"
  std::string reason;  // e.g. "lambda = mu: only theta = alpha - beta is defined"
};

// Empty optionals are undefined at this state; `undefined` names each with its reason.
// Conventions: λ ≥ |μ|, μ < 0 after the frame passed through det L = 0; angles in (−π, π].
struct PaperCoordinates {
  double r = 0.0;
  std::optional<double> phi, alpha, beta, theta;  // θ = α − β, the rotation part of L
  double lambda = 0.0, mu = 0.0;
  std::optional<double> r_dot, phi_dot, alpha_dot, beta_dot, theta_dot;
  double lambda_dot = 0.0, mu_dot = 0.0;
  std::optional<double> p_r;
  // p_phi far out on H² keeps fewer than 8 digits: then it is listed under `undefined` (outputs show
  // null) and this is only the nearest double the chart gives.
  double p_phi = 0.0, p_alpha = 0.0, p_beta = 0.0, p_lambda = 0.0, p_mu = 0.0;
  Vec3 X;                 // global embedding position (physics.md §1)
  std::optional<Mat2> L;  // rows as physics.md §2: L_BA = component of e_A along E_B
  double det_L = 0.0;     // frame-independent
  std::vector<UndefinedValue> undefined;
};

PaperCoordinates paper_coordinates(const Scene& scene, const State& state);

// λ ≥ |μ| of L = U(α)diag(λ, μ)U(β)ᵀ: λ the sum of the two polar radii, μ = det L / λ (0 at L = 0).
struct FrameStretches {
  double lambda = 0.0, mu = 0.0;
};
FrameStretches frame_stretches(const Mat2& L);

struct Inertia;
// The internal coordinates of L = U(α)diag(λ, μ)U(β)ᵀ and L̇ given in one frame: λ, μ and their rates
// and momenta always; with frame_defined also L, α, β, θ and their rates (each undefined where
// physics.md §2 says, with the reason). M = De_A/Dt in that frame gives p_λ, p_μ for anisotropic J.
void set_internal_coordinates(PaperCoordinates& out, const Mat2& L, const Mat2& L_dot, const Mat2& M,
                              const Inertia& inertia, BodyModel model, bool frame_defined);

}  // namespace spinfold
