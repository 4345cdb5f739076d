// Conversions from a double to an integer type that check the range first: a conversion out of
// range (or of NaN) is undefined behaviour in C++, and in practice gives INT64_MIN or garbage.
#pragma once

#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

namespace spinfold {

// x truncated towards zero when the result fits I (NaN and ±inf never do); nullopt otherwise.
template <class I>
std::optional<I> integer_within(double x) {
  static_assert(std::is_integral_v<I>);
  // I's range is [min, 2^digits): both ends are exact doubles (min is 0 or −2^digits).
  constexpr double lowest = static_cast<double>(std::numeric_limits<I>::min());
  const double above = std::ldexp(1.0, std::numeric_limits<I>::digits);
  const double whole = std::trunc(x);
  if (!(whole >= lowest && whole < above)) return std::nullopt;
  return static_cast<I>(whole);
}

// x truncated and clamped to [lo, hi]; NaN gives lo. For counts and sizes derived from a double
// that the caller bounds anyway; lo and hi within ±2^53 (exact as doubles).
template <class I>
I clamped_integer(double x, I lo, I hi) {
  static_assert(std::is_integral_v<I>);
  if (!(x >= static_cast<double>(lo))) return lo;
  if (!(x <= static_cast<double>(hi))) return hi;
  return static_cast<I>(x);
}

}  // namespace spinfold
