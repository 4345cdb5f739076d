// Session ids are capabilities (server/sessions/session_id.h): base64url of 16 random bytes, checked
// against known encodings and a million draws.
#include "server/sessions/session_id.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_set>

namespace spinfold::server {
namespace {

constexpr std::string_view kBase64Url = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";

// The 16 bytes of an id (inverse of base64url).
std::array<std::uint8_t, 16> decoded(const std::string& id) {
  std::array<std::uint8_t, 16> bytes{};
  unsigned bits = 0, buffer = 0;
  std::size_t n = 0;
  for (char c : id) {
    buffer = (buffer << 6) | static_cast<unsigned>(kBase64Url.find(c));
    bits += 6;
    if (bits >= 8 && n < bytes.size()) {
      bits -= 8;
      bytes[n++] = static_cast<std::uint8_t>(buffer >> bits);
    }
  }
  return bytes;
}

TEST(SessionId, Base64UrlOfKnownBytes) {
  std::array<std::uint8_t, 16> bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(i);
  EXPECT_EQ(base64url(bytes), "AAECAwQFBgcICQoLDA0ODw");  // Python: urlsafe_b64encode, '=' stripped
  bytes.fill(0xff);
  EXPECT_EQ(base64url(bytes), "_____________________w");
  EXPECT_EQ(decoded("AAECAwQFBgcICQoLDA0ODw")[15], 15);
}

// A million draws: no repeat, 22 URL-safe characters each, and nothing to derive one id from the
// one before (no constant difference, every bit set about half the time).
TEST(SessionId, UniqueUrlSafeAndNotDerivable) {
  constexpr int kDraws = 1000000;
  std::unordered_set<std::string> seen;
  seen.reserve(kDraws);
  std::array<int, 128> ones{};
  std::uint64_t previous_high = 0, previous_difference = 0;
  int same_difference = 0;
  for (int i = 0; i < kDraws; ++i) {
    const std::string id = new_session_id();
    ASSERT_EQ(id.size(), 22u) << id;
    ASSERT_EQ(id.find_first_not_of(kBase64Url), std::string::npos) << id;
    ASSERT_TRUE(seen.insert(id).second) << "repeated id " << id << " after " << i << " draws";
    const auto bytes = decoded(id);
    ASSERT_EQ(base64url(bytes), id);
    for (int bit = 0; bit < 128; ++bit) ones[bit] += (bytes[bit / 8] >> (bit % 8)) & 1;
    std::uint64_t high = 0;
    for (int b = 0; b < 8; ++b) high = (high << 8) | bytes[b];
    const std::uint64_t difference = high - previous_high;
    same_difference += i > 1 && difference == previous_difference;
    previous_high = high;
    previous_difference = difference;
  }
  EXPECT_EQ(same_difference, 0);
  // Binomial(10^6, 1/2): standard deviation 500; 6 of them is far beyond chance.
  for (int bit = 0; bit < 128; ++bit) EXPECT_NEAR(ones[bit], kDraws / 2, 3000) << "bit " << bit;
}

}  // namespace
}  // namespace spinfold::server
