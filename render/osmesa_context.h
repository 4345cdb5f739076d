// The OSMesa backend of GlContext (llvmpipe on the CPU). Upstream Mesa removed OSMesa in 25.1:
// the build leaves it out where Debian no longer ships it (SPINFOLD_OSMESA).
#pragma once

#include "render/gl_context.h"

namespace spinfold::render {

class OsmesaContext final : public GlContext {
 public:
  // A GL 3.3+ core context with a 24-bit depth buffer (none unless asked: docs/platform-notes.md),
  // current at 64×64. Throws std::runtime_error when OSMesa cannot provide one.
  OsmesaContext();
  ~OsmesaContext() override;

  void make_current(int width, int height) override;
  // The default framebuffer is already in pixels(): OSMesa copies it at glFinish.
  void read_back(unsigned fbo) override;

 private:
  void* context_ = nullptr;  // OSMesaContext
};

}  // namespace spinfold::render
