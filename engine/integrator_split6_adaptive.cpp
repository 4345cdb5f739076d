// split6 with its step sized from the tolerance: `auto`'s method for the incompressible body, where
// the RATTLE compositions are the only integrators that keep det L (physics.md §15), so `auto` cannot
// fall back to dop853 and a fixed dt ignores the tolerance. Step doubling (Richardson): one split6
// step of h against two of h/2; their difference (≈ the error of the full step, 2⁶ − 1 times that
// of the halves asymptotically; not divided by it, since the Yoshida composition's large negative
// sub-step keeps it far from asymptotic at the steps a tolerance allows) is held to the tolerance,
// and the two halves are what is taken (no local extrapolation: each accepted step is still a composition of
// exact flows and RATTLE steps, so det L stays on its level set). Internal to `auto`, not a catalog
// entry: it reports itself as split6 (the method its steps are) with adaptive = true.
#include <algorithm>
#include <cmath>

#include "engine/splitting.h"

namespace spinfold {

const IntegratorInfo split6_adaptive_info{
    "split6", 6,     false,
    true,     false, "split6 steps sized by step doubling to the tolerance (auto, incompressible body)",
    true};

namespace {

constexpr double kSafety = 0.9;
constexpr double kMaxShrink = 4.0;  // h may shrink by at most 4x after a rejection
constexpr double kMaxGrow = 4.0;
constexpr int kOrder = 6;  // of split6

class Split6Adaptive final : public Integrator {
 public:
  Split6Adaptive() : full_(make_split6()), half_(make_split6()) {}
  const IntegratorInfo& info() const override { return split6_adaptive_info; }

  StepResult try_step(const StepProblem& f, const Coords& y, double h, double tolerance,
                      Coords& increment) override {
    full_->try_step(f, y, h, tolerance, whole_);
    half_->try_step(f, y, 0.5 * h, tolerance, first_);
    mid_ = y + first_;
    half_->try_step(f, mid_, 0.5 * h, tolerance, second_);
    increment = first_ + second_;
    // The same scaled RMS norm as dop853: absolute and relative parts, per coordinate.
    const Eigen::Index n = y.size();
    double sum = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double y_next = y[i] + increment[i];
      const double sk = tolerance * (1.0 + std::max(std::abs(y[i]), std::abs(y_next)));
      const double e = (increment[i] - whole_[i]) / sk;
      sum += e * e;
    }
    const double err = std::sqrt(sum / static_cast<double>(n));
    if (!std::isfinite(err)) return {false, h / kMaxShrink};
    // err ~ h⁷ (local error of an order-6 method)
    const double fac = std::pow(err, 1.0 / (kOrder + 1)) / kSafety;
    if (err <= 1.0) return {true, h / std::clamp(fac, 1.0 / kMaxGrow, kMaxShrink)};
    return {false, h / std::clamp(fac, 1.0, kMaxShrink)};
  }

 private:
  std::unique_ptr<Integrator> full_, half_;
  Coords whole_, first_, second_, mid_;
};

}  // namespace

std::unique_ptr<Integrator> make_split6_adaptive() {
  return std::make_unique<Split6Adaptive>();
}

}  // namespace spinfold
