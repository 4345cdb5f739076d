// The JSON sample and the HUD show the same values: both are made from one read-out.
#include "codec/sample_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "codec/presets.h"
#include "codec/sample_table.h"
#include "codec/scene_json.h"
#include "engine/readout.h"

namespace spinfold {
namespace {

std::string format(const char* pattern, double v) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, v);
  return text;
}

TEST(SampleJson, KeysInTheirDocumentedOrder) {
  const SceneParse parsed = parse_scene_text(R"({"potential": {"deformation": {"kind": "abc", "C": 0.5}}})");
  ASSERT_TRUE(parsed.errors.empty()) << describe_errors(parsed.errors);
  Simulation run = start_simulation(*parsed.scene);
  advance_to(run, 0.5);
  std::string keys;
  const nlohmann::ordered_json sample = sample_to_json(run, -1.0);
  for (const auto& [key, value] : sample.items()) keys += key + " ";
  EXPECT_EQ(keys,
            "t r phi alpha beta theta lambda mu r_dot phi_dot alpha_dot beta_dot theta_dot lambda_dot mu_dot "
            "p_r p_phi p_alpha p_beta p_lambda p_mu X L det_L energy energy_error energy_reference_t "
            "energy_orbital "
            "energy_deformation spin speed heading vorticity C_x C_y M casimir actions frequencies undefined "
            "events status "
            "status_detail "
            "integrator steps ");
}

TEST(SampleJson, ActionsAndFrequenciesWithTheirReasons) {
  // Separable, bounded (isotonic C > 0 on S²): every action and frequency is a number, and the
  // frequencies are the read-out's.
  const SceneParse good = parse_scene_text(R"({"potential": {"deformation": {"kind": "abc", "C": 0.5}},
                                               "initial": {"phi_dot": 0.3, "alpha_dot": 0.2, "mu": 0.7}})");
  ASSERT_TRUE(good.errors.empty()) << describe_errors(good.errors);
  Simulation run = start_simulation(*good.scene);
  const nlohmann::ordered_json sample = sample_to_json(run, -1.0);
  for (const char* key : {"J_r", "J_phi", "J_alpha", "J_beta", "J_x", "J_y"})
    EXPECT_TRUE(sample["actions"][key].is_number()) << key;
  EXPECT_EQ(sample["frequencies"]["x"].get<double>(), *readout(run).actions->nu_x);
  EXPECT_FALSE(sample["undefined"].contains("actions.J_x"));
  // No deformation potential: J_x null, the reason under undefined.
  const SceneParse free = parse_scene_text(R"({"initial": {"phi_dot": 0.3}})");
  const nlohmann::ordered_json free_sample = sample_to_json(start_simulation(*free.scene), -1.0);
  EXPECT_TRUE(free_sample["actions"]["J_x"].is_null());
  EXPECT_TRUE(free_sample["frequencies"]["y"].is_null());
  EXPECT_TRUE(free_sample["undefined"]["actions.J_x"].is_string());
  EXPECT_TRUE(free_sample["undefined"]["frequencies.y"].is_string());
  // Not separable: both null, one reason.
  const SceneParse aniso = parse_scene_text(R"({"body": {"inertia": [[0.2, 0.05], [0.05, 0.1]]}})");
  const nlohmann::ordered_json aniso_sample = sample_to_json(start_simulation(*aniso.scene), -1.0);
  EXPECT_TRUE(aniso_sample["actions"].is_null());
  EXPECT_NE(aniso_sample["undefined"]["actions"].get<std::string>().find("anisotropic"), std::string::npos);
}

TEST(SampleJson, SampleAndHudComeFromTheSameReadout) {
  for (const PresetSource& preset : preset_sources()) {
    const SceneParse parsed = parse_scene_text(preset.json);
    ASSERT_TRUE(parsed.scene) << preset.name;
    Simulation run = start_simulation(*parsed.scene);
    advance_to(run, 0.9);
    const Readout r = readout(run);
    const nlohmann::ordered_json sample = sample_to_json(run, -1.0);
    nlohmann::ordered_json main_body = sample;
    main_body.erase("companions");
    EXPECT_EQ(main_body, sample_to_json(r, events_after(run, -1.0))) << preset.name;
    // Each companion's sample is its own run's read-out, with its label first.
    for (std::size_t i = 0; i < run.companions.size(); ++i) {
      nlohmann::ordered_json companion = sample["companions"][i];
      EXPECT_EQ(companion["label"], companion_label(run.scene, i));
      companion.erase("label");
      EXPECT_EQ(companion, sample_to_json(readout(run.companions[i]), events_after(run.companions[i], -1.0)));
    }
    EXPECT_EQ(sample.contains("companions"), !run.companions.empty()) << preset.name;

    // The sample's numbers are the read-out's, bit for bit.
    EXPECT_EQ(sample["t"].get<double>(), r.t);
    EXPECT_EQ(sample["energy"].get<double>(), r.energy);
    EXPECT_EQ(sample["energy_error"].get<double>(), r.energy_error);
    EXPECT_EQ(sample["spin"].get<double>(), r.spin);
    EXPECT_EQ(sample["vorticity"].get<double>(), r.vorticity);
    EXPECT_EQ(sample["det_L"].get<double>(), r.det_L);
    EXPECT_EQ(sample["status"], std::string(r.status_name));
    EXPECT_EQ(sample["status_detail"], std::string(r.status_detail));
    EXPECT_EQ(sample["integrator"], std::string(r.integrator));
    EXPECT_EQ(sample["steps"].get<std::uint64_t>(), r.steps);

    // The HUD's lines print those same numbers.
    const std::vector<std::string> hud = readout_lines(run.scene, r);
    ASSERT_EQ(hud.size(), 6u);
    EXPECT_EQ(hud[0], format("t = %.3f", sample["t"].get<double>())) << preset.name;
    EXPECT_EQ(hud[1], run.scene.friction
                          ? format("energy change = %.2e (friction)", sample["energy_error"].get<double>())
                          : format("energy error = %.2e", sample["energy_error"].get<double>()))
        << preset.name;
    EXPECT_EQ(hud[2].rfind("integrator: " + sample["integrator"].get<std::string>(), 0), 0u) << preset.name;
    EXPECT_EQ(hud[2].find("[stopped]") != std::string::npos, sample["status"] != "ok") << preset.name;
    EXPECT_EQ(hud[5], format("spin = %.4f", sample["spin"].get<double>()) +
                          format("  det L = %.4f", sample["det_L"].get<double>()))
        << preset.name;
  }
}

// The arrays of the Python binding hold the JSON sample's numbers to the bit, NaN for its nulls and
// missing values, over every preset and a start far out on H² (p_phi and M null there).
TEST(SampleJson, SampleValuesAreTheJsonNumbersToTheBit) {
  std::vector<std::string> scenes;
  for (const PresetSource& p : preset_sources()) scenes.emplace_back(p.json);
  scenes.push_back(R"({"surface": {"kind": "pseudosphere", "radius": 1}, "initial": {"r": 22, "spin": 1}})");
  scenes.push_back(R"({"surface": {"kind": "sphere"}, "initial": {"r": 0}})");  // at the pole
  const auto names = sample_value_names();
  std::vector<double> values(names.size());
  int nulls = 0;
  for (const std::string& text : scenes) {
    const SceneParse parsed = parse_scene_text(text);
    ASSERT_TRUE(parsed.scene) << describe_errors(parsed.errors);
    Simulation run = start_simulation(*parsed.scene);
    for (double t : {0.0, 0.7, 2.3}) {
      advance_to(run, t);
      const Readout r = readout(run);
      sample_values(r, values);
      const auto flat = flatten_sample(sample_to_json(r, {}));
      for (std::size_t i = 0; i < names.size(); ++i) {
        const auto found = flat.find(names[i]);
        if (found == flat.end() || found->second.is_null()) {
          EXPECT_TRUE(std::isnan(values[i])) << names[i] << " in " << text.substr(0, 60);
          ++nulls;
        } else {
          EXPECT_EQ(values[i], found->second.get<double>()) << names[i] << " in " << text.substr(0, 60);
        }
      }
      std::size_t listed = 0;
      for (const auto& [field, reason] : undefined_values(r))
        listed += flat.at("undefined").get<std::string>().find(field) != std::string::npos;
      EXPECT_EQ(listed, undefined_values(r).size());
    }
  }
  EXPECT_GT(nulls, 0);
}

}  // namespace
}  // namespace spinfold
