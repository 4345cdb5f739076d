// The body's inertia J^{AB} as the dynamics use it: isotropic (a number) or a symmetric
// positive-definite 2×2 matrix in the body frame (physics.md §13). With M = L̇ + Cφ̇εL the internal
// kinetic energy is T_int = ½ tr(M J Mᵀ), the momentum conjugate to L is P = M J, and
// H_int = ½ tr(P J⁻¹ Pᵀ). An isotropic matrix (J12 = 0, J11 = J22) is the number J11: every
// function below then evaluates exactly the scalar expressions, so results are bit-identical.
#pragma once

#include "engine/scene.h"
#include "engine/surface.h"

namespace spinfold {

struct Inertia {
  bool isotropic = true;
  double J = 0.1;                   // isotropic value [mass·length²]; tr(J)/2 otherwise
  Mat2 matrix = Mat2::Identity();   // J^{AB} [mass·length²]
  Mat2 inverse = Mat2::Identity();  // (J^{AB})⁻¹ [1/(mass·length²)]
};

// The body's inertia (the matrix when the scene gives one).
Inertia inertia_of(const Body& body);

// True when J^{AB} is a multiple of the identity (a number, or an isotropic matrix).
bool isotropic_inertia(const Body& body);

// M = P J⁻¹ [1/time] (isotropic: P/J).
Mat2 rate_from_momentum(const Inertia& inertia, const Mat2& P);
// P = M J [angular momentum] (isotropic: J M).
Mat2 momentum_from_rate(const Inertia& inertia, const Mat2& M);
// H_int = ½ tr(P J⁻¹ Pᵀ) (isotropic: ‖P‖²/(2J)) [energy].
double internal_kinetic_energy(const Inertia& inertia, const Mat2& P);
// s = tr((εL)ᵀ M J) (isotropic: J tr((εL)ᵀ M)) [angular momentum] (physics.md §3, §13).
double spin_from_rate(const Inertia& inertia, const Mat2& L, const Mat2& M);
// p_β = −tr((Lε)ᵀ M J): the vorticity, conserved only for isotropic J (physics.md §13).
double vorticity_from_rate(const Inertia& inertia, const Mat2& L, const Mat2& M);
// The rigid model's moment: L = λ₀U(θ), M = ωεL give T_int = ½ω²λ₀² tr J, the isotropic body with
// J = tr(J)/2 (physics.md §13) [mass·length²].
double rigid_inertia(const Inertia& inertia);

}  // namespace spinfold
