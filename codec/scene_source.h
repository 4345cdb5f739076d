// Where a scene comes from, the one rule for every front door (each CLI subcommand, Python): a
// name given positionally or as --scene is a scene file if a file by that name exists, else a
// preset's name (`spinfold scenes`); nothing given is the default preset. A name that is neither is
// refused naming both, and a name given both ways is refused.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "engine/scene.h"

namespace spinfold {

// Why a scene could not be had (no such file or preset, an unreadable file, both forms given, a
// scene that does not parse): the message names the option and the name.
struct SceneSourceError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

struct SceneSource {
  std::string text;   // the scene's JSON text
  std::string label;  // the file's name (no folder) or the preset's name
  bool file = false;  // read from a file (else a preset)
};

// `name` a file path or a preset's name ("" the default preset); `option` begins the messages
// ("--scene", "scene"). A name with a '/' or ending in .json that is no file is "cannot read scene
// file"; another name that is neither is "no scene file and no preset named".
SceneSource find_scene(std::string_view name, std::string_view option);

// A command's two ways to name its scene: positionally or with --scene, at most one of them.
// Neither: the default preset, or with `required` a SceneSourceError.
SceneSource scene_source(std::string_view positional, std::string_view named, bool required = false);

// A re-run's scene (`spinfold rerun`, cli/commands/rerun.cpp): while one lives, find_scene and
// scene_source give its text, the scene an output recorded, in place of the file or preset the
// recorded command names (the name still gives the label). One at a time, on one thread: the
// command line's; std::logic_error for a second.
class RecordedScene {
 public:
  explicit RecordedScene(std::string text);
  ~RecordedScene();
  RecordedScene(const RecordedScene&) = delete;
  RecordedScene& operator=(const RecordedScene&) = delete;
};

// The command line's integrator options (--integrator, --dt, --tolerance), set over the scene's.
struct IntegratorOverrides {
  std::optional<std::string> name;
  std::optional<double> dt;
  std::optional<double> tolerance;
};

// The scene, parsed and checked with the overrides set (checked as the file is); SceneSourceError
// naming each wrong field.
Scene load_scene(const SceneSource& source, const IntegratorOverrides& overrides = {});

// The presets' names, comma-separated (for messages).
std::string preset_name_list();

}  // namespace spinfold
