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

// Draws the given triangle and line-segment vertices (x, y, z triples, world coordinates) through
// `view_projection` (column-major 4x4) with one flat shader: the same geometry and screen coverage
// as the frame, none of its shading, blending, state changes or overlay.
BareTimings bare_render_loop(int width, int height, const std::vector<float>& triangles,
                             const std::vector<float>& lines, const float* view_projection, int frames);

}  // namespace spinfold::bench
