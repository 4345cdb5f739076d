// Splitting methods: H = H_A + H_B with H_A the integrable part solved exactly (integrable_flow:
// isometry flow of the orbit, spin rotation, internal motion under the abc potential) and H_B the
// rest (the radial potential V_r and the polar deformation potential), whose flow is a kick that
// changes only velocities. Strang steps K(h/2) D(h) K(h/2) composed to higher order; every piece
// is an exact Hamiltonian flow, so the method is symplectic. With anisotropic inertia the abc
// potential moves from the exact flow into the kick (the free drift L + tM stays exact; physics.md
// §13). For the incompressible body each sub-step adds a RATTLE step of the internal motion on
// det L = c, which commutes with the rest (physics.md §15). Shared by integrator_split4.cpp and
// integrator_split6.cpp.
#pragma once

#include <vector>

#include "engine/integrator.h"

namespace spinfold {

class SplittingComposition final : public Integrator {
 public:
  // `weights`: the Strang sub-steps w_i (Σ w_i = 1), applied in order.
  SplittingComposition(const IntegratorInfo& info, std::vector<double> weights)
      : info_(info), weights_(std::move(weights)) {}
  const IntegratorInfo& info() const override { return info_; }
  StepResult try_step(const StepProblem& problem, const Coords& y, double h, double tolerance,
                      Coords& increment) override;

 private:
  const IntegratorInfo& info_;
  std::vector<double> weights_;
};

}  // namespace spinfold
