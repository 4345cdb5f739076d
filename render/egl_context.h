// The EGL backend of GlContext: a pbuffer context on an EGL_EXT_platform_device device (a GPU when
// the machine has one) or on Mesa's EGL_MESA_platform_surfaceless (llvmpipe, no display or GPU).
#pragma once

#include <memory>

#include "render/gl_context.h"

namespace spinfold::render {

enum class EglPlatform {
  gpu_device,   // the first EGL device that is not Mesa's software one ("egl-device")
  surfaceless,  // Mesa's surfaceless platform ("egl-surfaceless")
};

// A GL 3.3+ core context with a 24-bit depth buffer on that platform, current at 64×64. Throws
// std::runtime_error saying what is missing.
std::unique_ptr<GlContext> make_egl_context(EglPlatform platform);

}  // namespace spinfold::render
