// A run's timeline as the API and the store write it: [{"t": T, "patch": MERGE_PATCH}, …], the
// parameter changes (engine/timeline.h) that rebuild a session bit for bit.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "engine/timeline.h"
#include "engine/validation.h"

namespace spinfold {

struct TimelineParse {
  std::vector<ParameterChange> changes;  // the scene in force from each entry's t on
  nlohmann::ordered_json entries;        // the timeline as it is kept and written back
  std::vector<FieldError> errors;        // non-empty: refused, naming the entry (timeline[i].t, …)
};

// Reads a timeline over `scene` up to `until` [time]: entries in time order, none after until,
// each patch a merge patch that continues the run (restart_reason is "").
TimelineParse parse_timeline(const Scene& scene, const nlohmann::json& timeline, double until);

}  // namespace spinfold
