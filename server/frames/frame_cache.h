// Encoded frames by ETag: a frame whose state and parameters have not changed is served from
// memory, not rendered again, and a frame being made is made once for everyone who asks (16
// viewers of one playing session wait for one render). Least recently used frames are dropped
// beyond the capacity, counted in frames and in bytes (a 4096-px PNG is ~10 MB: 128 of them were
// a gigabyte), and a deleted session's frames at once.
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
  FrameCache(std::size_t max_frames, std::size_t max_bytes)
      : max_frames_(max_frames), max_bytes_(max_bytes) {}
  // Whether the frame is made or being made (does not wait).
  bool contains(const std::string& etag);
  // The frame of this ETag: from memory, from the one making it now, or made by `make` on this
  // thread. An exception from `make` reaches everyone waiting and nothing is kept.
  FrameBytes get(const std::string& etag, const std::function<FrameBytes()>& make);
  // Drops the frames whose ETag starts with `prefix` (a session's: frame_etag's "W/\"<id>-").
  void drop(const std::string& prefix);
  std::size_t bytes();  // of the frames kept (made ones)

 private:
  struct Entry {
    std::shared_future<FrameBytes> frame;
    std::list<std::string>::iterator order;
    std::uint64_t maker = 0;  // which get() makes it
    std::size_t bytes = 0;    // once made
  };
  void erase(std::unordered_map<std::string, Entry>::iterator it);  // with mutex_ held
  void shrink();  // to the bounds, least recently used first (with mutex_ held)
  std::mutex mutex_;
  std::uint64_t makers_ = 0;
  std::size_t max_frames_, max_bytes_;
  std::size_t bytes_ = 0;
  std::list<std::string> order_;  // most recently used first
  std::unordered_map<std::string, Entry> frames_;
};

}  // namespace spinfold::server
