// The one strict reading of JSON text used by every input (request bodies, scene files, stored rows).
#pragma once

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace spinfold {

// Deepest nesting accepted in any JSON input (deeper input is rejected before it is built).
inline constexpr int kMaxJsonDepth = 32;

// Why a text is not exactly one JSON value; what() is the reason, e.g. "malformed JSON: ...".
// `field`: the dotted path of the member at fault when one is (a duplicate key), else empty.
struct JsonTextError : std::runtime_error {
  using std::runtime_error::runtime_error;
  JsonTextError(const std::string& reason, std::string field_)
      : std::runtime_error(reason), field(std::move(field_)) {}
  std::string field;
};

// Exactly one JSON value and nothing after it but whitespace (RFC 8259), nested at most
// kMaxJsonDepth deep, with no NUL byte anywhere; JsonTextError otherwise. The NUL check comes first
// because nlohmann-json's lexer reads a NUL byte as the end of its input, so that
// `{"a":1}\0garbage` would otherwise read as `{"a":1}`. A key repeated within one object is
// refused, its path in `field` (RFC 8259 leaves what it means to each reader, I-JSON, RFC 7493
// §2.3, forbids it; nlohmann-json would keep the last).
nlohmann::json parse_json_text(std::string_view text);

}  // namespace spinfold
