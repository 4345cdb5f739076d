// Snapshot in, image out: owns the context, the GL renderer and the HUD of one thread.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "render/gl_context.h"
#include "render/gl_renderer.h"
#include "render/overlay.h"
#include "render/png_encoder.h"
#include "render/scene_builder.h"

namespace spinfold::render {

// A rendered frame's pixels, owned: width·height·4 RGBA bytes, first row on top.
struct Image {
  int width = 0, height = 0;  // [pixels]
  std::vector<std::uint8_t> rgba;
};

class Renderer {
 public:
  // Creates the context (of gl_backend_setting()'s backend, or this one) on the calling thread and
  // warms it up (shader JIT costs the first frame 20–70 ms: docs/platform-notes.md). Use the renderer
  // only from this thread.
  Renderer();
  explicit Renderer(GlBackend backend);
  ~Renderer();

  // Draws the scene; the returned pointer is width·height·4 RGBA bytes, valid until the next call.
  const std::uint8_t* render_rgba(const FrameScene& scene, int width, int height);
  // build_scene + render, the pixels copied out (to be encoded on another thread).
  Image render_image(const Snapshot& snapshot, const ViewOptions& view);
  // build_scene + render + encode_png (with these text chunks).
  std::vector<std::uint8_t> render_png(const Snapshot& snapshot, const ViewOptions& view,
                                       std::span<const PngText> texts = {});
  // build_scene + render + encode_jpeg at this quality (1..100).
  std::vector<std::uint8_t> render_jpeg(const Snapshot& snapshot, const ViewOptions& view, int quality);
  // Frees the memory kept for the next frame (off-screen targets, cached backgrounds, uploaded
  // surfaces): a renderer that has been idle gives it back; the next frame takes a few ms more.
  void release_memory();
  // The context's backend ("egl-device", "egl-surfaceless", "osmesa") and GL_RENDERER.
  const GlContext& context() const { return *context_; }

 private:
  explicit Renderer(std::unique_ptr<GlContext> context);

  std::unique_ptr<GlContext> context_;
  std::unique_ptr<GlRenderer> gl_;
  std::unique_ptr<HudOverlay> hud_;  // created at the first frame that shows the HUD
};

}  // namespace spinfold::render
