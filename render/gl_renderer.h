// The one place that issues GL draw calls: a FrameScene in, pixels in the current context out.
//
// A frame is drawn into an off-screen target, which is left bound for the HUD; finish() reads it
// back into the context's buffer (glReadPixels, 0.04 ms at 640×480). Anti-aliasing, by default
// without multisampling: each line segment is an instanced screen-space quad (shaders/line.vert)
// whose last half pixel fades out (line.frag), with a width in pixels that grows with the frame
// (line_widths()), and the surface's outline against the background is drawn as such lines too
// (silhouette()). 4x multisampling is an option (samples = 4): on llvmpipe its resolve is a
// full-screen shader pass, 2–3 ms at 640×480 and 20–30 ms at 1920×1080, which made a frame
// 2.4–6× the aliased one; GL_LINE_SMOOTH cost ~2 µs a segment in llvmpipe's line stage
// (docs/performance.md).
//
// The background (clear, surface, outline, grid) of a camera seen on a recent frame is kept as a
// colour + depth image and copied in, so that a frame where only the bodies move draws only them;
// both paths draw the background the same way, so a cached frame has the bytes of a drawn one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <list>
#include <map>

#include "render/scene_builder.h"

namespace spinfold::render {

class GlRenderer {
 public:
  struct Options {
    int samples = 1;                       // samples per pixel (4: multisampled); fewer on very large frames
    bool smooth_lines = true;              // with one sample: coverage-blended lines and surface outline
    bool wide_lines = true;                // lines as wide as line_widths() says; false: 1 px
    bool cache_background = true;          // keep the backgrounds of fixed cameras (a small LRU)
    int cache_entries = 4;                 // at most this many backgrounds
    std::size_t cache_bytes = 160u << 20;  // and at most this many bytes of them [bytes]
  };
  // What the background cache did since the renderer was made (for tests and benchmarks).
  struct CacheStats {
    int hits = 0;           // background copied from the cache
    int fills = 0;          // background drawn into a new entry, then copied
    int misses = 0;         // background drawn in place (key not seen on a recent frame)
    int entries = 0;        // entries held now
    std::size_t bytes = 0;  // their size [bytes]
  };

  // Compiles the embedded shaders; a context must be current on this thread.
  GlRenderer() : GlRenderer(Options{}) {}
  explicit GlRenderer(const Options& options);
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  // Changes the options; drops the cached backgrounds and off-screen targets.
  void set_options(const Options& options);
  const Options& options() const { return options_; }
  const CacheStats& cache_stats() const { return stats_; }
  // Frees the off-screen targets and the cached backgrounds (at 1280×720 with 4× multisampling
  // ~30 MB each) and the uploaded surfaces and grids; the next frame makes what it needs again.
  void release_memory() {
    drop_targets();
    drop_meshes();
  }

  // Draws the frame (width × height: the current context's size) and leaves bound the framebuffer
  // that whatever draws next (the HUD) must draw into.
  void draw(const FrameScene& scene, int width, int height);
  // Waits for the frame and puts it into the context's buffer (GlContext::pixels()).
  void finish();

  // The samples a frame of this size is drawn with: options().samples, halved while the
  // multisampled colour + depth would exceed kMaxSampleCount samples (memory), down to 1.
  int samples_for(int width, int height) const;
  static constexpr std::int64_t kMaxSampleCount = 4LL * 1920 * 1080;

 private:
  struct Mesh {
    unsigned vao = 0, vbo = 0;
    int count = 0;
  };
  // An off-screen framebuffer with multisampled colour (RGBA8) and depth (24 bit) renderbuffers.
  struct Target {
    unsigned fbo = 0, color = 0, depth = 0;
    int width = 0, height = 0, samples = 0;
    std::size_t bytes() const { return static_cast<std::size_t>(width) * height * samples * 8; }
  };
  // Everything the background's pixels depend on.
  struct BackgroundKey {
    std::uint64_t statics = 0;  // StaticGeometry::id
    bool surface = false, grid = false, depth_test = false, tint = false;
    glm::mat4 view_projection{1.0f};
    glm::vec4 surface_color{0.0f}, clear_color{0.0f};
    int width = 0, height = 0, samples = 0;
    float grid_width = 1.0f, depth_bias = 0.0f;
    bool operator==(const BackgroundKey& other) const;
  };
  // A multisampled target and the single-sample one it is resolved into (the same one with one
  // sample).
  struct Working {
    Target drawn, resolved;
  };
  struct CacheEntry {
    BackgroundKey key;
    Target target;
  };

  // Static geometry is uploaded once per surface and view and kept.
  const Mesh& static_surface(const StaticGeometry& g);
  const Mesh& static_grid(const StaticGeometry& g);
  const Mesh& static_mesh(std::map<std::uint64_t, Mesh>& meshes, const StaticGeometry& g, const void* data,
                          std::size_t count, bool lit);
  void draw_flat(const std::vector<Vertex>& vertices, unsigned mode);

  // Binds the program and sets the camera uniforms the flat and line shaders share
  // (view_projection, eye, depth_bias).
  void use_program_with_camera(unsigned program, const FrameScene& scene);
  // The flat shader with the scene's camera and depth bias.
  void use_flat_program(const FrameScene& scene);
  // Clear, surface and grid into the bound framebuffer.
  void draw_background(const FrameScene& scene, float grid_width);
  // Fills and lines into the bound framebuffer.
  void draw_moving(const FrameScene& scene, float line_width);
  // `count` vertices of GL_LINES in mesh.vbo, `width` pixels wide: anti-aliased quads (line.vert)
  // when smooth_, else GL_LINES.
  void draw_lines(const FrameScene& scene, const Mesh& mesh, int count, float width);
  // The camera's position (xyz) and the depth bias to use (w; 0 for orthographic projections).
  static glm::vec4 camera_of(const FrameScene& scene);
  // The background into `target`: from the cache, into a new cache entry, or drawn in place.
  void background_into(const Target& target, const FrameScene& scene, float grid_width);
  Target make_target(int width, int height, int samples) const;
  void delete_target(Target& target) const;
  const Working& working_target(int width, int height, int samples);
  void drop_targets();
  void drop_meshes();

  Options options_;
  CacheStats stats_;
  unsigned lit_program_ = 0, flat_program_ = 0, line_program_ = 0;
  unsigned line_vao_ = 0;  // the line program's attributes, pointed at a mesh's buffer per draw
  Mesh dynamic_;
  // Uploaded static geometry by StaticGeometry::id; emptied when it passes kMaxMeshes (a surface
  // whose shape changes frame after frame must not fill the GPU's memory).
  static constexpr std::size_t kMaxMeshes = 24;
  std::map<std::uint64_t, Mesh> surfaces_, grids_;
  std::list<Working> working_;            // most recently used first, at most 2
  bool smooth_ = false;                   // this frame's lines are anti-aliased quads
  const Target* readback_ = nullptr;      // the last frame's, until finish()
  std::list<CacheEntry> cache_;           // most recently used first
  std::list<BackgroundKey> recent_keys_;  // the backgrounds of the last few frames
};

}  // namespace spinfold::render
