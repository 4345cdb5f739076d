// The bare minimum a frame can cost here: OSMesa, one trivial shader, the same numbers of
// triangles and line segments as a Spinfold frame, glFinish, libpng at the same settings. Uses
// nothing of render/: the baseline the renderer is compared with in the same run.
#pragma once

#include <vector>

namespace spinfold::bench {

struct BareTimings {
  double render_ms = 0.0;  // draw + glFinish, median
  double encode_ms = 0.0;  // PNG encoding, median
};

// Draws opaque triangles, translucent triangles and line segments given as (x, y, z, r, g, b, a)
// vertices in world coordinates through `view_projection` (column-major 4x4) with one
// pass-through shader: the same pixels as the frame (colours precomputed, the surface's lighting
// included), none of the frame's machinery (scene building, programs, uniforms, caches, overlay).
// libpng + zlib at level 1, no filter: how frames were encoded before libdeflate (the baseline of
// the encoder comparison in render_bench).
std::vector<unsigned char> bare_encode_png(const unsigned char* rgba, int width, int height);

BareTimings bare_render_loop(int width, int height, const std::vector<float>& opaque,
                             const std::vector<float>& translucent, const std::vector<float>& lines,
                             const float* view_projection, int frames);

}  // namespace spinfold::bench
