// frame_diff EXPECTED.png ACTUAL.png [DIFF.png [JITTER_LEVEL]]: the golden comparison's metrics for two PNGs,
// and whether they are within the tolerance (exit 0) or not (exit 1). Measures llvmpipe's jitter across CPU
// code (docs/performance.md, "Across CPUs").
#include <cstdio>
#include <cstdlib>

#include "frame_compare.h"

int main(int argc, char** argv) {
  using namespace spinfold::test;
  if (argc < 3) {
    std::fprintf(stderr, "usage: frame_diff EXPECTED.png ACTUAL.png [DIFF.png [JITTER_LEVEL]]\n");
    return 2;
  }
  const auto expected = read_png(argv[1]), actual = read_png(argv[2]);
  if (!expected || !actual) {
    std::fprintf(stderr, "frame_diff: %s is not a readable PNG\n", expected ? argv[2] : argv[1]);
    return 2;
  }
  FrameTolerance tolerance;
  if (argc > 4) tolerance.jitter_level = std::atoi(argv[4]);  // 0: where any differing pixels cluster
  const FrameDifference d = compare_frames(*expected, *actual, tolerance);
  std::printf("%s: %s\n", within(d, tolerance) ? "within" : "BEYOND", describe(d, tolerance).c_str());
  if (argc > 3) write_png(argv[3], difference_image(*expected, *actual, tolerance));
  return within(d, tolerance) ? 0 : 1;
}
