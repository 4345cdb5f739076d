// PNG encoding (libpng), GL-free: RGBA pixels in, RGB PNG bytes out.
#pragma once

#include <cstdint>
#include <vector>

namespace spinfold::render {

// zlib level 1 and no filtering: ~5 ms instead of ~26 ms at 640x480 for ~30% larger files
// (platform-notes.md). Rows are top-down. Deterministic: same pixels, same bytes.
std::vector<std::uint8_t> encode_png(const std::uint8_t* rgba, int width, int height);

}  // namespace spinfold::render
