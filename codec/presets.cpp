#include "codec/presets.h"

namespace spinfold {

const PresetSource* find_preset(std::string_view name) {
  for (const PresetSource& p : preset_sources())
    if (p.name == name) return &p;
  return nullptr;
}

}  // namespace spinfold
