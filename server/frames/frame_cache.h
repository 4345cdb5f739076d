// Encoded frames by ETag: a frame whose state and parameters have not changed is served from
// memory, not rendered again, and a frame being made is made once for everyone who asks (16
// viewers of one playing session wait for one render). Least recently used frames are dropped
// beyond the capacity.
#pragma once

#include <cstdint>
#include <functional>
#include <future>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

namespace spinfold::server {

using FrameBytes = std::shared_ptr<const std::vector<std::uint8_t>>;  // a PNG or a JPEG

class FrameCache {
 public:
  explicit FrameCache(std::size_t capacity) : capacity_(capacity) {}
  // Whether the frame is made or being made (does not wait).
  bool contains(const std::string& etag);
  // The frame of this ETag: from memory, from the one making it now, or made by `make` on this
  // thread. An exception from `make` reaches everyone waiting and nothing is kept.
  FrameBytes get(const std::string& etag, const std::function<FrameBytes()>& make);

 private:
  struct Entry {
    std::shared_future<FrameBytes> frame;
    std::list<std::string>::iterator order;
    std::uint64_t maker = 0;  // which get() makes it
  };
  std::mutex mutex_;
  std::uint64_t makers_ = 0;
  std::size_t capacity_;
  std::list<std::string> order_;  // most recently used first
  std::unordered_map<std::string, Entry> frames_;
};

}  // namespace spinfold::server
