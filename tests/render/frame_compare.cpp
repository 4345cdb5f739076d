#include "frame_compare.h"

#include <png.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>

namespace spinfold::test {

namespace {

// The largest difference of a channel at pixel i.
int level_at(const RgbImage& a, const RgbImage& b, std::size_t i) {
  int level = 0;
  for (int c = 0; c < 3; ++c)
    level = std::max(level, std::abs(int(a.rgb[3 * i + c]) - int(b.rgb[3 * i + c])));
  return level;
}

}  // namespace

FrameDifference compare_frames(const RgbImage& expected, const RgbImage& actual,
                               const FrameTolerance& tolerance) {
  FrameDifference d;
  d.pixels = static_cast<long>(expected.width) * expected.height;
  d.same_size = expected.width == actual.width && expected.height == actual.height &&
                expected.rgb.size() == actual.rgb.size() && expected.rgb.size() == 3 * std::size_t(d.pixels);
  if (!d.same_size) return d;
  const int side = std::max(1, tolerance.block);
  const int columns = (expected.width + side - 1) / side;
  std::vector<int> blocks(static_cast<std::size_t>(columns) * ((expected.height + side - 1) / side));
  for (int y = 0; y < expected.height; ++y)
    for (int x = 0; x < expected.width; ++x) {
      const int level = level_at(expected, actual, static_cast<std::size_t>(y) * expected.width + x);
      if (level == 0) continue;
      ++d.differing;
      d.max_level = std::max(d.max_level, level);
      if (level <= tolerance.jitter_level) continue;
      ++d.over_jitter;
      int& block = blocks[static_cast<std::size_t>(y / side) * columns + x / side];
      if (++block > d.worst_block) {
        d.worst_block = block;
        d.worst_block_x = x / side * side;
        d.worst_block_y = y / side * side;
      }
    }
  return d;
}

bool within(const FrameDifference& d, const FrameTolerance& tolerance) {
  return d.same_size && d.fraction() <= tolerance.max_differing_fraction &&
         d.over_jitter <= tolerance.max_over_jitter && d.worst_block <= tolerance.max_over_jitter_in_block;
}

std::string describe(const FrameDifference& d, const FrameTolerance& tolerance) {
  if (!d.same_size) return "the frames differ in size";
  char text[512];
  std::snprintf(text, sizeof text,
                "%ld of %ld pixels differ (%.4f%%, at most %.4f%%); largest channel difference %d levels; "
                "%ld pixels beyond %d levels (at most %d); at most %d of them in one %dx%d block (at most "
                "%d), at (%d, %d)",
                d.differing, d.pixels, 100.0 * d.fraction(), 100.0 * tolerance.max_differing_fraction,
                d.max_level, d.over_jitter, tolerance.jitter_level, tolerance.max_over_jitter, d.worst_block,
                tolerance.block, tolerance.block, tolerance.max_over_jitter_in_block, d.worst_block_x,
                d.worst_block_y);
  return text;
}

RgbImage difference_image(const RgbImage& expected, const RgbImage& actual, const FrameTolerance& tolerance) {
  RgbImage out{expected.width, expected.height, std::vector<std::uint8_t>(expected.rgb.size())};
  const bool comparable = compare_frames(expected, actual, {.block = 1}).same_size;
  for (std::size_t i = 0; i < expected.rgb.size() / 3; ++i) {
    const auto grey = static_cast<std::uint8_t>(
        128 + (int(expected.rgb[3 * i]) + expected.rgb[3 * i + 1] + expected.rgb[3 * i + 2]) / 6);  // faded
    const int level = comparable ? level_at(expected, actual, i) : 255;
    const std::uint8_t* colour = nullptr;
    static constexpr std::uint8_t red[3] = {255, 0, 0}, blue[3] = {0, 64, 255};
    if (level > tolerance.jitter_level)
      colour = red;
    else if (level > 0)
      colour = blue;
    for (int c = 0; c < 3; ++c) out.rgb[3 * i + c] = colour ? colour[c] : grey;
  }
  return out;
}

std::optional<RgbImage> decode_png(const std::vector<std::uint8_t>& bytes) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) return std::nullopt;
  image.format = PNG_FORMAT_RGB;
  RgbImage out{static_cast<int>(image.width), static_cast<int>(image.height),
               std::vector<std::uint8_t>(PNG_IMAGE_SIZE(image))};
  if (!png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr)) return std::nullopt;
  return out;
}

std::optional<RgbImage> read_png(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return decode_png({std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()});
}

bool write_png(const std::filesystem::path& path, const RgbImage& image) {
  png_image out{};
  out.version = PNG_IMAGE_VERSION;
  out.width = static_cast<png_uint_32>(image.width);
  out.height = static_cast<png_uint_32>(image.height);
  out.format = PNG_FORMAT_RGB;
  return png_image_write_to_file(&out, path.c_str(), 0, image.rgb.data(), 0, nullptr) != 0;
}

std::string golden_mismatch(const std::vector<std::uint8_t>& actual, const std::filesystem::path& golden,
                            const std::filesystem::path& actual_png, const FrameTolerance& tolerance) {
  std::filesystem::create_directories(actual_png.parent_path());
  std::ofstream(actual_png, std::ios::binary)
      .write(reinterpret_cast<const char*>(actual.data()), actual.size());
  const std::optional<RgbImage> expected = read_png(golden);
  const std::optional<RgbImage> got = decode_png(actual);
  if (!expected || !got)
    return (expected ? "the frame is not a PNG" : "no golden frame at " + golden.string()) + "; look at " +
           actual_png.string() + " and pin it if it is right";
  const FrameDifference d = compare_frames(*expected, *got, tolerance);
  if (within(d, tolerance)) return "";
  std::filesystem::path diff = actual_png;
  diff.replace_extension(".diff.png");
  write_png(diff, difference_image(*expected, *got, tolerance));
  return "frame differs from " + golden.string() + ": " + describe(d, tolerance) + "; see " +
         actual_png.string() + " and " + diff.string() + " (red: beyond the jitter, blue: within it)";
}

}  // namespace spinfold::test
