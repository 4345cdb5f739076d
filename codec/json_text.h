// The one strict reading of JSON text used by every input (request bodies, scene files, stored rows).
#pragma once

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string_view>

namespace spinfold {

// Deepest nesting accepted in any JSON input (deeper input is rejected before it is built).
inline constexpr int kMaxJsonDepth = 32;

// Why a text is not exactly one JSON value; what() is the reason, e.g. "malformed JSON: ...".
struct JsonTextError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Exactly one JSON value and nothing after it but whitespace (RFC 8259), nested at most
// kMaxJsonDepth deep, with no NUL byte anywhere; JsonTextError otherwise. The NUL check comes first
// because nlohmann-json's lexer reads a NUL byte as the end of its input, so that
// `{"a":1}\0garbage` would otherwise read as `{"a":1}`.
nlohmann::json parse_json_text(std::string_view text);

}  // namespace spinfold
