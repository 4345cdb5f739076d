#include "render/jpeg_encoder.h"

#include <turbojpeg.h>

#include <memory>
#include <stdexcept>
#include <string>

namespace spinfold::render {

namespace {

struct HandleFree {
  void operator()(void* handle) const { tjDestroy(handle); }
};

// One compressor per thread: its set-up costs more than a small frame.
tjhandle compressor() {
  thread_local std::unique_ptr<void, HandleFree> handle(tjInitCompress());
  if (!handle) throw std::runtime_error("libjpeg-turbo: cannot create a compressor");
  return handle.get();
}

}  // namespace

std::vector<std::uint8_t> encode_jpeg(const std::uint8_t* rgba, int width, int height, int quality) {
  tjhandle handle = compressor();
  // libjpeg-turbo's own buffer (malloc'd, not zeroed; tjBufSize's worst case is ~3 bytes a pixel,
  // so a zeroed buffer of our own cost a 2.8 MB memset and its page faults per 1280x720 frame),
  // copied out at its size.
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  const int failed = tjCompress2(handle, rgba, width, 0, height, TJPF_RGBX, &buffer, &size, TJSAMP_420,
                                 quality, TJFLAG_ACCURATEDCT);
  const std::unique_ptr<unsigned char, decltype(&tjFree)> owned(buffer, &tjFree);
  if (failed != 0) throw std::runtime_error(std::string("libjpeg-turbo: ") + tjGetErrorStr2(handle));
  return std::vector<std::uint8_t>(buffer, buffer + size);
}

}  // namespace spinfold::render
