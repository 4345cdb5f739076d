// The view-parameter and layer tables: their defaults, ranges and the reasons they give.
#include "render/view_parameters.h"

#include <gtest/gtest.h>

#include <set>

namespace spinfold::render {
namespace {

TEST(ViewParameters, NamesAreUniqueAndEachHasHelp) {
  std::set<std::string_view> names;
  for (const ViewParameter& p : view_parameters()) {
    EXPECT_TRUE(names.insert(p.name).second) << p.name;
    EXPECT_FALSE(p.help.empty()) << p.name;
  }
  EXPECT_EQ(names, (std::set<std::string_view>{"width", "height", "view", "layers", "scale", "yaw", "pitch",
                                               "distance", "trail"}));
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
            "surface,grid,body,frame,trail,hud");
  EXPECT_FALSE(default_value(view_parameter("yaw")));   // aimed at the body
  EXPECT_FALSE(default_value(view_parameter("view")));  // the surface's own
}

TEST(ViewParameters, TypesComeFromTheMembers) {
  EXPECT_EQ(parameter_type(view_parameter("width")), ParameterType::integer);
  EXPECT_EQ(parameter_type(view_parameter("scale")), ParameterType::number);
  EXPECT_EQ(parameter_type(view_parameter("trail")), ParameterType::number);
  EXPECT_EQ(parameter_type(view_parameter("view")), ParameterType::enumeration);
  EXPECT_EQ(parameter_type(view_parameter("layers")), ParameterType::list);
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
  EXPECT_EQ(why("view", std::string("cube")),
            "must be sphere, disk, hyperboloid, klein, halfplane, tractricoid, plane or conformal");
  // Every layer is listed, `actions` included.
  EXPECT_EQ(why("layers", std::string("surface,sparkles")),
            "'sparkles' is not one of surface, grid, body, frame, trail, hud, actions");
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
  EXPECT_EQ(parse_layers("surface,grid,body,frame,trail,hud,actions"), all);
  EXPECT_EQ(parse_layers(default_layer_list()), kDefaultLayers);
  EXPECT_EQ(parse_layers(""), 0u);
  std::string unknown;
  EXPECT_FALSE(parse_layers("grid,,glitter", &unknown));
  EXPECT_EQ(unknown, "glitter");
}

}  // namespace
}  // namespace spinfold::render
