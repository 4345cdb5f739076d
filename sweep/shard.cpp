#include "sweep/shard.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "codec/output_file.h"
#include "sweep/grid.h"
#include "sweep/rows.h"

namespace spinfold::sweep {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

Shard parse_shard(const std::string& text) {
  if (text.empty()) return {};
  const auto parts = split(text, '/');
  std::size_t i = 0, n = 0;
  const auto whole = [](const std::string& s, std::size_t& v) {
    return !s.empty() && std::from_chars(s.data(), s.data() + s.size(), v).ptr == s.data() + s.size();
  };
  if (parts.size() != 2 || !whole(parts[0], i) || !whole(parts[1], n) || n < 1 || i >= n || n > kMaxRuns)
    throw SweepError("--shard: must be I/N with 0 <= I < N (got '" + text + "')");
  return {i, n};
}

std::vector<std::size_t> shard_runs(std::size_t total, Shard shard) {
  std::vector<std::size_t> runs;
  for (std::size_t i = shard.index; i < total; i += shard.count) runs.push_back(i);
  return runs;
}

namespace {

struct ShardFile {
  std::vector<std::string> header;  // CSV: the column line and the comment lines; JSON Lines: one
  std::string command;              // the sweep's command that wrote it
  std::map<std::size_t, std::string> rows;
  Shard shard{0, 0};
  std::size_t total = 0;
};

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SweepError("--merge: cannot read '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

ShardFile read_shard(const std::string& path, bool jsonl) {
  const std::string text = read_text(path);
  ShardFile f;
  std::size_t pos = 0;
  // CSV: the column names, the comment lines, then rows (files of an older version: the comment lines
  // first); JSON Lines: the header object, then rows.
  bool columns_seen = false;
  while (pos < text.size()) {
    const std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) break;  // a line cut short by a kill: not a row
    const std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    const bool comment = !jsonl && line.starts_with("#");
    const bool header = jsonl ? f.header.empty() : comment || !columns_seen;
    if (!jsonl && !comment) columns_seen = true;
    if (header) {
      if (jsonl) {
        const json h = json::parse(line, nullptr, false);
        if (!h.is_object() || !h.contains("sweep"))
          throw SweepError("--merge: '" + path + "' is not a sweep's JSON Lines");
        f.shard = parse_shard(h["sweep"].value("shard", ""));
        f.total = h["sweep"].value("runs", std::size_t{0});
        json canonical = h;
        f.command = h["sweep"].value("command", "");
        canonical["sweep"].erase("command");
        canonical["sweep"].erase("shard");
        f.header.push_back(canonical.dump());
      } else if (line.starts_with("# shard: ")) {
        f.shard = parse_shard(line.substr(9));
        f.header.push_back("# shard");
      } else if (line.starts_with("# runs: ")) {
        f.total = std::strtoull(line.c_str() + 8, nullptr, 10);
        f.header.push_back(line);
      } else if (line.starts_with("# command: ")) {
        f.command = line.substr(11);
        f.header.push_back("# command");
      } else {
        f.header.push_back(line);
      }
      continue;
    }
    std::size_t index = 0, digits = 0;  // a row starts with its index: `7,...` or `{"index":7,...`
    if (jsonl) {
      digits = line.find("\"index\":");
      if (digits == std::string::npos) throw SweepError("--merge: '" + path + "': a row without an index");
      digits += 8;
    }
    const char* at = line.c_str() + digits;
    if (std::from_chars(at, line.c_str() + line.size(), index).ec != std::errc{})
      throw SweepError("--merge: '" + path + "': a row without an index");
    f.rows[index] = line;
  }
  if (f.header.empty() || f.shard.count == 0) throw SweepError("--merge: '" + path + "' has no sweep header");
  return f;
}

}  // namespace

void merge_shards(const std::vector<std::string>& paths, const std::string& out, const std::string& command) {
  if (out.empty() || out == "-") throw SweepError("--merge: --out FILE.csv|FILE.jsonl is required");
  if (format_of(out) == Format::npz)
    throw SweepError(
        "--merge: shards merge as text (--out FILE.csv|FILE.jsonl); numpy.load reads the merged "
        "CSV with numpy.genfromtxt, or write each shard as .npz and concatenate the arrays");
  const bool jsonl = format_of(out) == Format::jsonl;
  std::vector<ShardFile> shards;
  for (const std::string& path : paths) {
    if ((path.ends_with(".jsonl")) != jsonl)
      throw SweepError("--merge: '" + path + "' is not in --out's format (" + (jsonl ? "jsonl" : "csv") +
                       ")");
    shards.push_back(read_shard(path, jsonl));
  }
  if (shards.empty()) throw SweepError("--merge: no shard outputs given");
  std::set<std::size_t> indices;
  std::map<std::size_t, std::string> rows;
  for (std::size_t s = 0; s < shards.size(); ++s) {
    const ShardFile& f = shards[s];
    if (f.header != shards[0].header || f.shard.count != shards[0].shard.count)
      throw SweepError("--merge: '" + paths[s] + "' is from another sweep (its header differs from '" +
                       paths[0] + "')");
    if (!indices.insert(f.shard.index).second)
      throw SweepError("--merge: shard " + std::to_string(f.shard.index) + " given twice");
    for (const auto& [i, row] : f.rows) {
      if (i >= f.total || i % f.shard.count != f.shard.index)
        throw SweepError("--merge: '" + paths[s] + "': run " + std::to_string(i) + " is not in its shard");
      rows[i] = row;
    }
  }
  const std::size_t total = shards[0].total;
  std::string missing;
  std::size_t count = 0;
  for (std::size_t i = 0; i < total && count < 10; ++i)
    if (!rows.contains(i)) missing += (count++ ? ", " : "") + std::to_string(i);
  if (!missing.empty())
    throw SweepError("--merge: runs missing (" + missing + (count == 10 ? ", ..." : "") + ") of " +
                     std::to_string(total) + ": give every shard's complete output");

  // The sweep's own command (shard 0's, or the lowest given) stays; the merge's is added.
  const ShardFile& first =
      *std::min_element(shards.begin(), shards.end(),
                        [](const ShardFile& a, const ShardFile& b) { return a.shard.index < b.shard.index; });
  std::optional<OutputFile> opened;  // every write checked (WriteError naming the file)
  try {
    opened.emplace(out);
  } catch (const WriteError& e) {
    throw SweepError(std::string("--out: ") + e.what());
  }
  OutputFile& file = *opened;
  if (jsonl) {
    const json h = json::parse(shards[0].header[0]);
    // The same key order as a sweep writes.
    ojson o;
    o["sweep"] = {{"version", h["sweep"]["version"]},
                  {"commit", h["sweep"]["commit"]},
                  {"command", first.command},
                  {"merge", command},
                  {"runs", h["sweep"]["runs"]},
                  {"definition", h["sweep"]["definition"]},
                  {"shard", "0/1"},
                  {"columns", h["sweep"]["columns"]},
                  {"base", h["sweep"]["base"]}};
    file.write(o.dump() + "\n");
  } else {
    for (const std::string& line : shards[0].header) {
      const std::string text = line == "# command" ? "# command: " + first.command + "\n# merge: " + command
                               : line == "# shard" ? "# shard: 0/1"
                                                   : line;
      file.write(text + "\n");
    }
  }
  for (const auto& [i, row] : rows) file.write(row + "\n");
  file.close();
}

}  // namespace spinfold::sweep
