#include "render/osmesa_context.h"

#include <GL/osmesa.h>

#include <stdexcept>

namespace spinfold::render {

OsmesaContext::OsmesaContext() : GlContext("osmesa") {
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
  make_current(64, 64);
  load_api([](const char* name) { return reinterpret_cast<void (*)()>(OSMesaGetProcAddress(name)); });
}

OsmesaContext::~OsmesaContext() {
  if (current_gl_context() == this) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
  unbind_if_current();
  if (context_) OSMesaDestroyContext(static_cast<OSMesaContext>(context_));
}

void OsmesaContext::make_current(int width, int height) {
  resize(width, height);
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(context_), buffer_.data(), GL_UNSIGNED_BYTE, width,
                         height))
    throw std::runtime_error("OSMesaMakeCurrent failed");
  OSMesaPixelStore(OSMESA_Y_UP, 0);  // top-down rows: PNG order at no cost
  bind_api();
}

void OsmesaContext::read_back(unsigned fbo) {
  if (fbo != 0) GlContext::read_back(fbo);
}

}  // namespace spinfold::render
