// Encoded frames by ETag: a frame whose state and parameters have not changed is served from
// memory, not rendered again. Least recently used frames are dropped beyond the capacity.
#pragma once

#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

namespace spinfold::server {

using Png = std::shared_ptr<const std::vector<std::uint8_t>>;

class FrameCache {
 public:
  explicit FrameCache(std::size_t capacity) : capacity_(capacity) {}
  Png find(const std::string& etag);
  void insert(const std::string& etag, Png png);

 private:
  std::mutex mutex_;
  std::size_t capacity_;
  std::list<std::string> order_;  // most recently used first
  std::unordered_map<std::string, std::pair<Png, std::list<std::string>::iterator>> frames_;
};

}  // namespace spinfold::server
