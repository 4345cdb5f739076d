// The trajectory export as CSV: one row per sample, one column block per body.
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <string>

namespace spinfold {

// Columns: t, then the main body's block (r, phi, lambda, mu, det_L, energy, energy_error, X0, X1,
// X2, status), then one block per companion with the same columns named "LABEL.column" (the
// samples' "companions" entries, codec/sample_json.h). Undefined values are empty cells; a cell
// holding a comma or a quote is quoted (RFC 4180).
std::string trajectory_csv(std::span<const nlohmann::ordered_json> samples);

}  // namespace spinfold
