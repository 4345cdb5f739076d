#include "codec/provenance.h"

#include <cstdio>
#include <stdexcept>
#include <utility>

#include "codec/scene_json.h"
#include "engine/embedded_run.h"
#include "engine/number_text.h"
#include "engine/simulation.h"

namespace spinfold {

std::string version_line() {
  return std::string(build_version()) + " (commit " + std::string(build_commit()) + ")";
}

std::string fnv1a64_hex(std::string_view text) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const unsigned char c : text) hash = (hash ^ c) * 0x100000001b3ULL;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return hex;
}

std::string scene_hash(const Scene& scene) {
  return fnv1a64_hex(scene_to_json(scene).dump());  // nlohmann::json sorts keys: canonical
}

nlohmann::ordered_json provenance_json(const Scene& scene, std::string_view command) {
  nlohmann::ordered_json j;
  j["software"] = "spinfold";
  j["version"] = std::string(build_version());
  j["commit"] = std::string(build_commit());
  j["scene_hash"] = scene_hash(scene);
  j["integrator"] = {{"name", scene.integrator.name},
                     {"runs", std::string(resolve_integrator(scene))},
                     {"dt", scene.integrator.dt},
                     {"tolerance", scene.integrator.tolerance}};
  // where the curvature varies: whether the orbit alone was stepped (engine/embedded_run.h)
  if (chart_free(scene.surface)) j["integrator"]["steps"] = steps_orbit_only(scene) ? "orbit" : "all";
  if (!command.empty()) {
    j["command"] = std::string(command);
    j["scene"] = scene_to_json(scene);
  }
  return j;
}

std::string provenance_header(const Scene& scene) {
  return "version=" + std::string(build_version()) + "; commit=" + std::string(build_commit()) +
         "; scene_hash=" + scene_hash(scene) + "; integrator=" + std::string(resolve_integrator(scene)) +
         "; dt=" + shortest(scene.integrator.dt) + "; tolerance=" + shortest(scene.integrator.tolerance);
}

std::vector<std::pair<std::string, std::string>> picture_texts(const Scene& scene, std::string_view command,
                                                               double t, std::string_view view) {
  nlohmann::ordered_json p = provenance_json(scene, command);
  p["t"] = t;
  p["view"] = std::string(view);
  return {{"Software", "spinfold " + version_line()}, {"Source", p.dump()}};
}

std::string command_line(int argc, const char* const* argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    std::string a = argv[i];
    for (char& c : a)
      if (c == '\n' || c == '\r') c = ' ';
    if (a.empty() || a.find_first_of(" \t\"'\\$`;&|<>()*?") != std::string::npos) {
      std::string quoted = "'";
      for (char c : a) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
      a = quoted + "'";
    }
    line += (i ? " " : "") + a;
  }
  return line;
}

std::vector<std::string> command_words(std::string_view line) {
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == ' ' || c == '\t') {
      if (in_word) words.push_back(std::exchange(word, {}));
      in_word = false;
    } else if (c == '\'') {
      const std::size_t close = line.find('\'', i + 1);
      if (close == std::string_view::npos)
        throw std::invalid_argument("a quote opened at position " + std::to_string(i) + " is not closed");
      word.append(line.substr(i + 1, close - i - 1));
      in_word = true;
      i = close;
    } else if (c == '\\' && i + 1 < line.size()) {
      word += line[++i];
      in_word = true;
    } else {
      word += c;
      in_word = true;
    }
  }
  if (in_word) words.push_back(word);
  return words;
}

}  // namespace spinfold
