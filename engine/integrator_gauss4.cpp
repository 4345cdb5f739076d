// Two-stage Gauss–Legendre collocation (order 4, symplectic). Nodes 1/2 ∓ √3/6.
#include <cmath>

#include "engine/gauss_collocation.h"

namespace spinfold {

const IntegratorInfo gauss4_info{"gauss4", 4,     true,
                                 false,    false, "two-stage Gauss-Legendre, symplectic, fixed step"};

std::unique_ptr<Integrator> make_gauss4() {
  const double r = std::sqrt(3.0) / 6.0;
  const GaussTableau<2> tableau{{{{0.25, 0.25 - r}, {0.25 + r, 0.25}}}, {0.5, 0.5}};
  return std::make_unique<GaussCollocation<2>>(gauss4_info, tableau);
}

}  // namespace spinfold
