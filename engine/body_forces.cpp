#include "engine/body_forces.h"

#include "engine/overloaded.h"

namespace spinfold {

double height_energy(const HeightPotential& height, double mass, double z) {
  return std::visit(Overloaded{[](std::monostate) { return 0.0; },
                               [&](const GravityPotential& p) { return mass * p.g * z; },
                               [&](const SpringPotential& p) { return 0.5 * p.k * z * z; }},
                    height);
}

double height_slope(const HeightPotential& height, double mass, double z) {
  return std::visit(
      Overloaded{[](std::monostate) { return 0.0; }, [&](const GravityPotential& p) { return mass * p.g; },
                 [&](const SpringPotential& p) { return p.k * z; }},
      height);
}

}  // namespace spinfold
