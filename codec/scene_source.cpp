#include "codec/scene_source.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "codec/presets.h"
#include "codec/scene_json.h"

namespace spinfold {

std::string preset_name_list() {
  std::string names;
  for (const PresetSource& p : preset_sources()) names += (names.empty() ? "" : ", ") + std::string(p.name);
  return names;
}

namespace {
const std::string* recorded_scene = nullptr;  // RecordedScene's text while one lives
}  // namespace

RecordedScene::RecordedScene(std::string text) {
  if (recorded_scene) throw std::logic_error("RecordedScene: one is already in force");
  recorded_scene = new std::string(std::move(text));
}

RecordedScene::~RecordedScene() {
  delete recorded_scene;
  recorded_scene = nullptr;
}

SceneSource find_scene(std::string_view name, std::string_view option) {
  if (recorded_scene) {
    const bool preset = find_preset(name.empty() ? kDefaultPreset : name) != nullptr &&
                        name.find('/') == std::string_view::npos && !name.ends_with(".json");
    return {*recorded_scene,
            name.empty() ? std::string(kDefaultPreset) : std::filesystem::path(name).filename().string(),
            !preset};
  }
  if (name.empty())
    return {std::string(find_preset(kDefaultPreset)->json), std::string(kDefaultPreset), false};
  const std::string path(name);
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec)) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SceneSourceError("cannot read scene file '" + path + "'");
    std::ostringstream text;
    text << in.rdbuf();
    return {text.str(), std::filesystem::path(path).filename().string(), true};
  }
  if (const PresetSource* preset = find_preset(name)) return {std::string(preset->json), path, false};
  if (path.find('/') != std::string::npos || path.ends_with(".json"))  // meant as a file
    throw SceneSourceError("cannot read scene file '" + path + "'");
  throw SceneSourceError(std::string(option) + ": no scene file and no preset named '" + path +
                         "' (presets: " + preset_name_list() + ")");
}

SceneSource scene_source(std::string_view positional, std::string_view named, bool required) {
  if (!positional.empty() && !named.empty())
    throw SceneSourceError("give either a scene file or --scene, not both");
  if (required && positional.empty() && named.empty())
    throw SceneSourceError("give either a scene file or --scene PRESET (see `spinfold scenes`)");
  return positional.empty() ? find_scene(named, "--scene") : find_scene(positional, "scene");
}

Scene load_scene(const SceneSource& source, const IntegratorOverrides& overrides) {
  SceneParse parsed = parse_scene_text(source.text);
  if (!parsed.errors.empty()) throw SceneSourceError(describe_errors(parsed.errors));
  if (!overrides.name && !overrides.dt && !overrides.tolerance) return *parsed.scene;
  nlohmann::json document = scene_to_json(*parsed.scene);
  if (overrides.name) document["integrator"]["name"] = *overrides.name;
  if (overrides.dt) document["integrator"]["dt"] = *overrides.dt;
  if (overrides.tolerance) document["integrator"]["tolerance"] = *overrides.tolerance;
  parsed = parse_scene(document);
  if (!parsed.errors.empty()) throw SceneSourceError(describe_errors(parsed.errors));
  return *parsed.scene;
}

}  // namespace spinfold
