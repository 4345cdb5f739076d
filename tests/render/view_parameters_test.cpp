// The view-parameter and layer tables: their defaults, ranges and the reasons they give.
#include "render/view_parameters.h"

#include <gtest/gtest.h>

#include <set>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "engine/simulation.h"
#include "render/scene_builder.h"
#include "render/snapshot.h"
#include "render/view_table.h"
#include "render/views/camera.h"
#include "render/views/view_model.h"
#include "views/view_test_support.h"

namespace spinfold::render {
namespace {

TEST(ViewParameters, NamesAreUniqueAndEachHasHelp) {
  std::set<std::string_view> names;
  for (const ViewParameter& p : view_parameters()) {
    EXPECT_TRUE(names.insert(p.name).second) << p.name;
    EXPECT_FALSE(p.help.empty()) << p.name;
  }
  EXPECT_EQ(names, (std::set<std::string_view>{"width", "height", "view", "layers", "scale", "yaw", "pitch",
                                               "distance", "trail", "motion", "shown"}));
}

// The request's defaults are the renderer's: a frame asked for with no parameter is ViewOptions{}.
TEST(ViewParameters, DefaultsAreTheRenderersAndWithinTheirRanges) {
  const ViewRequest r;
  const ViewOptions o;
  EXPECT_EQ(r.width, o.width);
  EXPECT_EQ(r.height, o.height);
  EXPECT_EQ(r.layers, o.layers);
  EXPECT_EQ(r.scale, o.scale);
  for (const ViewParameter& p : view_parameters()) {
    const auto d = default_value(p);
    if (!d || !std::holds_alternative<double>(*d)) continue;
    EXPECT_TRUE(allowed_range(p).contains(std::get<double>(*d))) << p.name;
  }
  EXPECT_EQ(std::get<double>(*default_value(view_parameter("width"))), 640.0);
  EXPECT_EQ(std::get<std::string>(*default_value(view_parameter("layers"))),
            "surface,grid,body,frame,trail,hud,bending,drift");
  EXPECT_FALSE(default_value(view_parameter("yaw")));                                    // aimed at the body
  EXPECT_FALSE(default_value(view_parameter("view")));                                   // the surface's own
  EXPECT_EQ(std::get<std::string>(*default_value(view_parameter("motion"))), "steady");  // the lesson's
}

TEST(ViewParameters, TypesComeFromTheMembers) {
  EXPECT_EQ(parameter_type(view_parameter("width")), ParameterType::integer);
  EXPECT_EQ(parameter_type(view_parameter("scale")), ParameterType::number);
  EXPECT_EQ(parameter_type(view_parameter("trail")), ParameterType::number);
  EXPECT_EQ(parameter_type(view_parameter("view")), ParameterType::enumeration);
  EXPECT_EQ(parameter_type(view_parameter("layers")), ParameterType::list);
  EXPECT_EQ(parameter_type(view_parameter("motion")), ParameterType::enumeration);
  EXPECT_EQ(choices(view_parameter("motion")), (std::vector<std::string_view>{"steady", "follow"}));
  EXPECT_THROW(view_parameter("colour"), std::logic_error);
}

TEST(ViewParameters, SetParameterSetsTheMemberFromANumberOrText) {
  ViewRequest r;
  EXPECT_FALSE(set_parameter(r, view_parameter("width"), 320.0));
  EXPECT_FALSE(set_parameter(r, view_parameter("height"), std::string("200")));
  EXPECT_FALSE(set_parameter(r, view_parameter("view"), std::string("disk")));
  EXPECT_FALSE(set_parameter(r, view_parameter("layers"), std::string("body,actions")));
  EXPECT_FALSE(set_parameter(r, view_parameter("pitch"), std::string("-0.5")));
  EXPECT_FALSE(set_parameter(r, view_parameter("trail"), 0.0));
  EXPECT_FALSE(set_parameter(r, view_parameter("motion"), std::string("follow")));
  EXPECT_EQ(r.motion, CameraMotion::follow);
  EXPECT_EQ(std::get<std::string>(*parameter_value(r, view_parameter("motion"))), "follow");
  EXPECT_EQ(r.width, 320);
  EXPECT_EQ(r.height, 200);
  EXPECT_EQ(r.view, ViewKind::disk);
  EXPECT_EQ(r.layers, kBody | kActions);
  EXPECT_EQ(r.pitch, -0.5);
  EXPECT_EQ(r.trail, 0.0);
  EXPECT_FALSE(r.yaw);
  EXPECT_EQ(layer_list(r.layers), "body,actions");
  EXPECT_EQ(std::get<std::string>(*parameter_value(r, view_parameter("view"))), "disk");
}

// Each refusal reads the same wherever the value came from, and leaves the request as it was.
TEST(ViewParameters, RefusalsSayWhatIsAllowed) {
  ViewRequest r;
  const auto why = [&](std::string_view name, const GivenValue& v) {
    return set_parameter(r, view_parameter(name), v).value_or("(accepted)");
  };
  EXPECT_EQ(why("width", 5000.0), "must be a whole number from 16 to 4096 [pixels]");
  EXPECT_EQ(why("width", 64.5), "must be a whole number from 16 to 4096 [pixels]");
  EXPECT_EQ(why("width", std::string("wide")), "must be a whole number from 16 to 4096 [pixels]");
  EXPECT_EQ(why("scale", 0.0), "must be a number in (0, 10]");
  EXPECT_EQ(why("pitch", 2.0), "must be a number from -1.55 to 1.55 [rad]");
  EXPECT_EQ(why("distance", std::string("1e400")), "must be a number from 1.2 to 100 [radii]");
  EXPECT_EQ(why("trail", -1.0), "must be a number >= 0 [time]");
  EXPECT_EQ(why("motion", std::string("orbit")), "must be steady or follow");
  EXPECT_EQ(why("view", std::string("cube")),
            "must be sphere, disk, hyperboloid, klein, halfplane, tractricoid, plane, conformal, revolution, "
            "chart or formula");
  // Every layer is listed, `actions` included.
  EXPECT_EQ(
      why("layers", std::string("surface,sparkles")),
      "'sparkles' is not one of surface, grid, body, frame, trail, hud, actions, curvature, bending, drift, "
      "plain");
  EXPECT_EQ(r.width, 640);
  EXPECT_EQ(r.scale, 0.25);
  EXPECT_FALSE(r.view);
  EXPECT_EQ(r.layers, kDefaultLayers);
  // A server's smaller side limit narrows the range and its words.
  EXPECT_EQ(set_parameter(r, view_parameter("width"), 2048.0, 1024).value_or(""),
            "must be a whole number from 16 to 1024 [pixels]");
}

TEST(ViewParameters, LayerTableDefinesTheNamesAndTheDefaultMask) {
  ASSERT_EQ(layer_names().size(), std::size(kLayerTable));
  unsigned all = 0;
  for (std::size_t i = 0; i < std::size(kLayerTable); ++i) {
    EXPECT_EQ(layer_names()[i], kLayerTable[i].name);
    EXPECT_EQ(parse_layers(kLayerTable[i].name), kLayerTable[i].bit);
    all |= kLayerTable[i].bit;
  }
  EXPECT_EQ(parse_layers("surface,grid,body,frame,trail,hud,actions,curvature,bending,drift,plain"), all);
  EXPECT_EQ(parse_layers(default_layer_list()), kDefaultLayers);
  EXPECT_EQ(parse_layers(""), 0u);
  std::string unknown;
  EXPECT_FALSE(parse_layers("grid,,glitter", &unknown));
  EXPECT_EQ(unknown, "glitter");
}

// ---- the one resolver (view_options, place_camera, resolve_view) ---------------------------------

Snapshot snapshot_of(const std::string& preset, double t) {
  const Scene scene = *parse_scene_text(find_preset(preset)->json).scene;
  Simulation run;
  return snapshot_at(scene, t, true, std::nullopt, run);
}

// Nothing given: the surface's own view, the body's scale in the view's length, the camera aimed
// at the body, exactly as the front doors did it by hand before (so every golden frame stands).
TEST(ResolveView, NothingGivenIsTheAimedDefaultView) {
  for (const char* preset : {"spinning_rigid_sphere", "spin_vs_geodesic_sphere"}) {
    const Snapshot s = snapshot_of(preset, 1.0);
    ViewOptions by_hand;
    by_hand.kind = default_view(s.surface.kind);
    by_hand.scale = 0.25 * body_scale_length(by_hand.kind, s.surface);
    aim_camera_at_body(by_hand, s);
    const ViewOptions resolved = resolve_view(ViewRequest{}, s);
    EXPECT_EQ(resolved.kind, by_hand.kind) << preset;
    EXPECT_EQ(resolved.scale, by_hand.scale) << preset;
    EXPECT_EQ(resolved.yaw, by_hand.yaw) << preset;
    EXPECT_EQ(resolved.pitch, by_hand.pitch) << preset;
    EXPECT_EQ(resolved.distance, by_hand.distance) << preset;
    EXPECT_EQ(resolved.target, by_hand.target) << preset;
  }
}

// Each part given replaces the aimed one; all three replace all three, the target staying aimed.
TEST(ResolveView, EachCameraPartGivenReplacesTheAimedOne) {
  const Snapshot s = snapshot_of("spinning_rigid_sphere", 1.0);
  const ViewOptions aimed = resolve_view(ViewRequest{}, s);
  ViewRequest r;
  r.pitch = 0.3;
  const ViewOptions pitched = resolve_view(r, s);
  EXPECT_EQ(pitched.pitch, 0.3);
  EXPECT_EQ(pitched.yaw, aimed.yaw);
  EXPECT_EQ(pitched.distance, aimed.distance);
  r.yaw = 0.1;
  r.distance = 4.0;
  const ViewOptions whole = resolve_view(r, s);
  EXPECT_EQ(whole.yaw, 0.1);
  EXPECT_EQ(whole.pitch, 0.3);
  EXPECT_EQ(whole.distance, 4.0);
  EXPECT_EQ(whole.target, aimed.target);
}

TEST(ResolveView, AViewThatCannotShowTheSurfaceIsRefusedNamingTheView) {
  const Snapshot s = snapshot_of("spinning_rigid_sphere", 0.0);
  ViewRequest r;
  r.view = ViewKind::hyperboloid;
  EXPECT_TRUE(view_refusal(r, s.surface.kind));
  try {
    (void)resolve_view(r, s);
    FAIL() << "no refusal";
  } catch (const ViewRefused& e) {
    EXPECT_EQ(e.parameter, "view");
    EXPECT_EQ(e.value, "hyperboloid");
    EXPECT_EQ(std::string(e.what()), *view_refusal(r, s.surface.kind));
  }
}

// The one reader of numbers as text and the one writer of what a number must be (number_rule.h).
// The viewer's own angles about a target that follows the body (the hyperboloid's) are never a
// view from under the sheet: such a camera is tilted up (a drop of the body across the bowl left
// the page's camera looking at the dark underside). A lit one is left as asked.
TEST(PlaceCamera, TheViewersOwnAnglesNeverLookFromUnderTheHyperboloidsSheet) {
  const ViewModel& model = view_model(ViewKind::hyperboloid);
  int tilted = 0, kept = 0;
  for (const double r : {0.4, 1.5, 3.0})
    for (int k = 0; k < 21; ++k)
      for (const double pitch : {0.05, 0.3, 0.6})
        for (const double distance : {1.5, 3.4, 6.0}) {
          const Snapshot s = testing::body_at(SurfaceKind::pseudosphere, 1.0, r, 0.3);
          ViewOptions view;
          view.kind = ViewKind::hyperboloid, view.width = 640, view.height = 480;
          const ViewRequest request{
              .view = ViewKind::hyperboloid, .yaw = 0.3 * k, .pitch = pitch, .distance = distance};
          place_camera(view, request, s);
          EXPECT_TRUE(model.on_lit_side(eye_of(model.camera(view)))) << r << " " << k << " " << pitch;
          if (view.pitch == pitch && view.yaw == 0.3 * k)
            ++kept;
          else
            ++tilted;
        }
  EXPECT_GT(tilted, 10);  // the rule is needed
  EXPECT_GT(kept, 100);   // and a lit camera stays the viewer's
}

TEST(NumberRule, OneReaderAndOneWriter) {
  EXPECT_EQ(number_from_text("2.5"), 2.5);
  EXPECT_EQ(number_from_text("1e3"), 1000.0);
  for (const char* bad : {"", "nan", "inf", "-inf", "1x", " 1", "+1", "1e999"})
    EXPECT_FALSE(number_from_text(bad)) << bad;
  const NumberRule side{.whole = true, .range = {.min = 16, .max = 4096}, .unit = "pixels"};
  EXPECT_EQ(must_be(side), "must be a whole number from 16 to 4096 [pixels]");
  EXPECT_TRUE(allows(side, 16.0));
  EXPECT_FALSE(allows(side, 16.5));
  EXPECT_FALSE(allows(side, 1099511627776.0));
  EXPECT_EQ(must_be({.range = {.min = 0, .min_open = true, .max = 10}}), "must be a number in (0, 10]");
  EXPECT_EQ(must_be({.range = kNonNegative, .unit = "time"}), "must be a number >= 0 [time]");
  const NumberRule steps{.whole = true, .range = {.min = 1, .max = kMaxWholeNumber}};
  EXPECT_FALSE(allows(steps, 18446744073709551616.0));  // 2^64
  EXPECT_FALSE(allows(steps, -1.0));
  EXPECT_EQ(refused("--pitch", "must be a number from -1.55 to 1.55 [rad]", "'2'"),
            "--pitch: must be a number from -1.55 to 1.55 [rad] (got '2')");
  // The view table says it with the same writer.
  EXPECT_EQ(expectation(view_parameter("width")), must_be(side));
}

}  // namespace
}  // namespace spinfold::render
