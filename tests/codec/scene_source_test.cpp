// The one scene rule of every front door: a file if one has that name, else a preset; both forms
// refused; a name that is neither refused naming the presets.
#include "codec/scene_source.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "codec/presets.h"
#include "tests/error_of.h"

namespace spinfold {
namespace {

namespace fs = std::filesystem;

std::string error_of(const auto& call) {
  return test::error_of<SceneSourceError>(call);
}

TEST(SceneSource, AFileByThatNameElseAPresetElseTheDefault) {
  const SceneSource preset = scene_source("spin_vs_geodesic_sphere", "");
  EXPECT_FALSE(preset.file);
  EXPECT_EQ(preset.text, find_preset("spin_vs_geodesic_sphere")->json);
  EXPECT_EQ(scene_source("", "spin_vs_geodesic_sphere").text, preset.text);  // positional or --scene alike
  EXPECT_EQ(scene_source("", "").label, kDefaultPreset);
  // A file of that name wins over the preset.
  const fs::path dir = fs::temp_directory_path() / ("scene_source_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "spin_vs_geodesic_sphere";
  std::ofstream(file) << R"({"initial": {"r": 0.5}})";
  const SceneSource from_file = scene_source(file.string(), "");
  EXPECT_TRUE(from_file.file);
  EXPECT_EQ(from_file.label, "spin_vs_geodesic_sphere");
  EXPECT_EQ(load_scene(from_file).initial.r, 0.5);
  fs::remove_all(dir);
}

TEST(SceneSource, RefusalsNameTheOptionAndTheName) {
  EXPECT_NE(error_of([] {
              scene_source("", "nosuch");
            }).find("--scene: no scene file and no preset named 'nosuch'"),
            std::string::npos);
  EXPECT_NE(
      error_of([] { scene_source("nosuch", ""); }).find("scene: no scene file and no preset named 'nosuch'"),
      std::string::npos);
  EXPECT_EQ(error_of([] { scene_source("/nonexistent/scene.json", ""); }),
            "cannot read scene file '/nonexistent/scene.json'");
  EXPECT_EQ(error_of([] { scene_source("a.json", "b"); }), "give either a scene file or --scene, not both");
  EXPECT_NE(error_of([] { scene_source("", "", true); }).find("give either a scene file or --scene PRESET"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              load_scene(scene_source("", ""), {.name = "nosuch", .dt = {}, .tolerance = {}});
            }).find("integrator.name"),
            std::string::npos);
}

}  // namespace
}  // namespace spinfold
