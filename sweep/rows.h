// The sweep's row writer: the header (CSV comment lines and column names, or one JSON Lines record)
// and one line per row, CSV or JSON Lines.
#pragma once

#include <string>
#include <vector>

#include "sweep/plan.h"
#include "sweep/run.h"
#include "sweep/shard.h"

namespace spinfold::sweep {

enum class Format { csv, jsonl, npz };

// The format an output path asks for: "", "-" or *.csv: CSV; *.jsonl: JSON Lines; *.npz: NumPy's
// archive (one array per column, written when the sweep ends); else SweepError.
Format format_of(const std::string& out);

// index, the varied fields' paths, the plan's columns, events, status, detail, steps, seconds.
std::vector<std::string> column_names(const Plan& plan);

// What makes the rows (base scene, varied values, times, budget), as a hash: the shards of one
// sweep share it, so a merge can refuse a shard of another. FNV-1a, 64 bits, of a canonical text.
std::string definition_hash(const Plan& plan);

// The header. Everything in it but the command line is the same for every shard of a sweep, and
// for the merged output.
std::string header_text(const Plan& plan, Format format, Shard shard, const std::string& command);

// One row's line (with its '\n').
std::string row_text(const Row& row, Format format);

}  // namespace spinfold::sweep
