#include "server/http/byte_ranges.h"

#include <optional>
#include <vector>

namespace spinfold::server {

namespace {

constexpr std::uint64_t kMax = UINT64_MAX;

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// 1*DIGIT, saturated at 2^64 − 1; nullopt for anything else.
std::optional<std::uint64_t> digits(std::string_view s) {
  if (s.empty()) return std::nullopt;
  std::uint64_t n = 0;
  for (const char c : s) {
    if (c < '0' || c > '9') return std::nullopt;
    const auto d = static_cast<std::uint64_t>(c - '0');
    n = n > (kMax - d) / 10 ? kMax : n * 10 + d;
  }
  return n;
}

// One range-spec: int-range "first-[last]" or suffix-range "-N" (RFC 9110 §14.1.1).
struct Spec {
  bool suffix = false;
  std::uint64_t first = 0, last = kMax;  // suffix: `last` is the suffix length
};

std::optional<Spec> spec_of(std::string_view text) {
  const std::size_t dash = text.find('-');
  if (dash == std::string_view::npos) return std::nullopt;
  const std::string_view a = text.substr(0, dash), b = text.substr(dash + 1);
  Spec s;
  if (a.empty()) {
    const auto n = digits(b);
    if (!n) return std::nullopt;
    s.suffix = true;
    s.last = *n;
    return s;
  }
  const auto first = digits(a);
  if (!first) return std::nullopt;
  s.first = *first;
  if (!b.empty()) {
    const auto last = digits(b);
    if (!last || *last < *first) return std::nullopt;  // invalid (§14.1.1)
    s.last = *last;
  }
  return s;
}

bool is_bytes_unit(std::string_view unit) {
  if (unit.size() != 5) return false;
  for (std::size_t i = 0; i < 5; ++i)
    if ((unit[i] | 0x20) != "bytes"[i]) return false;
  return true;
}

}  // namespace

RangeAnswer answer_range(std::string_view header, std::uint64_t length) {
  RangeAnswer whole;
  const std::size_t equals = header.find('=');
  if (header.empty() || equals == std::string_view::npos || !is_bytes_unit(trimmed(header.substr(0, equals))))
    return whole;  // no Range, or a unit this server does not know: ignored (§14.2)
  std::vector<Spec> specs;
  std::string_view rest = header.substr(equals + 1);
  while (true) {
    const std::size_t comma = rest.find(',');
    const std::string_view one = trimmed(rest.substr(0, comma));
    if (!one.empty()) {  // empty list elements are allowed (RFC 9110 §5.6.1)
      const auto s = spec_of(one);
      if (!s) return whole;  // an invalid ranges-specifier: ignored
      specs.push_back(*s);
    }
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  if (specs.size() != 1) return whole;  // none, or several: the whole file (one policy, documented)
  const Spec& s = specs.front();
  RangeAnswer a;
  const bool satisfiable = s.suffix ? s.last > 0 && length > 0 : s.first < length;
  if (!satisfiable) {
    a.kind = RangeAnswer::Kind::unsatisfiable;
    a.content_range = "bytes */" + std::to_string(length);
    return a;
  }
  a.kind = RangeAnswer::Kind::partial;
  if (s.suffix) {
    a.first = s.last >= length ? 0 : length - s.last;
    a.last = length - 1;
  } else {
    a.first = s.first;
    a.last = s.last >= length ? length - 1 : s.last;
  }
  a.content_range =
      "bytes " + std::to_string(a.first) + "-" + std::to_string(a.last) + "/" + std::to_string(length);
  return a;
}

}  // namespace spinfold::server
