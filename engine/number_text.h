// Numbers written for people and for round trips: the shortest decimal that reads back to the
// same double (1e-10, 1000, -0.1; never 0.000000 nor 9.9999999999999997e+199).
#pragma once

#include <charconv>
#include <string>

namespace spinfold {

inline std::string shortest(double value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

inline std::string shortest(long long value) {
  return std::to_string(value);
}

}  // namespace spinfold
