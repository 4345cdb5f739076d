#include "server/sessions/session_id.h"

#include <sys/random.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace spinfold::server {

std::string base64url(const std::array<std::uint8_t, 16>& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";
  std::string text;
  text.reserve(22);
  // 3 bytes → 4 characters; the last byte alone → 2 characters (its 8 bits, 4 zero bits of padding).
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const std::uint32_t v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    for (int shift = 18; shift >= 0; shift -= 6) text += kAlphabet[(v >> shift) & 63];
  }
  const std::uint32_t last = bytes[i];
  text += kAlphabet[last >> 2];
  text += kAlphabet[(last & 3) << 4];
  return text;
}

std::string new_session_id() {
  std::array<std::uint8_t, 16> bytes{};
  std::size_t got = 0;
  while (got < bytes.size()) {
    // getrandom(2) from the urandom pool: blocks only before the pool is first initialised at boot.
    const ssize_t n = getrandom(bytes.data() + got, bytes.size() - got, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error(std::string("getrandom: ") + std::strerror(errno));
    got += static_cast<std::size_t>(n);
  }
  return base64url(bytes);
}

}  // namespace spinfold::server
