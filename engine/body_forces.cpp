#include "engine/body_forces.h"

namespace spinfold {

double height_energy(const HeightPotential& height, double mass, double z) {
  switch (height.kind) {
    case HeightPotential::Kind::none: return 0.0;
    case HeightPotential::Kind::gravity: return mass * height.g * z;
    case HeightPotential::Kind::spring: return 0.5 * height.k * z * z;
  }
  return 0.0;
}

double height_slope(const HeightPotential& height, double mass, double z) {
  switch (height.kind) {
    case HeightPotential::Kind::none: return 0.0;
    case HeightPotential::Kind::gravity: return mass * height.g;
    case HeightPotential::Kind::spring: return height.k * z;
  }
  return 0.0;
}

}  // namespace spinfold
