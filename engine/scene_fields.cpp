#include "engine/scene_fields.h"

#include "engine/integrator.h"

namespace spinfold {

std::vector<std::string_view> integrator_names() {
  std::vector<std::string_view> names{kAutoIntegrator};
  for (const CatalogEntry& e : integrator_catalog()) names.push_back(e.info.name);
  return names;
}

}  // namespace spinfold
