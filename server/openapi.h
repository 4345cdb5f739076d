// The OpenAPI 3 description of the HTTP API, served at /api/v1/openapi.json and kept true by
// tests/server/api_test.cpp (every operation it lists is routed).
#pragma once

#include <nlohmann/json.hpp>

namespace spinfold::server {

nlohmann::ordered_json openapi_document();

}  // namespace spinfold::server
