// Session ids are capabilities: whoever knows one controls that session, so an id is 128 bits from
// the operating system's random source, never derived from a counter or a clock.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace spinfold::server {

// A new session id: 16 bytes of getrandom(2), base64url without padding (22 characters of
// A-Z a-z 0-9 - _). Throws std::runtime_error when the random source fails (never a weaker id).
std::string new_session_id();

// base64url (RFC 4648 §5) of 16 bytes without padding: 22 characters.
std::string base64url(const std::array<std::uint8_t, 16>& bytes);

}  // namespace spinfold::server
