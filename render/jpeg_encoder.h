// JPEG encoding, GL-free: RGBA pixels in, baseline JPEG bytes out (libjpeg-turbo's TurboJPEG API,
// Debian libturbojpeg0-dev). For motion frames: a fraction of the PNG's bytes at a small, bounded
// error (docs/performance.md has the size/quality table the default comes from).
#pragma once

#include <cstdint>
#include <vector>

namespace spinfold::render {

// 1..100: 0.28 of the PNG's bytes on the default scene at 640x480, PSNR 31 dB, mean error 3/255
// (70 made 0.32 there but 0.36 on a frame with companions; progressive coding saves 7% for 8x the time).
inline constexpr int kDefaultJpegQuality = 60;

// 4:2:0 chroma subsampling, accurate DCT. Rows are top-down. Deterministic: same pixels and
// quality, same bytes.
std::vector<std::uint8_t> encode_jpeg(const std::uint8_t* rgba, int width, int height, int quality);

}  // namespace spinfold::render
