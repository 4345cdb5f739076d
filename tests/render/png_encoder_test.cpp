// The PNG encoder: what it writes decodes (libpng, an independent reader) to the pixels given, the
// same input gives the same bytes, and threads encoding at once share a few compressors.
#include "render/png_encoder.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cstdint>
#include <random>
#include <thread>
#include <vector>

namespace spinfold::render {
namespace {

std::vector<std::uint8_t> random_rgba(int width, int height, unsigned seed) {
  std::mt19937 random(seed);
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * height * 4);
  for (auto& v : rgba) v = static_cast<std::uint8_t>(random());
  return rgba;
}

// RGB rows decoded by libpng's simplified API.
std::vector<std::uint8_t> decode_rgb(const std::vector<std::uint8_t>& png, int& width, int& height) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, png.data(), png.size())) return {};
  image.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> rgb(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, rgb.data(), 0, nullptr)) return {};
  width = static_cast<int>(image.width);
  height = static_cast<int>(image.height);
  return rgb;
}

TEST(PngEncoder, DecodesToThePixelsGivenAndTheSameInputGivesTheSameBytes) {
  const int w = 37, h = 23;  // odd sizes: no row padding to hide behind
  const auto rgba = random_rgba(w, h, 7);
  const std::vector<PngText> texts = {{"Software", "Spinfold"}, {"Comment", "ünïcode"}};
  const auto png = encode_png(rgba.data(), w, h, texts);
  int dw = 0, dh = 0;
  const auto rgb = decode_rgb(png, dw, dh);
  ASSERT_EQ(dw, w);
  ASSERT_EQ(dh, h);
  ASSERT_EQ(rgb.size(), static_cast<std::size_t>(w) * h * 3);
  for (std::size_t i = 0; i < static_cast<std::size_t>(w) * h; ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(rgb[3 * i + c], rgba[4 * i + c]) << "pixel " << i;
  EXPECT_EQ(encode_png(rgba.data(), w, h, texts), png);
}

TEST(PngEncoder, ThreadsEncodingAtOnceShareAFewCompressorsAndGetTheSameBytes) {
  const int w = 160, h = 120;
  const auto rgba = random_rgba(w, h, 8);
  const auto expected = encode_png(rgba.data(), w, h);
  std::vector<std::thread> threads;
  std::vector<int> same(48, 0);
  for (int t = 0; t < 48; ++t)
    threads.emplace_back([&, t] {
      for (int i = 0; i < 20; ++i) same[t] += encode_png(rgba.data(), w, h) == expected;
    });
  for (auto& thread : threads) thread.join();
  for (int t = 0; t < 48; ++t) EXPECT_EQ(same[t], 20) << "thread " << t;
  // 48 threads made no more than 16 kept (one each would be 48 × ~200 KiB).
  EXPECT_GE(png_compressors_kept(), 1u);
  EXPECT_LE(png_compressors_kept(), 16u);
}

}  // namespace
}  // namespace spinfold::render
