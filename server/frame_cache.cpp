#include "server/frame_cache.h"

namespace spinfold::server {

Png FrameCache::find(const std::string& etag) {
  const std::lock_guard lock(mutex_);
  const auto it = frames_.find(etag);
  if (it == frames_.end()) return nullptr;
  order_.splice(order_.begin(), order_, it->second.second);
  return it->second.first;
}

void FrameCache::insert(const std::string& etag, Png png) {
  const std::lock_guard lock(mutex_);
  if (const auto it = frames_.find(etag); it != frames_.end()) {
    it->second.first = std::move(png);
    order_.splice(order_.begin(), order_, it->second.second);
    return;
  }
  order_.push_front(etag);
  frames_[etag] = {std::move(png), order_.begin()};
  while (frames_.size() > capacity_) {
    frames_.erase(order_.back());
    order_.pop_back();
  }
}

}  // namespace spinfold::server
