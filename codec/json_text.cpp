#include "codec/json_text.h"

#include <string>

namespace spinfold {

namespace {
struct TooDeep {};
}  // namespace

nlohmann::json parse_json_text(std::string_view text) {
  // JSON text holds no raw NUL: outside strings only whitespace, inside them control characters
  // must be escaped.
  if (const std::size_t at = text.find('\0'); at != std::string_view::npos)
    throw JsonTextError("malformed JSON: a NUL byte at byte " + std::to_string(at) +
                        " (JSON text cannot contain one)");
  try {
    const nlohmann::json::parser_callback_t depth_guard = [](int depth, nlohmann::json::parse_event_t,
                                                             nlohmann::json&) {
      if (depth > kMaxJsonDepth) throw TooDeep{};
      return true;
    };
    // strict (the default): a second value or anything but whitespace after the first is an error.
    return nlohmann::json::parse(text, depth_guard, true, false);
  } catch (const TooDeep&) {
    throw JsonTextError("JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  } catch (const nlohmann::json::exception& e) {
    throw JsonTextError(std::string("malformed JSON: ") + e.what());
  }
}

}  // namespace spinfold
