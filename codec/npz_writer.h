// Tables as NumPy's .npz (an archive of .npy arrays, one per column), which numpy.load reads with
// nothing of spinfold installed: `spinfold simulate --format npz`. Numbers are little-endian uint64 or
// int64 where every cell is whole (counts, steps), else float64
// (a null cell NaN), text columns fixed-width unicode ('<U', UTF-32). The .npy format is NumPy's
// own, version 1.0 (numpy.lib.format); the archive is a zip written by libzip, stored uncompressed.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace spinfold {

// A column: its name (the array's key in the archive) and its cells (numbers, null or text).
struct NpzColumn {
  std::string name;
  std::vector<nlohmann::ordered_json> cells;
};

// One column as a .npy file's bytes: uint64 (int64 with a negative) when every cell is a whole
// number, as Python's sweep columns are; float64 when every cell is a number or null; else unicode
// (numbers written as JSON writes them, null as "").
std::vector<std::uint8_t> npy_bytes(const std::vector<nlohmann::ordered_json>& cells);

// Writes the columns to `path` as an .npz (each as "<name>.npy"); std::runtime_error naming the
// path when libzip cannot write it.
void write_npz(const std::string& path, const std::vector<NpzColumn>& columns);

}  // namespace spinfold
