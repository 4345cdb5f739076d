#include "server/frames/render_pool.h"

#include <algorithm>
#include <memory>

namespace spinfold::server {

RenderPool::RenderPool(int threads, Observer observer, std::chrono::milliseconds idle_release)
    : idle_release_(idle_release), observer_(std::move(observer)) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  thread_count_ = threads;  // before any thread reads it
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
                                              render::ViewOptions view, RenderPriority priority) {
  std::packaged_task<render::Image(render::Renderer&)> work(
      [snapshot = std::move(snapshot), view](render::Renderer& renderer) {
        return renderer.render_image(snapshot, view);
      });
  auto result = work.get_future();
  {
    const std::lock_guard lock(mutex_);
    queue_.push_back({std::move(key), ++asked_, priority, std::move(work)});
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
  bool holding = false;  // memory kept for the next frame since the last one
  for (;;) {
    Task task;
    {
      std::unique_lock lock(mutex_);
      // The oldest live task whose key no other thread is rendering (the first of its key, so a
      // key's frames come out in order); else the oldest such background task, while background
      // frames hold fewer than threads − 1 threads.
      const int background_threads = std::max(1, thread_count_ - 1);
      auto next = queue_.end();
      const auto ready = [&] {
        const auto free_of = [&](RenderPriority p) {
          return std::find_if(queue_.begin(), queue_.end(),
                              [&](const Task& t) { return t.priority == p && !busy_.contains(t.key); });
        };
        next = free_of(RenderPriority::live);
        if (next == queue_.end() && background_busy_ < background_threads)
          next = free_of(RenderPriority::background);
        return stopping_ || next != queue_.end();
      };
      if (holding && !wake_.wait_for(lock, idle_release_, ready)) {
        lock.unlock();
        if (renderer) renderer->release_memory();
        holding = false;
        ++releases_;
        continue;
      }
      wake_.wait(lock, ready);
      if (next == queue_.end()) return;  // stopping, nothing left to take
      task = std::move(*next);
      queue_.erase(next);
      busy_.insert(task.key);
      if (task.priority == RenderPriority::background) ++background_busy_;
    }
    if (observer_) observer_(task.key, task.number, true);
    if (renderer) task.work(*renderer);
    holding = true;
    if (observer_) observer_(task.key, task.number, false);
    {
      const std::lock_guard lock(mutex_);
      busy_.erase(task.key);
      if (task.priority == RenderPriority::background) --background_busy_;
    }
    wake_.notify_all();  // a task of this key may be waiting for it
  }
}

}  // namespace spinfold::server
