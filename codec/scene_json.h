// The scene format (JSON) shared by the CLI, the API and assets/scenes: parse, check, write.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>
#include <vector>

#include "codec/json_text.h"
#include "engine/scene.h"
#include "engine/validation.h"

namespace spinfold {

struct SceneParse {
  std::optional<Scene> scene;      // set only when errors is empty
  std::vector<FieldError> errors;  // structure errors (unknown key, wrong type) and validate_scene's
};

// Parses JSON text (parse_json_text: exactly one value, no NUL byte); malformed JSON is one error
// with field "" naming the position.
SceneParse parse_scene_text(std::string_view text);
// Reads a parsed document: unknown keys and kinds are rejected, omitted fields get the defaults
// of engine/scene.h, and the result passes validate_scene.
SceneParse parse_scene(const nlohmann::json& document);

nlohmann::json scene_to_json(const Scene& scene);

// Applies a JSON merge patch (RFC 7396) to a scene document, except that a patch that sets one
// form of a value drops the other form already there, by the tables' stand-in relation
// (Field::replaces, engine/scene_fields.h: spin ↔ alpha_dot; speed, heading ↔ r_dot, phi_dot;
// surface.curvature ↔ kind, radius): the patch's value wins instead of clashing with it.
void merge_scene_patch(nlohmann::json& document, const nlohmann::json& patch);

// Why a merge patch taking the scene `before` to `after` cannot continue the run (retune) and
// starts it over at t = 0 instead (a new start, other companions, another surface kind without a
// curvature dial, joining or leaving the incompressible constraint), or "" when it can continue.
std::string restart_reason(const nlohmann::json& patch, const Scene& before, const Scene& after);

// What a change that continues the run says, in every front door's answer: "new parameters from
// t = 5.32927 on, continuing from the current state", or "…from t = 0, continuing from the start"
// when nothing had run yet. The time to 6 digits (the answer's own `t` is exact).
std::string continued_reason(double t);

// "field: reason (value)" lines, one per error.
std::string describe_errors(const std::vector<FieldError>& errors);

}  // namespace spinfold
