// The render pool (server/frames/render_pool.h): one frame at a time per key, in the order asked for,
// frames of other keys meanwhile; live frames before background ones (recordings).
#include "server/frames/render_pool.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <future>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "engine/simulation.h"
#include "engine/trail.h"
#include "render/snapshot.h"

namespace spinfold::server {
namespace {

using namespace std::chrono_literals;

// With one thread, a live frame asked after a background one is drawn first; with two, background
// frames never take both threads, so a live frame starts while a background one is drawn.
TEST(RenderPool, LiveFramesGoBeforeBackgroundOnes) {
  const Scene scene = *parse_scene_text(find_preset("spin_vs_geodesic_sphere")->json).scene;
  const Simulation run = start_simulation(scene);
  render::ViewOptions view;
  view.width = 32;
  view.height = 24;
  const auto snapshot = [&] { return render::make_snapshot(run, Trail{}, -1.0); };
  for (const int threads : {1, 2}) {
    std::mutex mutex;
    std::condition_variable changed;
    bool release = false;
    std::vector<std::string> started;
    RenderPool pool(threads, [&](const std::string& key, std::uint64_t, bool start) {
      std::unique_lock lock(mutex);
      if (!start) return;
      started.push_back(key);
      changed.notify_all();
      if (key == "hold") changed.wait(lock, [&] { return release; });  // holds this thread
    });
    std::vector<std::future<render::Image>> frames;
    const auto priority = threads == 1 ? RenderPriority::live : RenderPriority::background;
    frames.push_back(pool.render("hold", snapshot(), view, priority));
    {
      std::unique_lock lock(mutex);
      changed.wait(lock, [&] { return !started.empty(); });
    }
    frames.push_back(pool.render("recording", snapshot(), view, RenderPriority::background));
    frames.push_back(pool.render("live", snapshot(), view, RenderPriority::live));
    if (threads == 2) {  // the live frame gets the free thread; the background one waits for "hold"
      std::unique_lock lock(mutex);
      ASSERT_TRUE(changed.wait_for(lock, 20s, [&] { return started.size() == 2; }));
      std::this_thread::sleep_for(50ms);  // the background frame would have started by now
      EXPECT_EQ(started, (std::vector<std::string>{"hold", "live"}));
    }
    {
      const std::lock_guard lock(mutex);
      release = true;
    }
    changed.notify_all();
    for (auto& f : frames) EXPECT_EQ(f.get().rgba.size(), 32u * 24u * 4u);
    EXPECT_EQ(started, (std::vector<std::string>{"hold", "live", "recording"})) << threads << " threads";
  }
}

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

// A thread idle for idle_release gives its renderer's memory back once (not again while idle), and
// the next frame is drawn as before it, pixel for pixel (the targets and meshes are made again).
TEST(RenderPool, AnIdleThreadGivesItsMemoryBackAndDrawsTheSameAfter) {
  const Scene scene = *parse_scene_text(find_preset("spin_vs_geodesic_sphere")->json).scene;
  const Simulation run = start_simulation(scene);
  render::ViewOptions view;
  view.width = 320;
  view.height = 240;
  RenderPool pool(1, {}, 100ms);
  const render::Image before = pool.render("a", render::make_snapshot(run, Trail{}, -1.0), view).get();
  EXPECT_EQ(pool.releases(), 0);  // nothing drawn and released before the first frame
  for (int i = 0; i < 500 && pool.releases() < 1; ++i) std::this_thread::sleep_for(10ms);
  EXPECT_EQ(pool.releases(), 1);
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(pool.releases(), 1);  // idle still, with nothing more to give back
  const render::Image after = pool.render("a", render::make_snapshot(run, Trail{}, -1.0), view).get();
  EXPECT_EQ(after.rgba, before.rgba);
  for (int i = 0; i < 500 && pool.releases() < 2; ++i) std::this_thread::sleep_for(10ms);
  EXPECT_EQ(pool.releases(), 2);
}

}  // namespace
}  // namespace spinfold::server
