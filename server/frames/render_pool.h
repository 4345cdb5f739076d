// The render pool: N threads, each owning an OpenGL context (a context is bound to one thread, and
// a dedicated thread costs ~30% less than binding it on whichever worker serves: docs/platform-notes.md).
// Threads only render; the caller encodes the pixels, so a render thread never waits on encoding
// or on a client. Frames with the same key (a session) are rendered one at a time, in the order
// they were asked for; frames of different keys run in parallel. Background frames (recordings)
// wait while a live frame is waiting, and take at most threads − 1 threads (with more than one),
// so that live viewers always have a thread.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "render/renderer.h"
#include "render/snapshot.h"
#include "render/view.h"

namespace spinfold::server {

// Live frames (frame.png, the live stream) go before background ones (recordings).
enum class RenderPriority { live, background };

class RenderPool {
 public:
  // Told on the render thread when a frame starts and ends: its key and its number (frames are
  // numbered from 1 in the order asked for). For tests and metrics.
  using Observer = std::function<void(const std::string& key, std::uint64_t number, bool started)>;

  // threads: 0 for one per core. A thread idle for `idle_release` frees what its renderer keeps
  // for the next frame (render::Renderer::release_memory: tens of MB per frame size).
  explicit RenderPool(int threads, Observer observer = {},
                      std::chrono::milliseconds idle_release = std::chrono::seconds(20));
  ~RenderPool();
  RenderPool(const RenderPool&) = delete;
  RenderPool& operator=(const RenderPool&) = delete;

  int threads() const { return static_cast<int>(threads_.size()); }
  // Threads past their start: the context made and its shaders compiled (or failed). Until then a
  // thread takes a core compiling (tens of ms, seconds under sanitizers).
  int started() const { return started_.load(); }
  // Times a thread gave its renderer's memory back after idle_release without a frame.
  int releases() const { return releases_.load(); }
  // The frame's pixels. Without a GL context the future holds std::future_error (broken promise).
  std::future<render::Image> render(std::string key, render::Snapshot snapshot, render::ViewOptions view,
                                    RenderPriority priority = RenderPriority::live);

 private:
  struct Task {
    std::string key;
    std::uint64_t number = 0;
    RenderPriority priority = RenderPriority::live;
    std::packaged_task<render::Image(render::Renderer&)> work;
  };
  void loop();
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Task> queue_;
  std::set<std::string> busy_;  // keys being rendered now
  int background_busy_ = 0;     // background frames being rendered now
  int thread_count_ = 0;
  bool stopping_ = false;
  std::uint64_t asked_ = 0;  // frames asked for so far
  std::atomic<int> started_{0};
  std::atomic<int> releases_{0};
  std::chrono::milliseconds idle_release_;
  Observer observer_;
  std::vector<std::thread> threads_;
};

}  // namespace spinfold::server
