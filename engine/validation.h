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

// The numbers a scene may hold: magnitudes up to 1e100 and positive quantities (mass, inertia,
// radius, λ, μ, dt) from 1e-100, so that the products of a few of them that the state and its
// energy are made of stay finite; a start that overflows anyway is rejected too.
inline constexpr double kMaxSceneMagnitude = 1e100;
inline constexpr double kMinScenePositive = 1e-100;

// Every error found (empty: the scene can be run).
std::vector<FieldError> validate_scene(const Scene& scene);

}  // namespace spinfold
