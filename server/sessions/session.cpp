#include "server/sessions/session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "codec/sample_json.h"
#include "codec/scene_json.h"
#include "codec/timeline_json.h"
#include "engine/number_text.h"
#include "engine/path_circle.h"
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

ordered_json session_sample(const Session& session) {
  ordered_json sample = sample_to_json(session.run, session.run.state.t);
  const CircleReadout circle = circle_readout(session.run, session.trail);
  const auto number = [](const std::optional<double>& v) {
    return v ? ordered_json(*v) : ordered_json(nullptr);
  };
  sample["circle"] = {{"measured", number(circle.measured)},
                      {"predicted", number(circle.predicted.radius)},
                      {"line", circle_line(session.run.scene, circle)}};
  return sample;
}

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

AdvanceEnd advance(Session& session, double t, std::uint64_t max_attempts, double max_seconds) {
  const auto start = std::chrono::steady_clock::now();
  AdvanceEnd end = AdvanceEnd::reached;
  for (std::uint64_t left = max_attempts;;) {
    const std::uint64_t slice = std::min(left, kAdvanceSliceAttempts);
    if (advance_sampling_trail(session.run, session.trail, t, slice)) break;
    left -= slice;  // a slice that did not reach t spent all its attempts
    if (left == 0) {
      end = AdvanceEnd::attempts;
      break;
    }
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= max_seconds) {
      end = AdvanceEnd::seconds;
      break;
    }
  }
  state_changed(session);
  return end;
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
    out.reason = continued_reason(0.0);
    return out;
  }
  retune_carrying_trail(session.run, session.trail, *parsed.scene);
  session.timeline.push_back({{"t", t}, {"patch", patch}});
  session.changes.push_back({t, *parsed.scene});
  sample_trail_if_due(session.trail, session.run);
  state_changed(session);
  out.reason = continued_reason(t);
  return out;
}

Rebuild rebuild(Session& session, const Scene& scene, const json& timeline, double until,
                std::uint64_t max_attempts) {
  TimelineParse parsed = parse_timeline(scene, timeline, until);
  Rebuild out;
  if (!parsed.errors.empty()) {
    out.errors = std::move(parsed.errors);
    return out;
  }
  session.scene = scene;
  session.timeline = std::move(parsed.entries);
  session.changes = std::move(parsed.changes);
  session.trail = Trail{};
  out.complete = replay(scene, session.changes, until, session.run, session.trail, max_attempts);
  state_changed(session);
  return out;
}

}  // namespace spinfold::server
