#include "render/gl_context.h"

#include <cstdlib>
#include <cstring>
#include <mutex>
#include <stdexcept>

#ifdef SPINFOLD_HAVE_EGL
#include "render/egl_context.h"
#endif
#ifdef SPINFOLD_HAVE_OSMESA
#include "render/osmesa_context.h"
#endif

namespace spinfold::render {

namespace {

thread_local const GlApi* current_api = nullptr;
thread_local GlContext* current_context = nullptr;

std::mutex& settings_mutex() {
  static std::mutex mutex;
  return mutex;
}
std::optional<GlBackend> chosen_backend;  // by set_gl_backend
GlInUse last_made;

}  // namespace

const GlApi* current_gl_api() {
  return current_api;
}
void set_current_gl_api(const GlApi* api) {
  current_api = api;
}

GlApi GlApi::load(ProcLookup lookup) {
  GlApi api;
#define SPINFOLD_GL_LOAD(name)                                              \
  api.fn_##name = reinterpret_cast<decltype(api.fn_##name)>(lookup(#name)); \
  if (!api.fn_##name) throw std::runtime_error("the GL context has no " + std::string(#name));
  SPINFOLD_GL_FUNCTIONS(SPINFOLD_GL_LOAD)
#undef SPINFOLD_GL_LOAD
  return api;
}

std::optional<GlBackend> parse_gl_backend(std::string_view name) {
  if (name == "auto") return GlBackend::automatic;
  if (name == "egl") return GlBackend::egl;
  if (name == "osmesa") return GlBackend::osmesa;
  return std::nullopt;
}

std::string_view gl_backend_name(GlBackend backend) {
  switch (backend) {
    case GlBackend::egl: return "egl";
    case GlBackend::osmesa: return "osmesa";
    case GlBackend::automatic: break;
  }
  return "auto";
}

std::string compiled_gl_backends() {
  std::string names;
#ifdef SPINFOLD_HAVE_EGL
  names += "egl";
#endif
#ifdef SPINFOLD_HAVE_OSMESA
  names += names.empty() ? "osmesa" : " osmesa";
#endif
  return names;
}

void set_gl_backend(GlBackend backend) {
  const std::lock_guard lock(settings_mutex());
  chosen_backend = backend;
}

GlBackend gl_backend_setting() {
  {
    const std::lock_guard lock(settings_mutex());
    if (chosen_backend) return *chosen_backend;
  }
  const char* env = std::getenv("SPINFOLD_GL");
  if (!env || !*env) return GlBackend::automatic;
  const std::optional<GlBackend> parsed = parse_gl_backend(env);
  if (!parsed)
    throw std::invalid_argument("SPINFOLD_GL: must be auto, egl or osmesa (not '" + std::string(env) + "')");
  return *parsed;
}

void GlContext::load_api(GlApi::ProcLookup lookup) {
  api_ = GlApi::load(lookup);
  bind_api();
  const auto* renderer = reinterpret_cast<const char*>(api_.fn_glGetString(GL_RENDERER));
  renderer_ = renderer ? renderer : "";
  GLint count = 0;
  api_.fn_glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const auto* extension = reinterpret_cast<const char*>(api_.fn_glGetStringi(GL_EXTENSIONS, i));
    if (extension && std::strcmp(extension, "GL_MESA_pack_invert") == 0) pack_invert_ = true;
  }
}

void GlContext::bind_api() const {
  current_api = &api_;
  current_context = const_cast<GlContext*>(this);
}

void GlContext::unbind_if_current() const {
  if (current_context != this) return;
  current_api = nullptr;
  current_context = nullptr;
}

bool GlContext::resize(int width, int height) {
  if (width == width_ && height == height_) return false;
  buffer_.assign(static_cast<std::size_t>(width) * height * 4, 0);
  width_ = width;
  height_ = height;
  return true;
}

void GlContext::read_back(unsigned fbo) {
  api_.fn_glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  api_.fn_glPixelStorei(GL_PACK_ALIGNMENT, 4);
  if (pack_invert_) api_.fn_glPixelStorei(GL_PACK_INVERT_MESA, GL_TRUE);
  api_.fn_glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, buffer_.data());
  if (pack_invert_) {
    api_.fn_glPixelStorei(GL_PACK_INVERT_MESA, GL_FALSE);
  } else {  // GL's rows come bottom-up (GPU drivers without the Mesa extension)
    const std::size_t row = static_cast<std::size_t>(width_) * 4;
    std::vector<std::uint8_t> swap(row);
    for (int top = 0, bottom = height_ - 1; top < bottom; ++top, --bottom) {
      std::uint8_t* a = buffer_.data() + top * row;
      std::uint8_t* b = buffer_.data() + bottom * row;
      std::memcpy(swap.data(), a, row);
      std::memcpy(a, b, row);
      std::memcpy(b, swap.data(), row);
    }
  }
}

GlContext* current_gl_context() {
  return current_context;
}

std::unique_ptr<GlContext> make_gl_context(GlBackend backend) {
  std::unique_ptr<GlContext> context;
  std::string why;
  const auto attempt = [&](auto make) {
    if (context) return;
    try {
      context = make();
    } catch (const std::exception& e) {
      why += why.empty() ? "" : "; ";
      why += e.what();
    }
  };
#ifdef SPINFOLD_HAVE_EGL
  if (backend != GlBackend::osmesa) {
    attempt([] { return make_egl_context(EglPlatform::gpu_device); });
    attempt([] { return make_egl_context(EglPlatform::surfaceless); });
  }
#endif
#ifdef SPINFOLD_HAVE_OSMESA
  if (backend != GlBackend::egl) attempt([] { return std::make_unique<OsmesaContext>(); });
#endif
  if (!context) {
    if (why.empty())
      why = "this build has no " + std::string(gl_backend_name(backend)) +
            " backend (it has: " + compiled_gl_backends() + ")";
    throw std::runtime_error("no GL context (--gl " + std::string(gl_backend_name(backend)) + "): " + why);
  }
  const std::lock_guard lock(settings_mutex());
  last_made = {context->name(), context->renderer()};
  return context;
}

std::unique_ptr<GlContext> make_gl_context() {
  return make_gl_context(gl_backend_setting());
}

GlInUse gl_in_use() {
  const std::lock_guard lock(settings_mutex());
  return last_made;
}

}  // namespace spinfold::render
