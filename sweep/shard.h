// Sharding a sweep for a job array: shard I of N runs the runs i with i mod N = I; merging the
// shards' outputs gives the rows one process would have written.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace spinfold::sweep {

struct Shard {
  std::size_t index = 0, count = 1;
};

// "I/N" with 0 <= I < N ("" is 0/1); SweepError "--shard: …" otherwise.
Shard parse_shard(const std::string& text);

// The runs of `total` that `shard` runs, in order.
std::vector<std::size_t> shard_runs(std::size_t total, Shard shard);

// Joins the shard outputs at `paths` (all CSV or all JSON Lines, as `out`) into `out`: the header
// with the sweep's own command (shard 0's), the merge's `command` beside it and shard 0/1, then every
// run's row in order. SweepError "--merge: …" for another
// sweep's shard, a shard given twice, a row outside its shard, or runs missing (named).
void merge_shards(const std::vector<std::string>& paths, const std::string& out, const std::string& command);

}  // namespace spinfold::sweep
