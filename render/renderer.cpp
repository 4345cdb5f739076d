#include "render/renderer.h"

#include "render/jpeg_encoder.h"
#include "render/png_encoder.h"

namespace spinfold::render {

Renderer::Renderer() : Renderer(make_gl_context()) {}

Renderer::Renderer(GlBackend backend) : Renderer(make_gl_context(backend)) {}

Renderer::Renderer(std::unique_ptr<GlContext> context) : context_(std::move(context)) {
  context_->make_current(64, 64);
  gl_ = std::make_unique<GlRenderer>();
  render_rgba(FrameScene{}, 64, 64);  // warm-up: compile the shaders' machine code now
}

Renderer::~Renderer() {
  hud_.reset();
  gl_.reset();
}

const std::uint8_t* Renderer::render_rgba(const FrameScene& scene, int width, int height) {
  context_->make_current(width, height);
  gl_->draw(scene, width, height);
  if (!scene.hud_lines.empty() || !scene.legend.empty()) {
    if (!hud_) hud_ = std::make_unique<HudOverlay>();
    hud_->draw(scene.hud_lines, scene.legend, scene.hud, width, height);
  }
  gl_->finish();
  return context_->pixels();
}

void Renderer::release_memory() {
  gl_->release_memory();
  context_->make_current(64, 64);  // the frame-sized default framebuffer (an EGL pbuffer) as at the start
}

Image Renderer::render_image(const Snapshot& snapshot, const ViewOptions& view) {
  const FrameScene scene = build_scene(snapshot, view);
  const std::uint8_t* rgba = render_rgba(scene, view.width, view.height);
  const std::size_t bytes = static_cast<std::size_t>(view.width) * static_cast<std::size_t>(view.height) * 4;
  return {view.width, view.height, std::vector<std::uint8_t>(rgba, rgba + bytes)};
}

std::vector<std::uint8_t> Renderer::render_png(const Snapshot& snapshot, const ViewOptions& view,
                                               std::span<const PngText> texts) {
  const FrameScene scene = build_scene(snapshot, view);
  return encode_png(render_rgba(scene, view.width, view.height), view.width, view.height, texts);
}

std::vector<std::uint8_t> Renderer::render_jpeg(const Snapshot& snapshot, const ViewOptions& view,
                                                int quality) {
  const FrameScene scene = build_scene(snapshot, view);
  return encode_jpeg(render_rgba(scene, view.width, view.height), view.width, view.height, quality);
}

}  // namespace spinfold::render
