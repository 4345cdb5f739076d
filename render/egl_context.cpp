#include "render/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <stdexcept>
#include <string>

namespace spinfold::render {

namespace {

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t length = std::strlen(name);
  for (const char* at = std::strstr(list, name); at; at = std::strstr(at + 1, name))
    if ((at == list || at[-1] == ' ') && (at[length] == ' ' || at[length] == '\0')) return true;
  return false;
}

// An initialised display on the platform. Displays are per process and shared by every render
// thread's context, so none is ever terminated.
EGLDisplay open_display(EglPlatform platform) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  EGLDisplay display = EGL_NO_DISPLAY;
  if (platform == EglPlatform::surfaceless) {
    if (!has_extension(client, "EGL_MESA_platform_surfaceless"))
      throw std::runtime_error("EGL has no EGL_MESA_platform_surfaceless");
    display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  } else {
    if (!has_extension(client, "EGL_EXT_platform_device") ||
        !has_extension(client, "EGL_EXT_device_enumeration"))
      throw std::runtime_error("EGL has no EGL_EXT_platform_device");
    const auto query_devices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    const auto query_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!query_devices || !query_string || !query_devices(16, devices, &count))
      throw std::runtime_error("EGL could not list its devices");
    for (EGLint i = 0; i < count && display == EGL_NO_DISPLAY; ++i) {
      // Mesa lists llvmpipe as a device too; the surfaceless platform is the way to that one.
      if (has_extension(query_string(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software")) continue;
      EGLDisplay candidate = eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
      if (candidate != EGL_NO_DISPLAY && eglInitialize(candidate, nullptr, nullptr)) display = candidate;
    }
    if (display == EGL_NO_DISPLAY) throw std::runtime_error("EGL found no GPU device");
    return display;
  }
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr))
    throw std::runtime_error("EGL could not initialise the surfaceless display");
  return display;
}

class EglContext final : public GlContext {
 public:
  explicit EglContext(EglPlatform platform)
      : GlContext(platform == EglPlatform::gpu_device ? "egl-device" : "egl-surfaceless"),
        display_(open_display(platform)) {
    const EGLint config_attributes[] = {EGL_SURFACE_TYPE,
                                        EGL_PBUFFER_BIT,
                                        EGL_RENDERABLE_TYPE,
                                        EGL_OPENGL_BIT,
                                        EGL_RED_SIZE,
                                        8,
                                        EGL_GREEN_SIZE,
                                        8,
                                        EGL_BLUE_SIZE,
                                        8,
                                        EGL_ALPHA_SIZE,
                                        8,
                                        EGL_DEPTH_SIZE,
                                        24,
                                        EGL_NONE};
    EGLint count = 0;
    if (!eglChooseConfig(display_, config_attributes, &config_, 1, &count) || count < 1)
      throw std::runtime_error(name() + ": no RGBA8 + depth 24 pbuffer config for desktop GL");
    if (!eglBindAPI(EGL_OPENGL_API)) throw std::runtime_error(name() + ": no desktop OpenGL API");
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         3,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         3,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
    context_ = eglCreateContext(display_, config_, EGL_NO_CONTEXT, context_attributes);
    if (context_ == EGL_NO_CONTEXT)
      throw std::runtime_error(name() + ": could not create a GL 3.3 core context");
    make_current(64, 64);
    load_api([](const char* function) { return eglGetProcAddress(function); });
  }

  ~EglContext() override {
    if (current_gl_context() == this)
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    unbind_if_current();
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
    eglDestroyContext(display_, context_);
  }

  // A pbuffer of the frame's size: the default framebuffer that the renderer's aliased path draws
  // into; other frames are drawn into the renderer's own framebuffers and read back from those.
  void make_current(int width, int height) override {
    if (resize(width, height) || surface_ == EGL_NO_SURFACE) {
      if (surface_ != EGL_NO_SURFACE) {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroySurface(display_, surface_);
      }
      const EGLint attributes[] = {EGL_WIDTH, width, EGL_HEIGHT, height, EGL_NONE};
      surface_ = eglCreatePbufferSurface(display_, config_, attributes);
      if (surface_ == EGL_NO_SURFACE)
        throw std::runtime_error(name() + ": no " + std::to_string(width) + "x" + std::to_string(height) +
                                 " pbuffer");
    }
    if (eglGetCurrentContext() != context_ || eglGetCurrentSurface(EGL_DRAW) != surface_)
      if (!eglMakeCurrent(display_, surface_, surface_, context_))
        throw std::runtime_error(name() + ": eglMakeCurrent failed");
    bind_api();
  }

 private:
  EGLDisplay display_;
  EGLConfig config_ = nullptr;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface surface_ = EGL_NO_SURFACE;
};

}  // namespace

std::unique_ptr<GlContext> make_egl_context(EglPlatform platform) {
  return std::make_unique<EglContext>(platform);
}

}  // namespace spinfold::render
