#include "bench/cross_cpu.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "engine/exact_solution.h"
#include "engine/integrator.h"
#include "engine/invariants.h"
#include "engine/simulation.h"

namespace spinfold::bench {

namespace {

// One run's end: status, position X [length], internal matrix L, energy H.
struct End {
  std::string status;
  double values[8] = {};  // X₀ X₁ X₂ L₀₀ L₀₁ L₁₀ L₁₁ H
};

// FNV-1a of the bits of libm's transcendental functions over a grid: which variants this process
// runs (they differ between the FMA and the SSE2 code of the same glibc).
unsigned long long libm_fingerprint() {
  unsigned long long h = 1469598103934665603ull;
  for (int i = 1; i <= 20000; ++i) {
    const double x = i * 1e-3;
    for (double v : {std::sin(x), std::cos(x), std::exp(-x), std::log(x), std::atan2(x, 1.3),
                     std::pow(x, 0.37), std::sinh(1e-3 * x), std::cosh(1e-3 * x), std::tan(x)}) {
      unsigned long long bits;
      std::memcpy(&bits, &v, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
    }
  }
  return h;
}

// "scene integrator" → its end at `until`, for every catalog integrator that runs the scene.
std::map<std::string, End> run_all(const CrossCpuOptions& options) {
  std::map<std::string, End> ends;
  for (const std::string& name : options.scenes) {
    const PresetSource* preset = find_preset(name);
    if (!preset) {
      std::fprintf(stderr, "cross-cpu: no preset %s\n", name.c_str());
      continue;
    }
    const Scene base = *parse_scene_text(preset->json).scene;
    for (const CatalogEntry& entry : integrator_catalog()) {
      Scene scene = base;
      scene.integrator.name = std::string(entry.info.name);
      if (entry.info.exact && exact_unsupported_reason(scene)) continue;
      Simulation run = start_simulation(scene);
      advance_to(run, options.until);
      End end;
      end.status = run.state.status == Status::ok ? "ok" : "stopped";
      const GlobalBody body = global_body(run.scene, run.state);
      const double values[8] = {body.X[0],    body.X[1],    body.X[2],    body.L(0, 0),
                                body.L(0, 1), body.L(1, 0), body.L(1, 1), energy(run.scene, run.state)};
      std::copy(std::begin(values), std::end(values), end.values);
      ends[name + " " + std::string(entry.info.name)] = end;
    }
  }
  return ends;
}

std::string dump_text(const std::map<std::string, End>& ends) {
  std::ostringstream out;
  char line[512];
  std::snprintf(line, sizeof line, "libm %016llx\n", libm_fingerprint());
  out << line;
  for (const auto& [key, end] : ends) {
    out << key << ' ' << end.status;
    for (double v : end.values) {
      std::snprintf(line, sizeof line, " %a", v);
      out << line;
    }
    out << '\n';
  }
  return out.str();
}

std::map<std::string, End> parse_dump(const std::string& text, std::string& libm) {
  std::map<std::string, End> ends;
  std::istringstream in(text);
  std::string first, second;
  while (in >> first >> second) {
    if (first == "libm") {
      libm = second;
      continue;
    }
    End end;
    in >> end.status;
    for (double& v : end.values) {
      std::string word;
      in >> word;
      v = std::strtod(word.c_str(), nullptr);
    }
    ends[first + " " + second] = end;
  }
  return ends;
}

// This program again with the tunable in its environment, asked for its dump.
std::string other_cpu_dump(const CrossCpuOptions& options) {
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  std::ostringstream command;
  command << "GLIBC_TUNABLES='" << options.tunable << "' '" << self << "' cross-cpu --dump --until "
          << options.until;
  for (const std::string& s : options.scenes) command << " --scenes " << s;
  std::string text;
  FILE* pipe = popen(command.str().c_str(), "r");
  if (!pipe) return text;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) text.append(buffer, n);
  pclose(pipe);
  return text;
}

}  // namespace

int run_cross_cpu(const CrossCpuOptions& options) {
  if (options.dump) {
    std::fputs(dump_text(run_all(options)).c_str(), stdout);
    return 0;
  }
  const auto start = std::chrono::steady_clock::now();
  std::string libm_here, libm_other;
  const std::map<std::string, End> here = parse_dump(dump_text(run_all(options)), libm_here);
  const std::map<std::string, End> other = parse_dump(other_cpu_dump(options), libm_other);
  std::printf("cross-cpu: t = %g, %zu runs; other CPU: GLIBC_TUNABLES=%s\n", options.until, here.size(),
              options.tunable.c_str());
  std::printf("libm variants: %s here, %s there (%s)\n\n", libm_here.c_str(), libm_other.c_str(),
              libm_here == libm_other ? "THE SAME: the tunable changed nothing, the table proves nothing"
                                      : "they differ");
  // Per integrator, the largest difference over the scenes.
  struct Row {
    int runs = 0, identical = 0;
    double dX = 0, dL = 0, dH = 0, rel_H = 0;
    std::string worst_scene;
  };
  std::map<std::string, Row> rows;
  int missing = 0;
  for (const auto& [key, a] : here) {
    const std::string scene = key.substr(0, key.find(' ')), integrator = key.substr(key.find(' ') + 1);
    const auto it = other.find(key);
    if (it == other.end()) {
      ++missing;
      continue;
    }
    const End& b = it->second;
    Row& row = rows[integrator];
    ++row.runs;
    row.identical += std::memcmp(a.values, b.values, sizeof a.values) == 0 && a.status == b.status;
    double dX = 0, dL = 0;
    for (int i = 0; i < 3; ++i) dX = std::max(dX, std::abs(a.values[i] - b.values[i]));
    for (int i = 3; i < 7; ++i) dL = std::max(dL, std::abs(a.values[i] - b.values[i]));
    const double dH = std::abs(a.values[7] - b.values[7]);
    if (dX > row.dX) row.worst_scene = scene;
    row.dX = std::max(row.dX, dX);
    row.dL = std::max(row.dL, dL);
    row.dH = std::max(row.dH, dH);
    row.rel_H = std::max(row.rel_H, dH / std::max(1e-300, std::abs(a.values[7])));
  }
  std::printf(
      "| integrator | runs | bit-identical | max abs ΔX | max abs ΔL | max abs ΔH | max rel ΔH | worst ΔX in "
      "|\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (const auto& [name, row] : rows)
    std::printf("| %s | %d | %d | %.1e | %.1e | %.1e | %.1e | %s |\n", name.c_str(), row.runs, row.identical,
                row.dX, row.dL, row.dH, row.rel_H, row.worst_scene.c_str());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("\n%.1f s%s\n", seconds, missing ? " (some runs missing from the other CPU's dump)" : "");
  return missing || here.empty() ? 1 : 0;
}

}  // namespace spinfold::bench
