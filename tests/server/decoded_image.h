// Pixels of the frames the server sends, for comparing pictures: RGB rows, top first.
#pragma once

#include <png.h>
#include <turbojpeg.h>

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

namespace spinfold::server {

// RGB pixels of an image: PNG through libpng's simplified API, JPEG through TurboJPEG.
inline std::vector<std::uint8_t> png_pixels(const std::string& bytes, int& width, int& height) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) return {};
  image.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(image));
  png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr);
  width = static_cast<int>(image.width);
  height = static_cast<int>(image.height);
  return pixels;
}

inline std::vector<std::uint8_t> jpeg_pixels(const std::string& bytes, int width, int height) {
  tjhandle handle = tjInitDecompress();
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(width) * height * 3);
  const int failed = tjDecompress2(handle, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(),
                                   pixels.data(), width, 0, height, TJPF_RGB, TJFLAG_ACCURATEDCT);
  tjDestroy(handle);
  return failed ? std::vector<std::uint8_t>{} : pixels;
}

// Mean absolute difference per channel [of 255] of two RGB images of one size (255 if they differ in size).
inline double mean_difference(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  if (a.size() != b.size() || a.empty()) return 255.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += std::abs(int(a[i]) - int(b[i]));
  return sum / static_cast<double>(a.size());
}

}  // namespace spinfold::server
