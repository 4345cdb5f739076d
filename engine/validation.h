// Validation of a scene: one pure function that names every bad field, its value and the reason.
#pragma once

#include <string>
#include <vector>

#include "engine/scene.h"
#include "engine/scene_fields.h"

namespace spinfold {

struct FieldError {
  std::string field;   // dotted path as in the scene JSON, e.g. "body.mass"
  std::string value;   // the offending value as text (numbers: shortest round-trip form, 1e-10)
  std::string reason;  // why it is rejected, e.g. "must be > 0"
};

// The numbers a scene may hold: magnitudes up to 1e100 and positive quantities (mass, inertia,
// radius, λ, μ, dt) from 1e-100, so that the products of a few of them that the state and its
// energy are made of stay finite; a start that overflows anyway is rejected too.
inline constexpr double kMaxSceneMagnitude = 1e100;
inline constexpr double kMinScenePositive = 1e-100;

// Every error found (empty: the scene can be run): each field against its range in
// engine/scene_fields.h, then the rules that tie fields together.
std::vector<FieldError> validate_scene(const Scene& scene);
// The surface alone: its fields by their table and the relations between them (the torus's c > a).
// The initial rates are converted on it (codec/scene_json.cpp), so a wrong one is named before them.
std::vector<FieldError> validate_surface(const Scene& scene);

// The reason given for a number outside `range`, e.g. "must be > 0", "must be between 1e-15 and
// 1e-2"; a `note` is appended in parentheses.
std::string range_reason(const Range& range, std::string_view note = {});
// A bound as written in reasons: powers of ten as 1eN (1e-2, 1e100), else the shortest form.
std::string bound_text(double bound);

}  // namespace spinfold
