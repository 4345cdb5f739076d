#include "server/render_pool.h"

#include <algorithm>
#include <memory>

namespace spinfold::server {

RenderPool::RenderPool(int threads, Observer observer) : observer_(std::move(observer)) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (int i = 0; i < threads; ++i) threads_.emplace_back([this] { loop(); });
}

RenderPool::~RenderPool() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (auto& thread : threads_) thread.join();
}

std::future<render::Image> RenderPool::render(std::string key, render::Snapshot snapshot,
                                              render::ViewOptions view) {
  std::packaged_task<render::Image(render::Renderer&)> work(
      [snapshot = std::move(snapshot), view](render::Renderer& renderer) {
        return renderer.render_image(snapshot, view);
      });
  auto result = work.get_future();
  {
    const std::lock_guard lock(mutex_);
    queue_.push_back({std::move(key), ++asked_, std::move(work)});
  }
  wake_.notify_one();
  return result;
}

void RenderPool::loop() {
  // Created, and warmed up, on this thread. Without a context every frame request fails (its
  // dropped task breaks the promise) and the server keeps serving everything else.
  std::unique_ptr<render::Renderer> renderer;
  try {
    renderer = std::make_unique<render::Renderer>();
  } catch (const std::exception&) {
  }
  ++started_;
  for (;;) {
    Task task;
    {
      std::unique_lock lock(mutex_);
      // The oldest task whose key no other thread is rendering: the first of its key, so a key's
      // frames come out in order.
      auto next = queue_.end();
      wake_.wait(lock, [&] {
        next =
            std::find_if(queue_.begin(), queue_.end(), [&](const Task& t) { return !busy_.contains(t.key); });
        return stopping_ || next != queue_.end();
      });
      if (next == queue_.end()) return;  // stopping, nothing left to take
      task = std::move(*next);
      queue_.erase(next);
      busy_.insert(task.key);
    }
    if (observer_) observer_(task.key, task.number, true);
    if (renderer) task.work(*renderer);
    if (observer_) observer_(task.key, task.number, false);
    {
      const std::lock_guard lock(mutex_);
      busy_.erase(task.key);
    }
    wake_.notify_all();  // a task of this key may be waiting for it
  }
}

}  // namespace spinfold::server
