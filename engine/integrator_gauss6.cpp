// Three-stage Gauss–Legendre collocation (order 6, symplectic). Nodes 1/2 − √15/10, 1/2, 1/2 + √15/10.
#include <cmath>

#include "engine/gauss_collocation.h"

namespace spinfold {

const IntegratorInfo gauss6_info{"gauss6", 6,     true,
                                 false,    false, "three-stage Gauss-Legendre, symplectic, fixed step"};

std::unique_ptr<Integrator> make_gauss6() {
  const double q = std::sqrt(15.0);
  const GaussTableau<3> tableau{{{{5.0 / 36, 2.0 / 9 - q / 15, 5.0 / 36 - q / 30},
                                  {5.0 / 36 + q / 24, 2.0 / 9, 5.0 / 36 - q / 24},
                                  {5.0 / 36 + q / 30, 2.0 / 9 + q / 15, 5.0 / 36}}},
                                {5.0 / 18, 4.0 / 9, 5.0 / 18}};
  return std::make_unique<GaussCollocation<3>>(gauss6_info, tableau);
}

}  // namespace spinfold
