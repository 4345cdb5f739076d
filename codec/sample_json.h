// One sample of a run as a JSON object: the CLI's JSON Lines record and the API's state.
#pragma once

#include <nlohmann/json.hpp>
#include <span>

#include "engine/readout.h"
#include "engine/simulation.h"

namespace spinfold {

// Paper coordinates, rates, momenta, X, L, det L, invariants, status and provenance.
// Undefined values are null and listed under "undefined" with the reason; "events" are the
// det L = 0 crossings after time `events_since` (the previous sample's). A run with companions
// has "companions": [sample, …], each with its "label" and its own events and status.
nlohmann::ordered_json sample_to_json(const Simulation& run, double events_since);
// One body's sample from a read-out already made (engine/readout.h): the HUD shows the same
// values; `new_events` are given.
nlohmann::ordered_json sample_to_json(const Readout& readout, std::span<const DegenerateEvent> new_events);

}  // namespace spinfold
