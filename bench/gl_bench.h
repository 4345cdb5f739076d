// Frame time and frames per second of each GL backend (EGL, OSMesa) at 640×480 and 1920×1080,
// measured in one run: `spinfold-bench gl [--backend all|auto|egl|osmesa]`.
#pragma once

#include <string>

namespace spinfold::bench {

struct GlBenchOptions {
  std::string backend = "all";  // all: every backend this build has, one after the other
  int frames = 60;              // frames per size (median)
};

// Prints a Markdown table with each context's GL_RENDERER; 2 on a bad --backend.
int run_gl_bench(const GlBenchOptions& options);

}  // namespace spinfold::bench
