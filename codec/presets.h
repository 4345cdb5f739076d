// Preset scenes (assets/scenes/*.json) and their lesson cards (assets/lessons/*.txt), embedded in the
// binary at build time.
#pragma once

#include <span>
#include <string_view>

namespace spinfold {

struct PresetSource {
  std::string_view name;  // file name without .json
  std::string_view json;  // the scene, in the same format as the CLI and the API accept
  // What to look for, in plain words, for a class (assets/lessons/NAME.txt): the claim the preset
  // shows, which its tests check.
  std::string_view look_for;
};

std::span<const PresetSource> preset_sources();
// The lesson sequence (assets/lessons/sequence.txt): every preset once, in teaching order, each in
// its chapter (one surface or one idea). The gallery's order and each preset's "next".
struct LessonPlace {
  std::string_view chapter;  // its title, in plain words
  std::string_view preset;   // a PresetSource::name
};
std::span<const LessonPlace> lesson_sequence();

// nullptr if there is no preset of that name.
const PresetSource* find_preset(std::string_view name);

// The scene `spinfold simulate` and the server run when none is given.
inline constexpr std::string_view kDefaultPreset = "spinning_rigid_sphere";

}  // namespace spinfold
