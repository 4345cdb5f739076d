// PNG encoding, GL-free: RGBA pixels in, RGB PNG bytes out. The PNG container is written here
// (signature, IHDR, one IDAT, IEND); the compression and CRC are libdeflate's (Debian
// libdeflate-dev), which is 1.5x faster than libpng + zlib at level 1 with 4% smaller files
// (docs/performance.md).
#pragma once

#include <cstdint>
#include <vector>

namespace spinfold::render {

// Level 1 and no filtering (filters cost more time than they save bytes on these frames). Rows are
// top-down. Deterministic: same pixels, same bytes.
std::vector<std::uint8_t> encode_png(const std::uint8_t* rgba, int width, int height);

}  // namespace spinfold::render
