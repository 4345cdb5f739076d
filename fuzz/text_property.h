// What the text fuzzers (scene_text_fuzzer, formula_fuzzer) do when a property fails: print it with
// the input that broke it, and abort (libFuzzer keeps the input as a crash).
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace spinfold::fuzz {

[[noreturn]] inline void violated(const char* what, std::string_view text) {
  std::fprintf(stderr, "property violated: %s\ninput: %.*s\n", what, static_cast<int>(text.size()),
               text.data());
  std::abort();
}

}  // namespace spinfold::fuzz
