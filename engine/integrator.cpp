#include "engine/integrator.h"

#include <array>

namespace spinfold {

std::span<const CatalogEntry> integrator_catalog() {
  static const std::array<CatalogEntry, 6> catalog{{
      {exact_info, nullptr},
      {dop853_info, &make_dop853},
      {rk4_info, &make_rk4},
      {implicit_midpoint_info, &make_implicit_midpoint},
      {gauss4_info, &make_gauss4},
      {gauss6_info, &make_gauss6},
  }};
  return catalog;
}

const CatalogEntry* find_integrator(std::string_view name) {
  for (const CatalogEntry& entry : integrator_catalog())
    if (entry.info.name == name) return &entry;
  return nullptr;
}

}  // namespace spinfold
