#include "render/gl_renderer.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>
#include <string>

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
}

}  // namespace

GlRenderer::GlRenderer() {
  lit_program_ = link("lit.vert", "lit.frag");
  flat_program_ = link("flat.vert", "flat.frag");
  glGenVertexArrays(1, &dynamic_.vao);
  glGenBuffers(1, &dynamic_.vbo);
}

GlRenderer::~GlRenderer() {
  for (auto* meshes : {&surfaces_, &grids_})
    for (auto& [key, mesh] : *meshes) {
      glDeleteBuffers(1, &mesh.vbo);
      glDeleteVertexArrays(1, &mesh.vao);
    }
  glDeleteBuffers(1, &dynamic_.vbo);
  glDeleteVertexArrays(1, &dynamic_.vao);
  glDeleteProgram(lit_program_);
  glDeleteProgram(flat_program_);
}

const GlRenderer::Mesh& GlRenderer::static_mesh(std::map<const StaticGeometry*, Mesh>& meshes,
                                                 const StaticGeometry& g, const void* data, std::size_t count,
                                                 bool lit) {
  auto [it, fresh] = meshes.try_emplace(&g);
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
  glFinish();
}

void GlRenderer::draw(const FrameScene& scene, int width, int height) {
  glViewport(0, 0, width, height);
  glClearColor(scene.clear_color.r, scene.clear_color.g, scene.clear_color.b, scene.clear_color.a);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (scene.depth_test)
    glEnable(GL_DEPTH_TEST);
  else
    glDisable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  const float* vp = glm::value_ptr(scene.view_projection);

  if (scene.statics && scene.draw_surface) {
    const Mesh& mesh = static_surface(*scene.statics);
    glUseProgram(lit_program_);
    glUniformMatrix4fv(glGetUniformLocation(lit_program_, "view_projection"), 1, GL_FALSE, vp);
    glUniform4fv(glGetUniformLocation(lit_program_, "color"), 1, glm::value_ptr(scene.surface_color));
    // Headlight from the camera's side (3-D), straight on (2-D).
    const glm::mat4 inverse = glm::inverse(scene.view_projection);
    glm::vec3 towards_camera = glm::normalize(glm::vec3(inverse * glm::vec4(0, 0, -1, 0)));
    if (!scene.depth_test) towards_camera = {0, 0, 1};
    glUniform3fv(glGetUniformLocation(lit_program_, "light_direction"), 1, glm::value_ptr(towards_camera));
    glUniform1f(glGetUniformLocation(lit_program_, "ambient"), scene.depth_test ? 0.35f : 1.0f);
    glBindVertexArray(mesh.vao);
    glDrawArrays(GL_TRIANGLES, 0, mesh.count);
  }
  glUseProgram(flat_program_);
  glUniformMatrix4fv(glGetUniformLocation(flat_program_, "view_projection"), 1, GL_FALSE, vp);
  if (scene.statics && scene.draw_grid) {
    const Mesh& mesh = static_grid(*scene.statics);
    glBindVertexArray(mesh.vao);
    glDrawArrays(GL_LINES, 0, mesh.count);
  }
  if (!scene.fills.empty()) {
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);  // translucent: test against the surface, write nothing
    draw_flat(scene.fills, GL_TRIANGLES);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
  }
  draw_flat(scene.lines, GL_LINES);
  glBindVertexArray(0);
}

}  // namespace spinfold::render
