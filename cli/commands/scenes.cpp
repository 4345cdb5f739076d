// `spinfold scenes`: the embedded presets, one per line with its description.
#include <cstdio>
#include <string>

#include "cli/commands/command.h"
#include "codec/presets.h"
#include "codec/scene_json.h"

namespace spinfold::cli {

namespace {

int list_scenes() {
  for (const PresetSource& p : preset_sources()) {
    const SceneParse parsed = parse_scene_text(p.json);
    const std::string description = parsed.scene ? parsed.scene->description : "(invalid preset)";
    std::printf("%-32s %s\n", std::string(p.name).c_str(), description.c_str());
  }
  return 0;
}

}  // namespace

Command register_scenes(CLI::App& app) {
  return {app.add_subcommand("scenes", "List the embedded preset scenes"),
          [](int, char**) { return list_scenes(); }};
}

}  // namespace spinfold::cli
