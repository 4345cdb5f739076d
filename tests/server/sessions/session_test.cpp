// The session store: its limit and the expiry of idle sessions.
#include <gtest/gtest.h>

#include <thread>

#include "server/sessions/session_store.h"

namespace spinfold::server {
namespace {

TEST(SessionStore, FullStoreRefusesAndIdleSessionsExpire) {
  Scene scene;
  scene.body.model = BodyModel::rigid;
  SessionStore store(2, std::chrono::seconds(1));
  std::string a, b, c;
  ASSERT_TRUE(store.create(scene, a));
  ASSERT_TRUE(store.create(scene, b));
  EXPECT_NE(a, b);
  EXPECT_FALSE(store.create(scene, c));  // full
  EXPECT_TRUE(store.find(a));
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  ASSERT_TRUE(store.create(scene, c));  // both idle sessions expired to make room
  EXPECT_FALSE(store.find(a));
  EXPECT_EQ(store.size(), 1u);
  EXPECT_TRUE(store.erase(c));
  EXPECT_FALSE(store.erase(c));
}

}  // namespace
}  // namespace spinfold::server
