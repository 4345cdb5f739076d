// The scene options of simulate, render and record: a scene file or a preset's name (positional
// or --scene, the one rule of codec/scene_source.h) and the integrator overrides.
#pragma once

#include <optional>
#include <string>

#include "cli/commands/command.h"
#include "codec/scene_source.h"

namespace spinfold::cli {

struct SceneOptions {
  std::string scene_file;  // positional
  std::string preset;      // --scene
  std::optional<std::string> integrator;
  std::optional<double> dt;
  std::optional<double> tolerance;
  std::string command;  // the command line, for the provenance
};

// The scene, with --integrator, --dt and --tolerance checked as the scene file is.
inline Scene load_scene(const SceneOptions& opt) {
  try {
    return spinfold::load_scene(scene_source(opt.scene_file, opt.preset),
                                {.name = opt.integrator, .dt = opt.dt, .tolerance = opt.tolerance});
  } catch (const SceneSourceError& e) {
    throw BadInput{e.what()};
  }
}

}  // namespace spinfold::cli
