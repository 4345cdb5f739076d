// The one place that owns an off-screen OpenGL context (OSMesa, llvmpipe). A context is bound to
// the thread that made it current; keep one renderer per thread. Swapping OSMesa for an EGL
// surfaceless context later touches only this file.
#pragma once

#include <cstdint>
#include <vector>

namespace spinfold::render {

class OsmesaContext {
 public:
  // A GL 3.3+ core context with a 24-bit depth buffer (none unless asked: platform-notes.md).
  // Throws std::runtime_error when OSMesa cannot provide one.
  OsmesaContext();
  ~OsmesaContext();
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;

  // Binds an RGBA colour buffer of this size [pixels] to the calling thread (rows top-down).
  void make_current(int width, int height);
  // The colour buffer after glFinish: width·height·4 bytes, first row on top.
  const std::uint8_t* pixels() const { return buffer_.data(); }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  void* context_ = nullptr;  // OSMesaContext
  std::vector<std::uint8_t> buffer_;
  int width_ = 0, height_ = 0;
};

// The colour buffer of the context current on this thread (as OsmesaContext::pixels(), rows
// top-down) and its size, or null when none is current. For the GL renderer, which reads its
// off-screen frame back into it (OSMesa's own copy of the default framebuffer happens at glFinish).
std::uint8_t* current_color_buffer(int& width, int& height);

}  // namespace spinfold::render
