// Validation of a scene: one pure function that names every bad field, its value and the reason.
#pragma once

#include <string>
#include <vector>

#include "engine/scene.h"

namespace spinfold {

struct FieldError {
  std::string field;   // dotted path as in the scene JSON, e.g. "body.mass"
  std::string value;   // the offending value as text
  std::string reason;  // why it is rejected, e.g. "must be > 0"
};

// Every error found (empty: the scene can be run).
std::vector<FieldError> validate_scene(const Scene& scene);

}  // namespace spinfold
