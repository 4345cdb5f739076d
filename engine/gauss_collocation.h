// Gauss–Legendre collocation (implicit Runge–Kutta with s stages, order 2s), shared by
// integrator_implicit_midpoint.cpp, integrator_gauss4.cpp and integrator_gauss6.cpp.
// Symplectic for any Hamiltonian system in canonical coordinates, hence for the (L, P) chart form
// whose Hamiltonian is not separable (physics.md §4, §11).
#pragma once

#include <array>

#include "engine/integrator.h"

namespace spinfold {

template <int Stages>
struct GaussTableau {
  std::array<std::array<double, Stages>, Stages> a;
  std::array<double, Stages> b;
};

// Stage equations Z_i = h Σ_j a_ij f(y + Z_j) solved by fixed-point iteration to round-off.
// Stopping rule: stop when the max-norm change of Z is zero, or when it has fallen below 1e-12 of
// the state's scale and no longer decreases (round-off reached). A solve that has not stopped after
// kMaxIterations, or whose change grows to 1e6 times the first one or to a non-finite value, is a
// failed step (not accepted): the caller keeps its state.
template <int Stages>
class GaussCollocation final : public Integrator {
 public:
  static constexpr int kMaxIterations = 60;

  GaussCollocation(const IntegratorInfo& info, const GaussTableau<Stages>& tableau)
      : info_(info), tableau_(tableau) {}
  const IntegratorInfo& info() const override { return info_; }
  StepResult try_step(const StepProblem& f, const Coords& y, double h, double tolerance,
                      Coords& increment) override;

  int last_iterations() const { return iterations_; }

 private:
  const IntegratorInfo& info_;
  GaussTableau<Stages> tableau_;
  std::array<Coords, Stages> z_, z_new_, k_;
  Coords stage_;
  int iterations_ = 0;
};

}  // namespace spinfold
