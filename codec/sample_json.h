// One sample of a run as a JSON object: the CLI's JSON Lines record and the API's state.
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

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

// The numbers of one body's sample without building JSON (the Python binding's arrays): in the
// order of sample_value_names() (codec/sample_table.h), NaN where the JSON sample has null or
// leaves the value out. The same doubles as sample_to_json's, to the bit.
void sample_values(const Readout& readout, std::span<double> out);
// The sample's "undefined": {field, reason} of every value that is null.
std::vector<std::pair<std::string, std::string>> undefined_values(const Readout& readout);
// The same without building it: fn(prefix, field, reason) for each, the name being prefix + field.
template <typename F>
void for_each_undefined(const Readout& r, F&& fn) {
  for (const UndefinedValue& u : r.coordinates.undefined) fn(std::string_view(), u.field, u.reason);
  for (const UndefinedValue& u : r.undefined) fn(std::string_view(), u.field, u.reason);
  if (r.actions) {
    for (const UndefinedValue& u : r.actions->undefined) {
      const bool frequency = u.field.starts_with("nu_");
      fn(frequency ? std::string_view("frequencies.") : std::string_view("actions."),
         frequency ? std::string_view(u.field).substr(3) : std::string_view(u.field), u.reason);
    }
  } else {
    fn(std::string_view(), std::string_view("actions"), r.actions_unsupported);
  }
}

}  // namespace spinfold
