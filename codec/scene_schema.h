// The scene format as JSON Schema (draft 2020-12): what GET /api/v1/schema serves and what the web
// UI builds its controls from. Kept in step with parse_scene by tests/codec/scene_schema_test.cpp.
#pragma once

#include <nlohmann/json.hpp>

namespace spinfold {

nlohmann::ordered_json scene_schema();

}  // namespace spinfold
