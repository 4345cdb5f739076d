// One thread owns the OpenGL context and renders every frame (a context is bound to a thread, and
// a dedicated thread costs ~30% less than binding it on whichever worker serves: platform-notes.md).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "render/renderer.h"
#include "render/snapshot.h"
#include "render/view.h"

namespace spinfold::server {

class RenderWorker {
 public:
  RenderWorker();
  ~RenderWorker();
  // The PNG of a snapshot (or, with a JPEG quality, its JPEG), rendered on the worker thread.
  std::future<std::vector<std::uint8_t>> render(render::Snapshot snapshot, render::ViewOptions view,
                                                std::optional<int> jpeg_quality = std::nullopt);

 private:
  void loop();
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::packaged_task<std::vector<std::uint8_t>(render::Renderer&)>> queue_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace spinfold::server
