// PNG encoding, GL-free: RGBA pixels in, RGB PNG bytes out. The PNG container is written here
// (signature, IHDR, one IDAT, IEND); the compression and CRC are libdeflate's (Debian
// libdeflate-dev), which is 1.5x faster than libpng + zlib at level 1 with 4% smaller files
// (docs/performance.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace spinfold::render {

// A text chunk: keyword (1–79 printable Latin-1 characters) and text. Written as tEXt when both are
// ASCII, as iTXt (UTF-8, uncompressed) otherwise (PNG spec §11.3.4).
using PngText = std::pair<std::string, std::string>;

// Level 1 and no filtering (filters cost more time than they save bytes on these frames). Rows are
// top-down. The text chunks (provenance: codec/provenance.h) come before the image data.
// Deterministic: same pixels and texts, same bytes.
std::vector<std::uint8_t> encode_png(const std::uint8_t* rgba, int width, int height,
                                     std::span<const PngText> texts = {});

// The compressors kept for the next encodings (as many as have encoded at once, at most 16), shared
// by all threads.
std::size_t png_compressors_kept();

}  // namespace spinfold::render
