// Where an output came from (codec/provenance.h): the hash, the fields of the record, the header
// and picture texts built from it, and the command line; none of it may depend on the clock.
#include "codec/provenance.h"

#include <gtest/gtest.h>

#include <random>
#include <regex>
#include <stdexcept>

#include "codec/scene_json.h"
#include "engine/simulation.h"

namespace spinfold {
namespace {

Scene sphere_scene() {
  Scene s;
  s.surface = {SurfaceKind::sphere, 2.0};
  s.integrator = {"rk4", 0.005, 1e-9};
  return s;
}

// The published FNV-1a 64 test vectors (Fowler, Noll, Vo), written out independently.
TEST(Provenance, Fnv1a64MatchesTheReferenceVectors) {
  EXPECT_EQ(fnv1a64_hex(""), "cbf29ce484222325");
  EXPECT_EQ(fnv1a64_hex("a"), "af63dc4c8601ec8c");
  EXPECT_EQ(fnv1a64_hex("foobar"), "85944171f73967e8");
}

// The scene hash is of the canonical JSON: equal scenes hash equal, one changed field does not,
// and it is 16 lower-case hex digits.
TEST(Provenance, SceneHashIsOfTheCanonicalJson) {
  const Scene a = sphere_scene();
  EXPECT_EQ(scene_hash(a), fnv1a64_hex(scene_to_json(a).dump()));
  EXPECT_TRUE(std::regex_match(scene_hash(a), std::regex("[0-9a-f]{16}"))) << scene_hash(a);
  EXPECT_EQ(scene_hash(a), scene_hash(sphere_scene()));
  Scene b = a;
  b.surface.radius = 2.0000000001;
  EXPECT_NE(scene_hash(a), scene_hash(b));
}

// The same scene read from two texts with different spacing and key order has one hash.
TEST(Provenance, SceneHashIgnoresTheFilesLayout) {
  const SceneParse one =
      parse_scene_text(R"({"surface": {"kind": "sphere", "radius": 2}, "body": {"mass": 3}})");
  const SceneParse two =
      parse_scene_text("{\"body\":{\"mass\":3.0},\n  \"surface\":{\"radius\":2,\"kind\":\"sphere\"}}");
  ASSERT_TRUE(one.scene && two.scene);
  EXPECT_EQ(scene_hash(*one.scene), scene_hash(*two.scene));
}

// The record's fields, in their documented order; `runs` is what the engine resolves, `command`
// is omitted when empty.
TEST(Provenance, JsonHasTheDocumentedFieldsInOrder) {
  const Scene s = sphere_scene();
  const nlohmann::ordered_json p = provenance_json(s, "spinfold simulate x.json");
  std::vector<std::string> keys;
  for (const auto& [key, value] : p.items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{"software", "version", "commit", "scene_hash", "integrator",
                                            "command", "scene"}));
  EXPECT_EQ(p["software"], "spinfold");
  EXPECT_EQ(p["version"], std::string(build_version()));
  EXPECT_EQ(p["commit"], std::string(build_commit()));
  EXPECT_EQ(p["scene_hash"], scene_hash(s));
  EXPECT_EQ(p["integrator"]["name"], "rk4");
  EXPECT_EQ(p["integrator"]["runs"], "rk4");
  EXPECT_EQ(p["integrator"]["dt"], 0.005);
  EXPECT_EQ(p["integrator"]["tolerance"], 1e-9);
  EXPECT_EQ(p["command"], "spinfold simulate x.json");
  // the scene itself where a command made the output (spinfold rerun runs it again), as it reads back
  EXPECT_EQ(nlohmann::json(p["scene"]), scene_to_json(s));
  const SceneParse back = parse_scene(nlohmann::json(p["scene"]));
  ASSERT_TRUE(back.scene) << describe_errors(back.errors);
  EXPECT_EQ(scene_hash(*back.scene), scene_hash(s));
  EXPECT_FALSE(provenance_json(s, "").contains("command"));
  EXPECT_FALSE(provenance_json(s, "").contains("scene"));
}

// `auto` is recorded as asked and as resolved, so a reader sees which method ran.
TEST(Provenance, AutoRecordsTheResolvedIntegrator) {
  Scene s = sphere_scene();
  s.integrator.name = "auto";
  const nlohmann::ordered_json p = provenance_json(s, "");
  EXPECT_EQ(p["integrator"]["name"], "auto");
  EXPECT_EQ(p["integrator"]["runs"], std::string(resolve_integrator(s)));
  EXPECT_NE(p["integrator"]["runs"], "auto");
}

// Where the curvature varies the record says what was stepped: the orbit alone (the internal motion in
// closed form) or every number; on the constant-curvature surfaces it has no such field.
TEST(Provenance, SaysWhetherOnlyTheOrbitWasStepped) {
  EXPECT_FALSE(provenance_json(sphere_scene(), "")["integrator"].contains("steps"));
  Scene s;
  s.surface.kind = SurfaceKind::torus;
  s.body.inertia = 0.3;
  EXPECT_EQ(provenance_json(s, "")["integrator"]["steps"], "orbit");
  s.integrator.stepping = Stepping::full;
  EXPECT_EQ(provenance_json(s, "")["integrator"]["steps"], "all");
  s.integrator.stepping = Stepping::automatic;
  s.body.inertia_matrix = InertiaMatrix{0.3, 0.1, 0.1, 0.2};
  EXPECT_EQ(provenance_json(s, "")["integrator"]["steps"], "all");
}

// Nothing depends on the clock or the host: two calls give the same bytes.
TEST(Provenance, SameSceneSameBytes) {
  const Scene s = sphere_scene();
  EXPECT_EQ(provenance_json(s, "cmd").dump(), provenance_json(s, "cmd").dump());
  EXPECT_EQ(provenance_header(s), provenance_header(s));
  EXPECT_EQ(picture_texts(s, "cmd", 1.5, "sphere"), picture_texts(s, "cmd", 1.5, "sphere"));
}

TEST(Provenance, HeaderIsKeyValuePairsOnOneLine) {
  const Scene s = sphere_scene();
  EXPECT_EQ(provenance_header(s),
            "version=" + std::string(build_version()) + "; commit=" + std::string(build_commit()) +
                "; scene_hash=" + scene_hash(s) + "; integrator=rk4; dt=0.005; tolerance=1e-09");
}

// PNG text chunks: Software names the build, Source is the record plus the frame's time and view.
TEST(Provenance, PictureTextsCarryTimeAndView) {
  const Scene s = sphere_scene();
  const auto texts = picture_texts(s, "spinfold render", 2.25, "disk");
  ASSERT_EQ(texts.size(), 2u);
  EXPECT_EQ(texts[0].first, "Software");
  EXPECT_EQ(texts[0].second,
            "spinfold " + std::string(build_version()) + " (commit " + std::string(build_commit()) + ")");
  EXPECT_EQ(texts[0].second, "spinfold " + version_line());
  EXPECT_EQ(texts[1].first, "Source");
  const nlohmann::json source = nlohmann::json::parse(texts[1].second);
  EXPECT_EQ(source["t"], 2.25);
  EXPECT_EQ(source["view"], "disk");
  EXPECT_EQ(source["command"], "spinfold render");
  EXPECT_EQ(source["scene_hash"], scene_hash(s));
}

// argv as a shell would read it back: plain words bare, the rest single-quoted (a quote inside as
// '\''), line breaks flattened so the record stays on one line.
TEST(Provenance, CommandLineQuotesWhatTheShellWouldSplit) {
  const char* const argv[] = {"spinfold", "simulate", "my scene.json", "", "it's", "a$b", "x\ny", "--dt=0.1"};
  EXPECT_EQ(command_line(8, argv), "spinfold simulate 'my scene.json' '' 'it'\\''s' 'a$b' 'x y' --dt=0.1");
  EXPECT_EQ(command_line(0, argv), "");
}

// command_words reads command_line's line back into argv, over random arguments of every character
// the quoting handles (blanks, quotes, backslashes, shell metacharacters, empty ones).
TEST(Provenance, CommandWordsReadTheCommandLineBack) {
  std::mt19937 rng(7);
  const std::string alphabet = "ab=-_./ '\"$`;&|<>()*?#\t";
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<std::string> words(1 + rng() % 6);
    for (std::string& w : words)
      for (int k = static_cast<int>(rng() % 7); k > 0; --k) w += alphabet[rng() % alphabet.size()];
    std::vector<const char*> argv;
    for (const std::string& w : words) argv.push_back(w.c_str());
    const std::string line = command_line(static_cast<int>(argv.size()), argv.data());
    EXPECT_EQ(command_words(line), words) << line;
  }
  EXPECT_EQ(command_words("spinfold  simulate\\ x 'a b'c"),
            (std::vector<std::string>{"spinfold", "simulate x", "a bc"}));
  EXPECT_THROW(command_words("spinfold 'open"), std::invalid_argument);
}

}  // namespace
}  // namespace spinfold
