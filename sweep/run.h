// A sweep's runs: each takes the code path of `spinfold simulate` (the one sampling loop,
// engine/sampling.h), so its row holds simulate's numbers to the bit; many run on a thread pool and
// come back in run order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "sweep/plan.h"

namespace spinfold::sweep {

// One run's row: the varied values, the plan's columns, then events, status, detail, steps and
// seconds (column_names(plan) after `index`).
struct Row {
  std::size_t index = 0;
  std::vector<std::pair<std::string, nlohmann::ordered_json>> cells;
  bool ok = false;  // status "ok"
};

// Runs run `index` of the plan (its trajectory file too, when the plan has a directory). A run that
// fails, or a scene the engine refuses, is its row's status; this never throws for a run.
Row run_one(const Plan& plan, std::size_t index);

struct Progress {
  std::size_t done = 0, not_ok = 0, total = 0;
};

// Runs `runs` on `jobs` threads (0: one per core). on_row gets each row in the order of `runs`,
// as soon as the rows before it are done; on_progress after each run; both one call at a time.
// An exception of either (a write that failed) stops the sweep and is thrown on the caller's thread.
// `cancelled`, asked before each run from any worker, ends the sweep early when it says true (Python's
// Ctrl-C): the rows written so far are every run before the first missing one.
void run_all(const Plan& plan, std::span<const std::size_t> runs, unsigned jobs,
             const std::function<void(Row&&)>& on_row,
             const std::function<void(const Progress&)>& on_progress = {},
             const std::function<bool()>& cancelled = {});

}  // namespace spinfold::sweep
