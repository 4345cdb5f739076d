#include "render/png_encoder.h"

#include <libdeflate.h>

#include <array>
#include <cstring>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace spinfold::render {

namespace {

struct CompressorFree {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};

using Compressor = std::unique_ptr<libdeflate_compressor, CompressorFree>;

// Compressors kept between encodings (allocating one costs more than a small frame's compression),
// shared by every thread rather than one per thread: a server has ~160 HTTP workers, and a
// compressor is ~200 KiB (32 MiB of them in the soak, docs/performance.md). As many are kept as
// have been encoding at once, up to kKept.
constexpr std::size_t kKept = 16;
std::mutex pool_mutex;
std::vector<Compressor>& pool() {
  static std::vector<Compressor> kept;
  return kept;
}

// A compressor while in scope, back in the pool after.
class Lease {
 public:
  Lease() {
    {
      const std::lock_guard lock(pool_mutex);
      if (!pool().empty()) {
        c_ = std::move(pool().back());
        pool().pop_back();
      }
    }
    if (!c_) c_.reset(libdeflate_alloc_compressor(1));
    if (!c_) throw std::runtime_error("libdeflate: cannot allocate a compressor");
  }
  ~Lease() {
    const std::lock_guard lock(pool_mutex);
    if (pool().size() < kKept) pool().push_back(std::move(c_));
  }
  Lease(const Lease&) = delete;
  Lease& operator=(const Lease&) = delete;
  libdeflate_compressor* get() const { return c_.get(); }

 private:
  Compressor c_;
};

// Big-endian, as PNG writes every integer.
void put32(std::uint8_t* at, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) at[k] = static_cast<std::uint8_t>(v >> (24 - 8 * k));
}

// A PNG chunk: length, type, data, CRC-32 of type and data (PNG spec §5.3).
void chunk(std::vector<std::uint8_t>& out, std::string_view type, const std::uint8_t* data,
           std::size_t size) {
  const std::size_t at = out.size();
  out.resize(at + 12 + size);
  std::uint8_t* p = out.data() + at;
  put32(p, static_cast<std::uint32_t>(size));
  std::memcpy(p + 4, type.data(), 4);
  if (size > 0) std::memcpy(p + 8, data, size);
  put32(p + 8 + size, libdeflate_crc32(0, p + 4, 4 + size));
}

bool ascii(std::string_view s) {
  for (const unsigned char c : s)
    if (c >= 0x80) return false;
  return true;
}

// tEXt: keyword, NUL, text; iTXt: keyword, NUL, no compression (0, 0), no language tag, NUL, no
// translated keyword, NUL, UTF-8 text. A NUL inside the text would end it early: dropped.
void text_chunk(std::vector<std::uint8_t>& out, const PngText& text) {
  std::string keyword = text.first.substr(0, 79);
  if (keyword.empty()) keyword = "Comment";
  std::string value;
  for (char c : text.second)
    if (c != '\0') value += c;
  const bool plain = ascii(keyword) && ascii(value);
  std::string data = keyword + '\0';
  if (!plain) data += std::string("\0\0", 2) + '\0' + '\0';
  data += value;
  chunk(out, plain ? "tEXt" : "iTXt", reinterpret_cast<const std::uint8_t*>(data.data()), data.size());
}

}  // namespace

std::vector<std::uint8_t> encode_png(const std::uint8_t* rgba, int width, int height,
                                     std::span<const PngText> texts) {
  const std::size_t w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
  // Scanlines: filter type 0 (none) and the RGB bytes.
  std::vector<std::uint8_t> raw(h * (1 + 3 * w));
  for (std::size_t y = 0; y < h; ++y) {
    std::uint8_t* row = raw.data() + y * (1 + 3 * w);
    const std::uint8_t* src = rgba + y * w * 4;
    row[0] = 0;
    for (std::size_t x = 0; x < w; ++x) {
      row[1 + 3 * x] = src[4 * x];
      row[2 + 3 * x] = src[4 * x + 1];
      row[3 + 3 * x] = src[4 * x + 2];
    }
  }
  const Lease lease;
  libdeflate_compressor* c = lease.get();
  std::vector<std::uint8_t> idat(libdeflate_zlib_compress_bound(c, raw.size()));
  const std::size_t compressed =
      libdeflate_zlib_compress(c, raw.data(), raw.size(), idat.data(), idat.size());
  if (compressed == 0) throw std::runtime_error("libdeflate: compression failed");

  std::vector<std::uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  out.reserve(compressed + 64);
  // IHDR: width, height, bit depth 8, colour type 2 (RGB), compression 0, filter 0, interlace 0.
  std::array<std::uint8_t, 13> header{};
  put32(header.data(), static_cast<std::uint32_t>(width));
  put32(header.data() + 4, static_cast<std::uint32_t>(height));
  header[8] = 8;
  header[9] = 2;
  chunk(out, "IHDR", header.data(), header.size());
  for (const PngText& text : texts) text_chunk(out, text);
  chunk(out, "IDAT", idat.data(), compressed);
  chunk(out, "IEND", nullptr, 0);
  return out;
}

std::size_t png_compressors_kept() {
  const std::lock_guard lock(pool_mutex);
  return pool().size();
}

}  // namespace spinfold::render
