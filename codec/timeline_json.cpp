#include "codec/timeline_json.h"

#include <cmath>
#include <string>

#include "codec/scene_json.h"
#include "engine/number_text.h"

namespace spinfold {

using nlohmann::json;
using nlohmann::ordered_json;

TimelineParse parse_timeline(const Scene& scene, const json& timeline, double until) {
  TimelineParse out;
  out.entries = ordered_json::array();
  // A refusal gives only its errors: no change of a refused timeline is used.
  const auto refused = [](std::vector<FieldError> errors) {
    TimelineParse none;
    none.entries = ordered_json::array();
    none.errors = std::move(errors);
    return none;
  };
  const auto refuse = [&refused](const std::string& field, const json& value, const std::string& reason) {
    return refused({{field, value.dump(-1, ' ', false, json::error_handler_t::replace), reason}});
  };
  if (!timeline.is_array()) return refuse("timeline", timeline, "must be an array of {\"t\", \"patch\"}");
  json current = scene_to_json(scene);
  Scene current_scene = scene;
  double previous = 0.0;
  for (std::size_t i = 0; i < timeline.size(); ++i) {
    const json& entry = timeline[i];
    const std::string at = "timeline[" + std::to_string(i) + "]";
    if (!entry.is_object()) return refuse(at, entry, "must be an object {\"t\", \"patch\"}");
    for (const auto& [key, value] : entry.items())
      if (key != "t" && key != "patch")
        return refuse(at + "." + key, value, "is not a known field (t, patch)");
    const auto t = entry.find("t");
    if (t == entry.end() || !t->is_number())
      return refuse(at + ".t", entry.value("t", json()), "must be a number");
    const double time = t->get<double>();
    if (!std::isfinite(time) || time < previous || time > until)
      return refuse(at + ".t", *t,
                    "must be finite, not before the previous change (" + shortest(previous) +
                        ") and not after until (" + shortest(until) + ")");
    const auto patch = entry.find("patch");
    if (patch == entry.end() || !patch->is_object())
      return refuse(at + ".patch", entry.value("patch", json()),
                    "must be a JSON merge patch of the scene (an object)");
    json merged = current;
    merge_scene_patch(merged, *patch);
    SceneParse parsed = parse_scene(merged);
    if (!parsed.scene) {
      for (FieldError& e : parsed.errors) e.field = at + ".patch." + e.field;
      return refused(std::move(parsed.errors));
    }
    if (const std::string why = restart_reason(*patch, current_scene, *parsed.scene); !why.empty())
      return refuse(at + ".patch", *patch, "restarts the run (" + why + "): put it in the scene instead");
    current = scene_to_json(*parsed.scene);  // as the live session merges: onto the parsed scene
    current_scene = *parsed.scene;
    out.changes.push_back({time, *parsed.scene});
    out.entries.push_back({{"t", time}, {"patch", *patch}});
    previous = time;
  }
  return out;
}

}  // namespace spinfold
