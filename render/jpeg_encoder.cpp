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
  std::vector<std::uint8_t> out(tjBufSize(width, height, TJSAMP_420));
  unsigned char* buffer = out.data();
  unsigned long size = out.size();
  // TJFLAG_NOREALLOC: into our buffer, sized by tjBufSize for the worst case.
  if (tjCompress2(handle, rgba, width, 0, height, TJPF_RGBX, &buffer, &size, TJSAMP_420, quality,
                  TJFLAG_NOREALLOC | TJFLAG_ACCURATEDCT) != 0)
    throw std::runtime_error(std::string("libjpeg-turbo: ") + tjGetErrorStr2(handle));
  out.resize(size);
  return out;
}

}  // namespace spinfold::render
