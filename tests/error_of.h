// The message of the exception of type E that a call throws, or "(no error)": tests assert on the
// words a refusal uses (the field, the value, the reason).
#pragma once

#include <string>

namespace spinfold::test {

template <typename E, typename Call>
std::string error_of(const Call& call) {
  try {
    call();
  } catch (const E& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace spinfold::test
