// The limits of a run as every front door takes them: its end time, sampling interval and budgets,
// and the most samples and sweep runs one request may ask for. `spinfold simulate`/`render`/`sweep`
// (--t-end, --every, --max-steps, --max-seconds, --t) and Python's simulate/run_many/sweep/render
// (t_end, every, max_steps, threads, t) check their values against these rows and refuse them in the
// rows' words (engine/number_rule.h), so that they refuse alike.
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "engine/number_rule.h"

namespace spinfold {

// The most samples one run may be asked for (t_end / every), and the most runs one sweep may hold.
inline constexpr double kMaxSamples = 1e7;
inline constexpr std::size_t kMaxRuns = 10'000'000;

struct RunLimit {
  std::string_view name;  // Python's keyword; the CLI's option is "--" + name with '-' for '_'
  NumberRule rule;
  std::string_view help;
};

inline constexpr RunLimit kRunLimits[] = {
    {"t_end", {.range = kNonNegative, .unit = "time"}, "simulated time to reach"},
    {"every", {.range = kPositive, .unit = "time"}, "sample interval"},
    {"t", {.range = kNonNegative, .unit = "time"}, "the time of the picture"},
    {"max_steps", {.whole = true, .range = {.min = 1.0, .max = kMaxWholeNumber}}, "step attempts at most"},
    {"max_seconds", {.range = kPositive, .unit = "s"}, "wall time at most"},
    {"threads",
     {.whole = true, .range = {.min = 1.0, .max = 4096.0}},
     "threads of a batch (none: one per core)"},
};

inline const RunLimit& run_limit(std::string_view name) {
  for (const RunLimit& l : kRunLimits)
    if (l.name == name) return l;
  throw std::logic_error("no run limit named " + std::string(name));
}

// The CLI's option for a run limit: "--max-steps".
inline std::string run_limit_option(std::string_view name) {
  std::string option = "--" + std::string(name);
  for (char& c : option)
    if (c == '_') c = '-';
  return option;
}

// Why t_end and every ask for too many samples, or nullopt (both already allowed by their rows).
inline std::optional<std::string> samples_refusal(double t_end, double every) {
  if (t_end / every > kMaxSamples) return "more than 1e7 samples requested";
  return std::nullopt;
}

// Why a sweep of `runs` runs is refused, or nullopt.
inline std::optional<std::string> runs_refusal(double runs) {
  if (runs > static_cast<double>(kMaxRuns)) return "more than " + std::to_string(kMaxRuns) + " runs";
  return std::nullopt;
}

}  // namespace spinfold
