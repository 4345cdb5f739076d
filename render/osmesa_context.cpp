#include "render/osmesa_context.h"

#include <GL/osmesa.h>

#include <stdexcept>

namespace spinfold::render {

OsmesaContext::OsmesaContext() {
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            24,
                            OSMESA_STENCIL_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            3,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            3,
                            0};
  context_ = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!context_)
    throw std::runtime_error("OSMesa could not create a GL 3.3 core context with a depth buffer");
}

OsmesaContext::~OsmesaContext() {
  if (context_) OSMesaDestroyContext(static_cast<OSMesaContext>(context_));
}

void OsmesaContext::make_current(int width, int height) {
  if (width != width_ || height != height_) {
    buffer_.assign(static_cast<std::size_t>(width) * height * 4, 0);
    width_ = width;
    height_ = height;
  }
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(context_), buffer_.data(), GL_UNSIGNED_BYTE, width,
                         height))
    throw std::runtime_error("OSMesaMakeCurrent failed");
  OSMesaPixelStore(OSMESA_Y_UP, 0);  // top-down rows: PNG order at no cost
}

std::uint8_t* current_color_buffer(int& width, int& height) {
  const OSMesaContext context = OSMesaGetCurrentContext();
  int format = 0;
  void* buffer = nullptr;
  if (!context || !OSMesaGetColorBuffer(context, &width, &height, &format, &buffer)) return nullptr;
  return static_cast<std::uint8_t*>(buffer);
}

}  // namespace spinfold::render
