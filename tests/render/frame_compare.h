// Comparing a rendered frame with a pinned one across CPUs. llvmpipe compiles its shaders for the
// CPU it runs on, so a frame pinned on one machine moves by a level here and there on another
// (docs/performance.md, "Across CPUs"): the comparison allows that jitter and nothing
// with a shape (a moved line, a missing glyph, a missing body).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace spinfold::test {

// RGB pixels, rows top-down.
struct RgbImage {
  int width = 0, height = 0;  // [pixels]
  std::vector<std::uint8_t> rgb;
};

// What may differ between a golden frame and a render on another CPU. The defaults are the measured
// jitter of llvmpipe's code for other CPUs with a margin (docs/performance.md, "Across CPUs").
struct FrameTolerance {
  double max_differing_fraction = 0.01;  // of all pixels, differing at all (measured: 0.46%)
  int jitter_level = 3;                  // a pixel differing by more than this in a channel [levels] (2)
  int max_over_jitter = 16;              // pixels allowed beyond jitter_level, edge pixels (4)
  int block = 16;                        // side of the blocks checked for structure [pixels]
  int max_over_jitter_in_block = 4;      // pixels beyond jitter_level in any one block (1)
};

// The difference of two frames. Pixels count once however many channels differ.
struct FrameDifference {
  bool same_size = false;
  long pixels = 0;        // in each frame
  long differing = 0;     // pixels differing at all
  int max_level = 0;      // largest difference of a channel [levels]
  long over_jitter = 0;   // pixels differing by more than the tolerance's jitter_level
  int worst_block = 0;    // the most over-jitter pixels in one block
  int worst_block_x = 0;  // that block's top-left corner [pixels]
  int worst_block_y = 0;
  double fraction() const { return pixels ? static_cast<double>(differing) / pixels : 1.0; }
};

FrameDifference compare_frames(const RgbImage& expected, const RgbImage& actual,
                               const FrameTolerance& tolerance);
bool within(const FrameDifference& d, const FrameTolerance& tolerance);
// One line: every metric beside its bound.
std::string describe(const FrameDifference& d, const FrameTolerance& tolerance);

// The expected frame in grey, pixels over the jitter level in red, other differing pixels in blue.
RgbImage difference_image(const RgbImage& expected, const RgbImage& actual, const FrameTolerance& tolerance);

// PNG through libpng's simplified API; nullopt when the bytes or file are not a PNG.
std::optional<RgbImage> decode_png(const std::vector<std::uint8_t>& bytes);
std::optional<RgbImage> read_png(const std::filesystem::path& path);
bool write_png(const std::filesystem::path& path, const RgbImage& image);

// The golden check: writes `actual` to `actual_png` (to look at, or to pin) and compares it with the
// PNG at `golden`. Empty when within the tolerance; otherwise writes the difference image beside it
// (`<name>.diff.png`) and returns the metrics and both paths.
std::string golden_mismatch(const std::vector<std::uint8_t>& actual, const std::filesystem::path& golden,
                            const std::filesystem::path& actual_png, const FrameTolerance& tolerance = {});

}  // namespace spinfold::test
