// Numbers given by people, read and checked in one place: the allowed interval (Range), the one
// reader of a number written as text, and the one writer of the reason a number is refused
// ("must be a whole number from 16 to 4096 [pixels]", "must be a number in (0, 10]", "must be a
// number >= 0 [time]"). The view parameters (render/view_parameters.h), the run limits
// (engine/run_limits.h), the API's query parameters (server/route_table.cpp) and the CLI's and
// Python's checks all say it with these, so that every front door refuses a value in the same words.
// (A scene field's reason is engine/validation.h's range_reason, which names its own bounds.)
#pragma once

#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

#include "engine/number_text.h"

namespace spinfold {

// An interval of allowed values, each end open or closed; an infinite end is no bound. Every number
// must also be finite (and a scene's at most kMaxSceneMagnitude in magnitude, and one that must be
// > 0 at least kMinScenePositive: engine/validation.h).
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  bool min_open = false;
  double max = std::numeric_limits<double>::infinity();
  bool max_open = false;

  constexpr bool has_min() const { return min != -std::numeric_limits<double>::infinity(); }
  constexpr bool has_max() const { return max != std::numeric_limits<double>::infinity(); }
  constexpr bool contains(double v) const {
    return (min_open ? v > min : v >= min) && (max_open ? v < max : v <= max);
  }
};

inline constexpr Range kAnyNumber{};
inline constexpr Range kPositive{.min = 0.0, .min_open = true};
inline constexpr Range kNonNegative{.min = 0.0};

// The largest whole number every reader holds exactly (a double, a JSON number): 2^53.
inline constexpr double kMaxWholeNumber = 9007199254740992.0;

// What a number given by a person must be: a whole number or any number, in `range`, in `unit`.
struct NumberRule {
  bool whole = false;       // a whole number (an integer value; 16.0 and 1e3 are whole)
  Range range{};            // also finite; whole numbers at most kMaxWholeNumber in magnitude
  std::string_view unit{};  // "pixels", "rad", "time", …; "" for none
};

// The one reader of a number written as text (a CLI option, a query value, a sweep value): all of
// the text, a decimal in the C locale as std::from_chars reads it (no sign '+', no spaces), finite.
inline std::optional<double> number_from_text(std::string_view text) {
  double x = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || !std::isfinite(x))
    return std::nullopt;
  return x;
}

// Whether the rule allows x.
inline bool allows(const NumberRule& rule, double x) {
  if (!std::isfinite(x) || !rule.range.contains(x)) return false;
  return !rule.whole || (x == std::floor(x) && std::abs(x) <= kMaxWholeNumber);
}

// The one writer of what a number must be: "must be a whole number from 16 to 4096 [pixels]",
// "must be a number in (0, 10]", "must be a number >= 0 [time]", "must be a whole number >= 1".
inline std::string must_be(const NumberRule& rule) {
  const Range& r = rule.range;
  std::string text = rule.whole ? "must be a whole number" : "must be a number";
  if (r.has_min() && r.has_max())
    text += r.min_open || r.max_open ? std::string(" in ") + (r.min_open ? "(" : "[") + shortest(r.min) +
                                           ", " + shortest(r.max) + (r.max_open ? ")" : "]")
                                     : " from " + shortest(r.min) + " to " + shortest(r.max);
  else if (r.has_min())
    text += (r.min_open ? " > " : " >= ") + shortest(r.min);
  else if (r.has_max())
    text += (r.max_open ? " < " : " <= ") + shortest(r.max);
  if (!rule.unit.empty()) text += " [" + std::string(rule.unit) + "]";
  return text;
}

// nullopt when the rule allows x, else why not (must_be).
inline std::optional<std::string> refusal(const NumberRule& rule, double x) {
  if (allows(rule, x)) return std::nullopt;
  return must_be(rule);
}

// A refusal as the CLI and Python write it: "--pitch: must be a number from -1.55 to 1.55 [rad]
// (got '2')" — the name as the front door spells it, the reason, the value as given.
inline std::string refused(std::string_view name, std::string_view reason, std::string_view given) {
  return std::string(name) + ": " + std::string(reason) + " (got " + std::string(given) + ")";
}

}  // namespace spinfold
