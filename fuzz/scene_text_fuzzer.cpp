// libFuzzer target: arbitrary text through the scene reader that the CLI and the API use.
// Properties (a violation aborts): no crash, no exception and no sanitizer report on any input;
// every error has a reason (and a field, unless the text is not JSON at all); an accepted scene
// passes validation and its JSON reads back to the same JSON.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "codec/scene_json.h"
#include "fuzz/text_property.h"

using spinfold::fuzz::violated;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace spinfold;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const SceneParse parsed = parse_scene_text(text);
  if (!parsed.scene) {
    if (parsed.errors.empty()) violated("rejected without an error", text);
    for (const FieldError& e : parsed.errors)
      if (e.reason.empty() || (e.field.empty() && parsed.errors.size() > 1))
        violated("an error without a reason or a field", text);
    if (describe_errors(parsed.errors).empty()) violated("an empty error description", text);
    return 0;
  }
  if (!validate_scene(*parsed.scene).empty()) violated("an accepted scene that fails validation", text);
  const nlohmann::json written = scene_to_json(*parsed.scene);
  const SceneParse reread = parse_scene_text(written.dump());
  if (!reread.scene) violated("the scene's own JSON is rejected", text);
  if (scene_to_json(*reread.scene) != written)
    violated("the scene's JSON does not read back to itself", text);
  return 0;
}
