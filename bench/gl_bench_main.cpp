// gl-bench: `spinfold-bench gl` alone, linking only the renderer and the codec (no FFmpeg, HTTP or
// OSMesa when built without it), so that it can be carried to a GPU machine with a few libraries.
#include <CLI/CLI.hpp>

#include "bench/gl_bench.h"

int main(int argc, char** argv) {
  CLI::App app{"Frame time and frames/s of each GL backend at 640x480 and 1920x1080"};
  spinfold::bench::GlBenchOptions options;
  app.add_option("--backend", options.backend, "all | auto | egl | osmesa")->capture_default_str();
  app.add_option("--frames", options.frames, "Frames per size (median)")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  return spinfold::bench::run_gl_bench(options);
}
