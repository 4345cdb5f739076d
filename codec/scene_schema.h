// The scene format as JSON Schema (draft 2020-12): what GET /api/v1/schema serves and what the web
// UI builds its controls from. Built from the field tables of engine/scene_fields.h, like parse_scene.
#pragma once

#include <nlohmann/json.hpp>

namespace spinfold {

nlohmann::ordered_json scene_schema();

}  // namespace spinfold
