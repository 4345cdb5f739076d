// Implicit midpoint rule: the one-stage Gauss–Legendre method (order 2, symplectic).
#include "engine/gauss_collocation.h"

namespace spinfold {

const IntegratorInfo implicit_midpoint_info{
    "implicit_midpoint", 2, true, false, false, "one-stage Gauss-Legendre, symplectic, fixed step"};

std::unique_ptr<Integrator> make_implicit_midpoint() {
  return std::make_unique<GaussCollocation<1>>(implicit_midpoint_info, GaussTableau<1>{{{{0.5}}}, {1.0}});
}

}  // namespace spinfold
