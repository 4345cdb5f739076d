// The render pool (server/render_pool.h): one frame at a time per key, in the order asked for,
// frames of other keys meanwhile.
#include "server/render_pool.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <future>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "engine/simulation.h"
#include "engine/trail.h"
#include "render/snapshot.h"

namespace spinfold::server {
namespace {

// The render pool renders a session's frames one at a time in the order asked for, frames of
// other sessions meanwhile.
TEST(RenderPool, FramesOfOneKeyInOrderOneAtATime) {
  std::mutex mutex;
  std::vector<std::pair<std::string, std::uint64_t>> started;
  std::map<std::string, int> running;
  bool overlapped = false;
  RenderPool pool(2, [&](const std::string& key, std::uint64_t number, bool start) {
    const std::lock_guard lock(mutex);
    if (start) {
      started.emplace_back(key, number);
      overlapped |= ++running[key] > 1;
    } else {
      --running[key];
    }
  });
  const Scene scene = *parse_scene_text(find_preset("spin_vs_geodesic_sphere")->json).scene;
  const Simulation run = start_simulation(scene);
  render::ViewOptions view;
  view.width = 64;
  view.height = 48;
  std::vector<std::future<render::Image>> frames;
  for (int i = 0; i < 12; ++i) {
    const Trail trail;
    frames.push_back(pool.render(i % 3 == 0 ? "b" : "a", render::make_snapshot(run, trail, -1.0), view));
  }
  for (auto& f : frames) EXPECT_EQ(f.get().rgba.size(), 64u * 48u * 4u);
  EXPECT_FALSE(overlapped);
  std::map<std::string, std::uint64_t> last;
  for (const auto& [key, number] : started) {
    EXPECT_GT(number, last[key]) << key;
    last[key] = number;
  }
  EXPECT_EQ(started.size(), 12u);
}

}  // namespace
}  // namespace spinfold::server
