#include "server/frames/frame_cache.h"

namespace spinfold::server {

bool FrameCache::contains(const std::string& etag) {
  const std::lock_guard lock(mutex_);
  return frames_.contains(etag);
}

FrameBytes FrameCache::get(const std::string& etag, const std::function<FrameBytes()>& make) {
  std::promise<FrameBytes> made;
  std::shared_future<FrameBytes> frame;
  std::uint64_t maker = 0;  // this call's number when it makes the frame
  {
    const std::lock_guard lock(mutex_);
    if (const auto it = frames_.find(etag); it != frames_.end()) {
      order_.splice(order_.begin(), order_, it->second.order);
      frame = it->second.frame;
    } else {
      maker = ++makers_;
      frame = made.get_future().share();
      order_.push_front(etag);
      frames_[etag] = {frame, order_.begin(), maker};
      while (frames_.size() > capacity_) {
        frames_.erase(order_.back());  // one being made is kept by its waiters' futures
        order_.pop_back();
      }
    }
  }
  if (!maker) return frame.get();
  try {
    made.set_value(make());
  } catch (...) {
    made.set_exception(std::current_exception());
    const std::lock_guard lock(mutex_);
    if (const auto it = frames_.find(etag); it != frames_.end() && it->second.maker == maker) {
      order_.erase(it->second.order);
      frames_.erase(it);
    }
  }
  return frame.get();
}

}  // namespace spinfold::server
