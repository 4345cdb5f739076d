#include "server/frames/frame_cache.h"

namespace spinfold::server {

bool FrameCache::contains(const std::string& etag) {
  const std::lock_guard lock(mutex_);
  return frames_.contains(etag);
}

std::size_t FrameCache::bytes() {
  const std::lock_guard lock(mutex_);
  return bytes_;
}

void FrameCache::erase(std::unordered_map<std::string, Entry>::iterator it) {
  bytes_ -= it->second.bytes;
  order_.erase(it->second.order);
  frames_.erase(it);  // one being made is kept by its waiters' futures
}

void FrameCache::shrink() {
  while (!order_.empty() && (frames_.size() > max_frames_ || bytes_ > max_bytes_))
    erase(frames_.find(order_.back()));
}

void FrameCache::drop(const std::string& prefix) {
  const std::lock_guard lock(mutex_);
  for (auto it = frames_.begin(); it != frames_.end();) {
    const auto next = std::next(it);
    if (it->first.starts_with(prefix)) erase(it);
    it = next;
  }
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
      shrink();
    }
  }
  if (!maker) return frame.get();
  try {
    FrameBytes bytes = make();
    const std::size_t size = bytes ? bytes->size() : 0;
    made.set_value(std::move(bytes));
    const std::lock_guard lock(mutex_);
    if (const auto it = frames_.find(etag); it != frames_.end() && it->second.maker == maker) {
      it->second.bytes = size;
      bytes_ += size;
      shrink();  // a frame over the whole bound is served to its waiters and not kept
    }
  } catch (...) {
    made.set_exception(std::current_exception());
    const std::lock_guard lock(mutex_);
    if (const auto it = frames_.find(etag); it != frames_.end() && it->second.maker == maker) erase(it);
  }
  return frame.get();
}

}  // namespace spinfold::server
