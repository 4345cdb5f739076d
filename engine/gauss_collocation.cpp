#include "engine/gauss_collocation.h"

#include <cmath>

namespace spinfold {

template <int Stages>
StepResult GaussCollocation<Stages>::try_step(const StepProblem& f, const Coords& y, double h,
                                              double /*tolerance*/, Coords& increment) {
  const auto& a = tableau_.a;
  const double scale = 1.0 + y.cwiseAbs().maxCoeff();
  // Start from the explicit Euler guess Z_i = c_i h f(y).
  f(y, k_[0]);
  for (int i = 0; i < Stages; ++i) {
    double c = 0.0;
    for (int j = 0; j < Stages; ++j) c += a[i][j];
    z_[i] = (c * h) * k_[0];
  }
  double previous_change = INFINITY, first_change = 0.0;
  bool converged = false;
  for (iterations_ = 1; iterations_ <= kMaxIterations; ++iterations_) {
    for (int j = 0; j < Stages; ++j) {
      stage_ = y + z_[j];
      f(stage_, k_[j]);
    }
    double change = 0.0;
    for (int i = 0; i < Stages; ++i) {
      z_new_[i] = (h * a[i][0]) * k_[0];
      for (int j = 1; j < Stages; ++j) z_new_[i] += (h * a[i][j]) * k_[j];
      change = std::max(change, (z_new_[i] - z_[i]).cwiseAbs().maxCoeff());
    }
    if (iterations_ == 1) first_change = change;
    if (!std::isfinite(change) || change > 1e6 * first_change) break;  // diverging
    z_.swap(z_new_);
    // Round-off reached: no change, or no more progress once below 1e-12 of the state's scale.
    if (change == 0.0 || (change <= 1e-12 * scale && change >= previous_change)) {
      converged = true;
      break;
    }
    previous_change = change;
  }
  if (!converged) {
    increment = Coords::Zero(y.size());
    return {false, 0.5 * h};
  }
  // y₁ = y + h Σ b_i f(y + Z_i): the slopes of the last sweep, taken at Z to round-off.
  increment = (h * tableau_.b[0]) * k_[0];
  for (int i = 1; i < Stages; ++i) increment += (h * tableau_.b[i]) * k_[i];
  return {true, h};
}

template class GaussCollocation<1>;
template class GaussCollocation<2>;
template class GaussCollocation<3>;

}  // namespace spinfold
