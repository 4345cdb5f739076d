// Recording benchmark: a clip of the spinning sphere with its geodesic companion in every format
// (wall time, file size), and the live view's frame rate while the server records against without.
#pragma once

#include <string>

namespace spinfold::bench {

struct RecordBenchOptions {
  double seconds = 10.0;                     // the clip's length [s of the file]
  double fps = 30.0;                         // [frames/s]
  int width = 640, height = 480;             // [pixels]
  double live_seconds = 4.0;                 // each live-rate measurement [s]
  std::string out_dir = "out/record-bench";  // the files, kept to be looked at
};

int run_record_bench(const RecordBenchOptions& options);

}  // namespace spinfold::bench
