// The provenance an output carries, read back from the file (`spinfold rerun`): wherever
// codec/provenance.h and sweep/rows.h put it — a JSON Lines header record, CSV comment lines, an
// .npz's `provenance` array, a PNG's Source text, an SVG's <metadata>, a PDF's Subject, a
// work-precision folder's CSV or summary.md. Reads the bytes only (no GL, no FFmpeg): the
// compute-only build has it.
#pragma once

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace spinfold {

// Why a file's provenance could not be had: the message names the file and what is missing.
struct ProvenanceError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// What a re-run needs of an output: the build that made it, the command line as recorded and the
// scene it ran (for a sweep, its base scene as given, before --set).
struct RecordedRun {
  std::string format;  // "jsonl", "csv", "npz", "png", "svg", "pdf", "markdown"
  std::string version;
  std::string commit;
  std::string command;  // codec/provenance.h's command_line
  nlohmann::json scene;
};

// The provenance of the output at `path`. ProvenanceError when the file cannot be read, is no
// spinfold output, or carries no command and scene (made by the HTTP API, or by a version before
// 0.3.0).
RecordedRun recorded_run(const std::string& path);

}  // namespace spinfold
