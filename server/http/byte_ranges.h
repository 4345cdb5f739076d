// Byte ranges by RFC 9110 §14: what a GET of a file answers to its Range header. One range is
// served (206 with Content-Range); a header that asks for several is answered with the whole file
// (RFC 9110 §14.2: a server MAY ignore Range), so no multipart/byteranges is ever made. cpp-httplib
// 0.11 applied ranges to every answer (errors and PATCH lost their bodies), computed an unsigned
// underflow for a first byte beyond the end, and refused an unknown unit: the connection's stream
// renames the header before httplib reads it (kRangeHeader), and only this reads it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace spinfold::server {

// The name a request's Range header reaches the routes under (same length as "Range", so that the
// stream renames it in place; a client's own header of this name is renamed away in turn).
inline constexpr std::string_view kRangeHeader = "Rnge_";

struct RangeAnswer {
  enum class Kind {
    whole,          // 200 with the whole file: no Range, another unit, an invalid or multiple ranges
    partial,        // 206: bytes first..last (inclusive) of length
    unsatisfiable,  // 416 with Content-Range "bytes */length"
  };
  Kind kind = Kind::whole;
  std::uint64_t first = 0, last = 0;  // partial: inclusive
  // The Content-Range value: "bytes first-last/length" (partial), "bytes */length" (unsatisfiable).
  std::string content_range;
};

// The answer to `header` (the Range field's value; empty: none) for a representation of `length`
// bytes. Numbers of any size are read (saturated: a last beyond the end is the end, a first
// beyond it is unsatisfiable); `bytes` is matched case-insensitively; whitespace around commas is
// allowed. Invalid syntax (a sign, a last before the first, an empty list) is ignored: the whole.
RangeAnswer answer_range(std::string_view header, std::uint64_t length);

}  // namespace spinfold::server
