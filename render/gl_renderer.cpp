#include "render/gl_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>
#include <string>

#include "render/gl_api.h"
#include "render/gl_context.h"
#include "render/shader_sources.h"

namespace spinfold::render {

namespace {

unsigned compile(GLenum type, std::string_view source) {
  const unsigned shader = glCreateShader(type);
  const char* text = source.data();
  const GLint length = static_cast<GLint>(source.size());
  glShaderSource(shader, 1, &text, &length);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024];
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("shader compilation failed: ") + log);
  }
  return shader;
}

unsigned link(std::string_view vertex_name, std::string_view fragment_name) {
  const unsigned program = glCreateProgram();
  const unsigned vs = compile(GL_VERTEX_SHADER, shader_source(vertex_name));
  const unsigned fs = compile(GL_FRAGMENT_SHADER, shader_source(fragment_name));
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("shader program link failed");
  return program;
}

void upload(unsigned vao, unsigned vbo, const void* data, std::size_t bytes, bool lit) {
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bytes), data, lit ? GL_STATIC_DRAW : GL_STREAM_DRAW);
  const GLsizei stride = lit ? sizeof(LitVertex) : sizeof(Vertex);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, lit ? 3 : 4, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<void*>(sizeof(glm::vec3)));
  if (lit) {  // the curvature layer's tint
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<void*>(offsetof(LitVertex, tint)));
  } else {
    glDisableVertexAttribArray(2);
  }
}

}  // namespace

GlRenderer::GlRenderer(const Options& options) : options_(options) {
  lit_program_ = link("lit.vert", "lit.frag");
  flat_program_ = link("flat.vert", "flat.frag");
  line_program_ = link("line.vert", "line.frag");
  glGenVertexArrays(1, &dynamic_.vao);
  glGenBuffers(1, &dynamic_.vbo);
  glGenVertexArrays(1, &line_vao_);
  // Warm-up: llvmpipe compiles a program's machine code for each state it is drawn in at the
  // first such draw (tens of ms); draw a fill and lines off-screen now, in the 3-D views' state.
  FrameScene warm;
  const glm::vec4 c{0.5f, 0.5f, 0.5f, 0.5f};
  warm.fills = {{{0, 0, 0}, c}, {{0.5f, 0, 0}, c}, {{0, 0.5f, 0}, c}};
  warm.lines = {{{0, 0, 0}, c}, {{0.5f, 0.5f, 0}, c}};
  draw(warm, 16, 16);
  glFinish();
  readback_ = nullptr;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

GlRenderer::~GlRenderer() {
  drop_targets();
  drop_meshes();
  glDeleteBuffers(1, &dynamic_.vbo);
  glDeleteVertexArrays(1, &dynamic_.vao);
  glDeleteProgram(lit_program_);
  glDeleteProgram(flat_program_);
  glDeleteProgram(line_program_);
  glDeleteVertexArrays(1, &line_vao_);
}

void GlRenderer::set_options(const Options& options) {
  drop_targets();
  options_ = options;
}

bool GlRenderer::BackgroundKey::operator==(const BackgroundKey& o) const {
  // Bitwise on the floats: the same camera gives the same matrix bits, and only then may the
  // cached pixels stand in for drawn ones.
  return statics == o.statics && surface == o.surface && grid == o.grid && depth_test == o.depth_test &&
         tint == o.tint && std::memcmp(&view_projection, &o.view_projection, sizeof view_projection) == 0 &&
         std::memcmp(&surface_color, &o.surface_color, sizeof surface_color) == 0 &&
         std::memcmp(&clear_color, &o.clear_color, sizeof clear_color) == 0 && width == o.width &&
         height == o.height && samples == o.samples &&
         std::memcmp(&grid_width, &o.grid_width, sizeof grid_width) == 0 &&
         std::memcmp(&depth_bias, &o.depth_bias, sizeof depth_bias) == 0;
}

int GlRenderer::samples_for(int width, int height) const {
  int samples = std::max(1, options_.samples);
  while (samples > 1 && static_cast<std::int64_t>(width) * height * samples > kMaxSampleCount) samples /= 2;
  return samples;
}

GlRenderer::Target GlRenderer::make_target(int width, int height, int samples) const {
  Target t;
  t.width = width;
  t.height = height;
  t.samples = samples;
  glGenRenderbuffers(1, &t.color);
  glBindRenderbuffer(GL_RENDERBUFFER, t.color);
  // One sample is asked for as 0: Mesa rounds a request for 1 up to a multisampled buffer.
  const int asked = samples > 1 ? samples : 0;
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, asked, GL_RGBA8, width, height);
  glGenRenderbuffers(1, &t.depth);
  glBindRenderbuffer(GL_RENDERBUFFER, t.depth);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, asked, GL_DEPTH_COMPONENT24, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glGenFramebuffers(1, &t.fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t.color);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t.depth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("incomplete off-screen framebuffer (" + std::to_string(samples) + " samples)");
  return t;
}

void GlRenderer::delete_target(Target& t) const {
  glDeleteFramebuffers(1, &t.fbo);
  glDeleteRenderbuffers(1, &t.color);
  glDeleteRenderbuffers(1, &t.depth);
  t = Target{};
}

void GlRenderer::drop_meshes() {
  for (auto* meshes : {&surfaces_, &grids_}) {
    for (auto& [key, mesh] : *meshes) {
      glDeleteBuffers(1, &mesh.vbo);
      glDeleteVertexArrays(1, &mesh.vao);
    }
    meshes->clear();
  }
}

void GlRenderer::drop_targets() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  for (Working& w : working_) {
    if (w.resolved.fbo != w.drawn.fbo) delete_target(w.resolved);
    delete_target(w.drawn);
  }
  readback_ = nullptr;
  for (CacheEntry& e : cache_) delete_target(e.target);
  working_.clear();
  cache_.clear();
  recent_keys_.clear();
  stats_.entries = 0;
  stats_.bytes = 0;
}

const GlRenderer::Working& GlRenderer::working_target(int width, int height, int samples) {
  const auto it = std::find_if(working_.begin(), working_.end(), [&](const Working& w) {
    return w.drawn.width == width && w.drawn.height == height && w.drawn.samples == samples;
  });
  if (it != working_.end()) {
    working_.splice(working_.begin(), working_, it);
    return working_.front();
  }
  // Two sizes alternate when one thread serves a frame and its thumbnail: keep both.
  if (working_.size() >= 2) {
    Working& last = working_.back();
    if (last.resolved.fbo != last.drawn.fbo) delete_target(last.resolved);
    delete_target(last.drawn);
    working_.pop_back();
  }
  Working w;
  w.drawn = make_target(width, height, samples);
  w.resolved = samples > 1 ? make_target(width, height, 1) : w.drawn;
  working_.push_front(w);
  return working_.front();
}

const GlRenderer::Mesh& GlRenderer::static_mesh(std::map<std::uint64_t, Mesh>& meshes,
                                                const StaticGeometry& g, const void* data, std::size_t count,
                                                bool lit) {
  if (meshes.size() >= kMaxMeshes && !meshes.contains(g.id)) {
    for (auto& [id, mesh] : meshes) {
      glDeleteBuffers(1, &mesh.vbo);
      glDeleteVertexArrays(1, &mesh.vao);
    }
    meshes.clear();
  }
  auto [it, fresh] = meshes.try_emplace(g.id);
  if (fresh) {
    glGenVertexArrays(1, &it->second.vao);
    glGenBuffers(1, &it->second.vbo);
    upload(it->second.vao, it->second.vbo, data, count * (lit ? sizeof(LitVertex) : sizeof(Vertex)), lit);
    it->second.count = static_cast<int>(count);
  }
  return it->second;
}

const GlRenderer::Mesh& GlRenderer::static_surface(const StaticGeometry& g) {
  return static_mesh(surfaces_, g, g.surface.data(), g.surface.size(), true);
}

const GlRenderer::Mesh& GlRenderer::static_grid(const StaticGeometry& g) {
  return static_mesh(grids_, g, g.grid.data(), g.grid.size(), false);
}

void GlRenderer::draw_flat(const std::vector<Vertex>& vertices, unsigned mode) {
  if (vertices.empty()) return;
  upload(dynamic_.vao, dynamic_.vbo, vertices.data(), vertices.size() * sizeof(Vertex), false);
  glDrawArrays(mode, 0, static_cast<GLsizei>(vertices.size()));
}

void GlRenderer::finish() {
  glFinish();  // OSMesa copies the default framebuffer into its buffer here
  GlContext* context = current_gl_context();
  if (!context ||
      (readback_ && (context->width() != readback_->width || context->height() != readback_->height)))
    throw std::runtime_error("the current context's buffer does not match the frame");
  context->read_back(readback_ ? readback_->fbo : 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  readback_ = nullptr;
}

glm::vec4 GlRenderer::camera_of(const FrameScene& scene) {
  // The camera: the point the projection sends to w = 0 (none in the 2-D views' orthographic one).
  const glm::dvec4 eye = glm::inverse(glm::dmat4(scene.view_projection)) * glm::dvec4(0, 0, 1, 0);
  if (std::abs(eye.w) <= 1e-12) return glm::vec4(0.0f);
  return glm::vec4(glm::vec3(glm::dvec3(eye) / eye.w), scene.depth_bias);
}

void GlRenderer::use_program_with_camera(unsigned program, const FrameScene& scene) {
  glUseProgram(program);
  glUniformMatrix4fv(glGetUniformLocation(program, "view_projection"), 1, GL_FALSE,
                     glm::value_ptr(scene.view_projection));
  const glm::vec4 eye = camera_of(scene);
  glUniform3fv(glGetUniformLocation(program, "eye"), 1, glm::value_ptr(glm::vec3(eye)));
  glUniform1f(glGetUniformLocation(program, "depth_bias"), eye.w);
}

void GlRenderer::use_flat_program(const FrameScene& scene) {
  use_program_with_camera(flat_program_, scene);
}

void GlRenderer::draw_background(const FrameScene& scene, float grid_width) {
  // Opaque: the pixels' alpha stays 1 (the blends above keep the destination's), as the PNG and
  // JPEG (RGB) and Python's Frame.pixels (RGBA) say; a translucent fill's alpha was left there.
  glClearColor(scene.clear_color.r, scene.clear_color.g, scene.clear_color.b, 1.0f);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (scene.depth_test)
    glEnable(GL_DEPTH_TEST);
  else
    glDisable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  const float* vp = glm::value_ptr(scene.view_projection);
  if (scene.statics && scene.draw_surface && !scene.statics->surface.empty()) {
    const Mesh& mesh = static_surface(*scene.statics);
    glUseProgram(lit_program_);
    glUniformMatrix4fv(glGetUniformLocation(lit_program_, "view_projection"), 1, GL_FALSE, vp);
    glUniform4fv(glGetUniformLocation(lit_program_, "color"), 1, glm::value_ptr(scene.surface_color));
    // Headlight from the camera's side (3-D), straight on (2-D).
    const glm::vec3 towards_camera = headlight(scene);
    glUniform3fv(glGetUniformLocation(lit_program_, "light_direction"), 1, glm::value_ptr(towards_camera));
    glUniform1f(glGetUniformLocation(lit_program_, "ambient"), scene.depth_test ? 0.35f : 1.0f);
    glUniform1f(glGetUniformLocation(lit_program_, "tint_mix"), scene.tint_by_curvature ? 1.0f : 0.0f);
    glBindVertexArray(mesh.vao);
    glDrawArrays(GL_TRIANGLES, 0, mesh.count);
    if (smooth_) {  // without multisampling, smooth the surface's outline with a line over it
      const std::vector<Vertex> outline = silhouette(*scene.statics, scene);
      if (!outline.empty()) {
        upload(dynamic_.vao, dynamic_.vbo, outline.data(), outline.size() * sizeof(Vertex), false);
        draw_lines(scene, dynamic_, static_cast<int>(outline.size()), grid_width);
      }
    }
  }
  if (scene.draw_surface && !scene.backdrop.empty()) {  // not cached: build_scene leaves statics null
    use_flat_program(scene);
    draw_flat(scene.backdrop, GL_TRIANGLES);
  }
  if (scene.statics && scene.draw_grid) {
    const Mesh& mesh = static_grid(*scene.statics);
    if (mesh.count > 0) draw_lines(scene, mesh, mesh.count, grid_width);
  }
  // The plane's grid follows the camera: a function of the view_projection and the frame's size,
  // which the background cache's key holds.
  if (scene.draw_grid && !scene.grid_lines.empty()) {
    upload(dynamic_.vao, dynamic_.vbo, scene.grid_lines.data(), scene.grid_lines.size() * sizeof(Vertex),
           false);
    draw_lines(scene, dynamic_, static_cast<int>(scene.grid_lines.size()), grid_width);
  }
}

void GlRenderer::draw_lines(const FrameScene& scene, const Mesh& mesh, int count, float width) {
  if (!smooth_) {  // GL_LINES, aliased
    use_flat_program(scene);
    glLineWidth(width);
    glBindVertexArray(mesh.vao);
    glDrawArrays(GL_LINES, 0, count);
    return;
  }
  // One instance per segment (line.vert): both ends' vertices from the GL_LINES array.
  use_program_with_camera(line_program_, scene);
  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  glUniform2f(glGetUniformLocation(line_program_, "viewport"), static_cast<float>(viewport[2]),
              static_cast<float>(viewport[3]));
  glUniform1f(glGetUniformLocation(line_program_, "half_width"), 0.5f * width);
  glBindVertexArray(line_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, mesh.vbo);
  const GLsizei stride = 2 * sizeof(Vertex);
  for (int end = 0; end < 2; ++end) {
    const std::size_t at = end * sizeof(Vertex);
    glEnableVertexAttribArray(2 * end);
    glVertexAttribPointer(2 * end, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(at));
    glVertexAttribDivisor(2 * end, 1);
    glEnableVertexAttribArray(2 * end + 1);
    glVertexAttribPointer(2 * end + 1, 4, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<void*>(at + sizeof(glm::vec3)));
    glVertexAttribDivisor(2 * end + 1, 1);
  }
  // Blended, and writing no depth, so that one line's fringe never hides another line.
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);  // keeps the frame opaque
  glDepthMask(GL_FALSE);
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, count / 2);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
}

void GlRenderer::draw_moving(const FrameScene& scene, float line_width) {
  // The state the background left may come from the cache: set all of it again.
  if (scene.depth_test)
    glEnable(GL_DEPTH_TEST);
  else
    glDisable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  use_flat_program(scene);
  if (!scene.ghost_fills.empty() || !scene.ghost_lines.empty()) {  // through the surface, under the rest
    glDisable(GL_DEPTH_TEST);
    if (!scene.ghost_fills.empty()) {
      glEnable(GL_BLEND);
      glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
      draw_flat(scene.ghost_fills, GL_TRIANGLES);
      glDisable(GL_BLEND);
    }
    if (!scene.ghost_lines.empty()) {
      upload(dynamic_.vao, dynamic_.vbo, scene.ghost_lines.data(), scene.ghost_lines.size() * sizeof(Vertex),
             false);
      draw_lines(scene, dynamic_, static_cast<int>(scene.ghost_lines.size()), line_width);
    }
    if (scene.depth_test) glEnable(GL_DEPTH_TEST);
    use_flat_program(scene);
  }
  if (!scene.fills.empty()) {
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);  // keeps the frame opaque
    glDepthMask(GL_FALSE);  // translucent: test against the surface, write nothing
    draw_flat(scene.fills, GL_TRIANGLES);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
  }
  if (!scene.lines.empty()) {
    upload(dynamic_.vao, dynamic_.vbo, scene.lines.data(), scene.lines.size() * sizeof(Vertex), false);
    draw_lines(scene, dynamic_, static_cast<int>(scene.lines.size()), line_width);
  }
  glBindVertexArray(0);
}

void GlRenderer::background_into(const Target& target, const FrameScene& scene, float grid_width) {
  const bool cacheable = options_.cache_background && scene.statics &&
                         (scene.draw_surface || scene.draw_grid) &&
                         target.bytes() * 2 <= options_.cache_bytes && options_.cache_entries > 0;
  glBindFramebuffer(GL_FRAMEBUFFER, target.fbo);
  glViewport(0, 0, target.width, target.height);
  if (!cacheable) {
    draw_background(scene, grid_width);
    return;
  }
  BackgroundKey key;
  key.statics = scene.statics->id;
  key.tint = scene.tint_by_curvature;
  key.surface = scene.draw_surface;
  key.grid = scene.draw_grid;
  key.depth_test = scene.depth_test;
  key.view_projection = scene.view_projection;
  key.surface_color = scene.surface_color;
  key.clear_color = scene.clear_color;
  key.width = target.width;
  key.height = target.height;
  key.samples = target.samples;
  key.grid_width = grid_width;
  key.depth_bias = scene.depth_bias;

  auto hit = std::find_if(cache_.begin(), cache_.end(), [&](const CacheEntry& e) { return e.key == key; });
  if (hit == cache_.end()) {
    // A key met on one of the last frames again: the camera stands still, fill an entry. A camera
    // aimed at a moving body gives a new key every frame and never pays for a fill.
    const bool seen = std::find(recent_keys_.begin(), recent_keys_.end(), key) != recent_keys_.end();
    recent_keys_.remove(key);
    recent_keys_.push_front(key);
    if (recent_keys_.size() > 4) recent_keys_.pop_back();
    if (!seen) {
      ++stats_.misses;
      draw_background(scene, grid_width);
      return;
    }
    while (!cache_.empty() && (static_cast<int>(cache_.size()) >= options_.cache_entries ||
                               stats_.bytes + target.bytes() > options_.cache_bytes)) {
      stats_.bytes -= cache_.back().target.bytes();
      delete_target(cache_.back().target);
      cache_.pop_back();
    }
    cache_.push_front({key, make_target(target.width, target.height, target.samples)});
    stats_.bytes += target.bytes();
    ++stats_.fills;
    glBindFramebuffer(GL_FRAMEBUFFER, cache_.front().target.fbo);
    draw_background(scene, grid_width);
    hit = cache_.begin();
  } else {
    ++stats_.hits;
    cache_.splice(cache_.begin(), cache_, hit);
    hit = cache_.begin();
  }
  stats_.entries = static_cast<int>(cache_.size());
  // Sample for sample: the same bytes the background drawn in place would have left.
  const Target& from = hit->target;
  glCopyImageSubData(from.color, GL_RENDERBUFFER, 0, 0, 0, 0, target.color, GL_RENDERBUFFER, 0, 0, 0, 0,
                     target.width, target.height, 1);
  if (scene.depth_test)  // the 2-D views never test depth
    glCopyImageSubData(from.depth, GL_RENDERBUFFER, 0, 0, 0, 0, target.depth, GL_RENDERBUFFER, 0, 0, 0, 0,
                       target.width, target.height, 1);
  glBindFramebuffer(GL_FRAMEBUFFER, target.fbo);
}

void GlRenderer::draw(const FrameScene& scene, int width, int height) {
  const LineWidths widths = options_.wide_lines ? line_widths(width, height) : LineWidths{1.0f, 1.0f};
  const int samples = samples_for(width, height);
  readback_ = nullptr;
  smooth_ = samples == 1 && options_.smooth_lines;
  // Aliased (the benchmarks' reference): straight into the context's buffer. Anything else goes
  // through the off-screen target, cached background or not, so that both give the same bytes
  // (the default framebuffer's depth buffer rounds differently from a renderbuffer's).
  if (samples == 1 && !smooth_ && !options_.cache_background) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    draw_background(scene, widths.grid);
    draw_moving(scene, widths.lines);
    return;
  }
  const Working& target = working_target(width, height, samples);
  background_into(target.drawn, scene, widths.grid);
  draw_moving(scene, widths.lines);
  if (target.resolved.fbo != target.drawn.fbo) {  // resolve: each pixel the mean of its samples
    glBindFramebuffer(GL_READ_FRAMEBUFFER, target.drawn.fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target.resolved.fbo);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, target.resolved.fbo);
  glViewport(0, 0, width, height);
  readback_ = &target.resolved;
}

}  // namespace spinfold::render
