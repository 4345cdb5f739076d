// The one place that issues GL draw calls: a FrameScene in, pixels in the current context out.
#pragma once

#include <map>

#include "render/scene_builder.h"

namespace spinfold::render {

class GlRenderer {
 public:
  // Compiles the embedded shaders; a context must be current on this thread.
  GlRenderer();
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  // Draws into the current context's viewport.
  void draw(const FrameScene& scene, int width, int height);
  // Waits for the frame: OSMesa copies it into the context's buffer here.
  void finish();

 private:
  struct Mesh {
    unsigned vao = 0, vbo = 0;
    int count = 0;
  };
  // Static geometry is uploaded once per surface and view and kept.
  const Mesh& static_surface(const StaticGeometry& g);
  const Mesh& static_grid(const StaticGeometry& g);
  const Mesh& static_mesh(std::map<const StaticGeometry*, Mesh>& meshes, const StaticGeometry& g, const void* data,
                          std::size_t count, bool lit);
  void draw_flat(const std::vector<Vertex>& vertices, unsigned mode);

  unsigned lit_program_ = 0, flat_program_ = 0;
  Mesh dynamic_;
  std::map<const StaticGeometry*, Mesh> surfaces_, grids_;
};

}  // namespace spinfold::render
