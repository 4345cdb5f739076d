#include "server/sessions/session.h"

#include <cmath>
#include <cstdio>

#include "codec/sample_json.h"
#include "codec/scene_json.h"
#include "engine/number_text.h"
#include "server/sessions/session_id.h"

namespace spinfold::server {

using nlohmann::json;
using nlohmann::ordered_json;

namespace {

// The state changed: frames and bodies cached for the old one are stale.
void state_changed(Session& session) {
  ++session.version;
}

}  // namespace

std::string state_tag(const Session& session) {
  char text[96];
  if (session.stored_version != 0) {
    std::snprintf(text, sizeof text, "r%lld-%.17g", static_cast<long long>(session.stored_version),
                  session.run.state.t);
  } else {
    static const std::string process = new_session_id().substr(0, 11);  // 66 random bits
    std::snprintf(text, sizeof text, "m%s-%llu", process.c_str(),
                  static_cast<unsigned long long>(session.version));
  }
  return text;
}

void restart(Session& session, const Scene& scene) {
  session.scene = scene;
  session.timeline = ordered_json::array();
  session.changes.clear();
  session.run = start_simulation(scene);
  session.trail = Trail{};
  sample_trail_if_due(session.trail, session.run);
  state_changed(session);
}

bool advance(Session& session, double t, std::uint64_t max_attempts) {
  const bool complete = advance_sampling_trail(session.run, session.trail, t, max_attempts);
  state_changed(session);
  return complete;
}

ChangeOutcome change(Session& session, const json& patch) {
  ChangeOutcome out;
  json document = scene_to_json(session.run.scene);
  json merged = document;
  merge_scene_patch(merged, patch);
  const SceneParse parsed = parse_scene(merged);
  if (!parsed.scene) {
    out.errors = parsed.errors;
    return out;
  }
  if (scene_to_json(*parsed.scene) == document) {
    out.reason = "the patch changes nothing";
    return out;
  }
  const double t = session.run.state.t;
  if (std::string why = restart_reason(patch, session.run.scene, *parsed.scene); !why.empty()) {
    restart(session, *parsed.scene);
    out.kind = ChangeOutcome::restarted;
    out.reason = why;
    return out;
  }
  out.kind = ChangeOutcome::continued;
  if (t == 0.0 && session.changes.empty()) {
    // Nothing has happened yet: the change is the scene itself.
    restart(session, *parsed.scene);
    out.reason = "new parameters from t = 0";
    return out;
  }
  retune_carrying_trail(session.run, session.trail, *parsed.scene);
  session.timeline.push_back({{"t", t}, {"patch", patch}});
  session.changes.push_back({t, *parsed.scene});
  sample_trail_if_due(session.trail, session.run);
  state_changed(session);
  out.reason = "new parameters from t = " + shortest(t) + " on, continuing from the current state";
  return out;
}

Rebuild rebuild(Session& session, const Scene& scene, const json& timeline, double until,
                std::uint64_t max_attempts) {
  Rebuild out;
  const auto refuse = [&out](const std::string& field, const json& value, const std::string& reason) {
    out.errors.push_back({field, value.dump(-1, ' ', false, json::error_handler_t::replace), reason});
    return out;
  };
  if (!timeline.is_array()) return refuse("timeline", timeline, "must be an array of {\"t\", \"patch\"}");
  std::vector<ParameterChange> changes;
  ordered_json entries = ordered_json::array();
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
      out.errors = parsed.errors;
      return out;
    }
    if (const std::string why = restart_reason(*patch, current_scene, *parsed.scene); !why.empty())
      return refuse(at + ".patch", *patch, "restarts the run (" + why + "): put it in the scene instead");
    current = scene_to_json(*parsed.scene);  // as the live session merges: onto the parsed scene
    current_scene = *parsed.scene;
    changes.push_back({time, *parsed.scene});
    entries.push_back({{"t", time}, {"patch", *patch}});
    previous = time;
  }
  session.scene = scene;
  session.timeline = entries;
  session.changes = changes;
  session.trail = Trail{};
  out.complete = replay(scene, changes, until, session.run, session.trail, max_attempts);
  state_changed(session);
  return out;
}

}  // namespace spinfold::server
