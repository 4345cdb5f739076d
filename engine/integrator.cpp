#include "engine/integrator.h"

#include <array>

#include "engine/dynamics.h"

namespace spinfold {

void StepProblem::operator()(const Coords& y, Coords& dydt) const {
  if (field)
    (*field)(y, dydt);
  else
    vector_field(scene, chart, y, dydt);
}

std::span<const CatalogEntry> integrator_catalog() {
  static const std::array<CatalogEntry, 8> catalog{{
      {exact_info, nullptr},
      {dop853_info, &make_dop853},
      {rk4_info, &make_rk4},
      {implicit_midpoint_info, &make_implicit_midpoint},
      {gauss4_info, &make_gauss4},
      {gauss6_info, &make_gauss6},
      {split4_info, &make_split4},
      {split6_info, &make_split6},
  }};
  return catalog;
}

const CatalogEntry* find_integrator(std::string_view name) {
  for (const CatalogEntry& entry : integrator_catalog())
    if (entry.info.name == name) return &entry;
  return nullptr;
}

}  // namespace spinfold
