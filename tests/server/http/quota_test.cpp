// Who the client is behind the front: the trusted proxy as one address or an IPv4 network.
#include "server/http/quota.h"

#include <gtest/gtest.h>

namespace {

using spinfold::server::is_trusted_proxy;

TEST(TrustedProxy, OneAddressOrAnIpv4Network) {
  EXPECT_TRUE(is_trusted_proxy("127.0.0.1", "127.0.0.1"));
  EXPECT_FALSE(is_trusted_proxy("127.0.0.2", "127.0.0.1"));
  EXPECT_FALSE(is_trusted_proxy("127.0.0.1", ""));  // "" never trusts the header
  EXPECT_TRUE(is_trusted_proxy("10.244.3.17", "10.244.0.0/16"));
  EXPECT_FALSE(is_trusted_proxy("10.245.0.1", "10.244.0.0/16"));
  EXPECT_TRUE(is_trusted_proxy("10.251.0.3", "10.251.0.3/32"));
  EXPECT_FALSE(is_trusted_proxy("10.251.0.4", "10.251.0.3/32"));
  EXPECT_TRUE(is_trusted_proxy("192.168.1.1", "0.0.0.0/0"));
  // Malformed networks and non-IPv4 peers trust nothing.
  EXPECT_FALSE(is_trusted_proxy("10.0.0.1", "10.0.0.0/33"));
  EXPECT_FALSE(is_trusted_proxy("10.0.0.1", "10.0.0/8"));
  EXPECT_FALSE(is_trusted_proxy("::1", "10.0.0.0/8"));
}

}  // namespace
