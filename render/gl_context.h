// An off-screen OpenGL 3.3+ core context with a depth buffer, from one of two backends chosen at
// run time: EGL (a GPU device, else Mesa's surfaceless llvmpipe) or OSMesa (llvmpipe; removed from
// Mesa in 25.1, hence EGL). A context is bound to the thread that made it current; keep one
// renderer per thread.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "render/gl_api.h"

namespace spinfold::render {

// What `--gl` and SPINFOLD_GL ask for. auto: an EGL GPU device, else EGL surfaceless, else OSMesa.
enum class GlBackend { automatic, egl, osmesa };

// "auto" | "egl" | "osmesa"; nullopt for anything else.
std::optional<GlBackend> parse_gl_backend(std::string_view name);
std::string_view gl_backend_name(GlBackend backend);
// The backends this build has, in auto's order of preference ("egl osmesa").
std::string compiled_gl_backends();

// The process's choice: set_gl_backend's (the CLI's --gl), else SPINFOLD_GL, else auto. Throws
// std::invalid_argument naming SPINFOLD_GL when it holds something else.
GlBackend gl_backend_setting();
void set_gl_backend(GlBackend backend);

class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Binds a colour buffer of this size [pixels] to the calling thread, with this context's GL
  // table (gl_api.h).
  virtual void make_current(int width, int height) = 0;
  // Reads framebuffer `fbo` (0: the default one) into pixels(), first row on top. Call after
  // glFinish with the frame's size current.
  virtual void read_back(unsigned fbo);
  // The frame after read_back: width·height·4 RGBA bytes, first row on top.
  const std::uint8_t* pixels() const { return buffer_.data(); }
  int width() const { return width_; }
  int height() const { return height_; }
  // "egl-device", "egl-surfaceless" or "osmesa".
  const std::string& name() const { return name_; }
  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  const std::string& renderer() const { return renderer_; }

 protected:
  explicit GlContext(std::string name) : name_(std::move(name)) {}
  // Loads the table (once the first make_current has bound the context) and reads GL_RENDERER.
  void load_api(GlApi::ProcLookup lookup);
  // Resizes the buffer; true when the size changed.
  bool resize(int width, int height);
  // Makes this context's table (and this context) the calling thread's current ones.
  void bind_api() const;
  // Forgets them when this context is the calling thread's current one (before destruction).
  void unbind_if_current() const;

  std::vector<std::uint8_t> buffer_;
  int width_ = 0, height_ = 0;

 private:
  std::string name_, renderer_;
  GlApi api_;
  bool pack_invert_ = false;  // GL_MESA_pack_invert: rows come out top-down at no cost
};

// A context from this backend, made current at 64×64. Throws std::runtime_error saying why each
// backend tried could not give one.
std::unique_ptr<GlContext> make_gl_context(GlBackend backend);
std::unique_ptr<GlContext> make_gl_context();  // gl_backend_setting()

// The context current on this thread (made current by GlContext::make_current), or null.
GlContext* current_gl_context();

// The backend and GL_RENDERER of the last context made in this process ("" before any): what the
// server's render threads use, for /api/v1/health.
struct GlInUse {
  std::string backend, renderer;
};
GlInUse gl_in_use();

}  // namespace spinfold::render
