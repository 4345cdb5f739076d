// Classical fixed-step Runge–Kutta of order 4: the baseline everybody knows.
#include "engine/integrator.h"

namespace spinfold {

const IntegratorInfo rk4_info{"rk4", 4,     false,
                              false, false, "classical fixed-step Runge-Kutta, 4 evaluations per step"};

namespace {

class Rk4 final : public Integrator {
 public:
  const IntegratorInfo& info() const override { return rk4_info; }

  StepResult try_step(const StepProblem& f, const Coords& y, double h, double /*tolerance*/,
                      Coords& increment) override {
    f(y, k1_);
    f(y + 0.5 * h * k1_, k2_);
    f(y + 0.5 * h * k2_, k3_);
    f(y + h * k3_, k4_);
    increment = (h / 6.0) * (k1_ + 2.0 * k2_ + 2.0 * k3_ + k4_);
    return {true, h};
  }

 private:
  Coords k1_, k2_, k3_, k4_;
};

}  // namespace

std::unique_ptr<Integrator> make_rk4() {
  return std::make_unique<Rk4>();
}

}  // namespace spinfold
