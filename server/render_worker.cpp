#include "server/render_worker.h"

#include <memory>

#include "render/renderer.h"

namespace spinfold::server {

RenderWorker::RenderWorker() : thread_([this] { loop(); }) {}

RenderWorker::~RenderWorker() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

std::future<std::vector<std::uint8_t>> RenderWorker::render(render::Snapshot snapshot,
                                                            render::ViewOptions view,
                                                            std::optional<int> jpeg_quality) {
  std::packaged_task<std::vector<std::uint8_t>(render::Renderer&)> task(
      [snapshot = std::move(snapshot), view, jpeg_quality](render::Renderer& renderer) {
        return jpeg_quality ? renderer.render_jpeg(snapshot, view, *jpeg_quality)
                            : renderer.render_png(snapshot, view);
      });
  auto result = task.get_future();
  {
    const std::lock_guard lock(mutex_);
    queue_.push_back(std::move(task));
  }
  wake_.notify_one();
  return result;
}

void RenderWorker::loop() {
  // Created, and warmed up, on this thread. Without a context every frame request fails (its
  // dropped task breaks the promise) and the server keeps serving everything else.
  std::unique_ptr<render::Renderer> renderer;
  try {
    renderer = std::make_unique<render::Renderer>();
  } catch (const std::exception&) {
  }
  for (;;) {
    std::packaged_task<std::vector<std::uint8_t>(render::Renderer&)> task;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;
      task = std::move(queue_.front());
      queue_.pop_front();
    }
    if (renderer) task(*renderer);
  }
}

}  // namespace spinfold::server
