// The one view-parameter table (render/view_parameters.h) against everything made from it: the
// frame routes' query parameters, the recording body, the CLI's render and record options, the
// OpenAPI document and GET /api/v1/view-parameters. Every name in one is in the others, with the
// same range and default, and a bad value is refused in the same words by each (field, value, reason).
#include "render/view_parameters.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "cli/view_options.h"
#include "engine/number_text.h"
#include "record/recorder.h"
#include "server/api.h"
#include "server/http/route_table.h"

// After Eigen (through the server's headers): httplib.h brings <resolv.h>'s `_res` macro.
#include <httplib.h>

#include "test_server.h"

namespace spinfold::server {
namespace {

using nlohmann::json;

// A side limit below the renderer's, so that the server's ranges are seen to come from its limits.
constexpr int kSide = 1024;
// And a frame's pixels below the side's square (512 × 512).
constexpr long long kPixels = 512LL * 512;

class ViewParameterTable : public ::testing::Test {
 protected:
  static ServerOptions options() {
    ServerOptions options = test::suite_options(4, 1);
    options.limits.max_image_side = kSide;
    options.limits.max_image_pixels = kPixels;
    return options;
  }
  static void SetUpTestSuite() {
    server_.start(options());
    auto res =
        client().Post("/api/v1/sessions", R"({"preset": "spin_vs_geodesic_sphere"})", "application/json");
    ASSERT_EQ(res->status, 201) << res->body;
    session_ = json::parse(res->body)["id"];
  }
  static void TearDownTestSuite() { server_.stop(); }
  static httplib::Client client() { return server_.client(60); }
  static json get(const std::string& path) {
    auto res = client().Get(path);
    EXPECT_TRUE(res);
    EXPECT_EQ(res->status, 200) << path;
    return json::parse(res->body);
  }
  static test::TestServer server_;
  static std::string session_;
};

test::TestServer ViewParameterTable::server_;
std::string ViewParameterTable::session_;

std::set<std::string> table_names() {
  std::set<std::string> names;
  for (const render::ViewParameter& p : render::view_parameters()) names.emplace(p.name);
  return names;
}

// The JSON Schema a parameter's value must have, from the table alone (the side at most kSide).
void expect_schema_of_table(const json& schema, const render::ViewParameter& p, const std::string& where) {
  SCOPED_TRACE(where + " " + std::string(p.name));
  const Range r = render::allowed_range(p, kSide);
  switch (render::parameter_type(p)) {
    case render::ParameterType::integer: EXPECT_EQ(schema["type"], "integer"); break;
    case render::ParameterType::number: EXPECT_EQ(schema["type"], "number"); break;
    case render::ParameterType::enumeration: {
      EXPECT_EQ(schema["type"], "string");
      std::vector<std::string> names;
      for (const std::string_view c : render::choices(p)) names.emplace_back(c);
      EXPECT_EQ(schema["enum"], names);
      break;
    }
    case render::ParameterType::list:
      EXPECT_EQ(schema["type"], "string");
      for (const std::string_view c : render::choices(p))
        EXPECT_NE(schema["pattern"].get<std::string>().find(std::string(c)), std::string::npos) << c;
      break;
  }
  if (r.has_min()) {
    EXPECT_EQ(schema[r.min_open ? "exclusiveMinimum" : "minimum"].get<double>(), r.min);
  } else {
    EXPECT_FALSE(schema.contains("minimum") || schema.contains("exclusiveMinimum"));
  }
  if (r.has_max()) {
    EXPECT_EQ(schema["maximum"].get<double>(), r.max);
  } else {
    EXPECT_FALSE(schema.contains("maximum"));
  }
  const auto fallback = render::default_value(p);
  if (!fallback)
    EXPECT_FALSE(schema.contains("default"));
  else if (std::holds_alternative<double>(*fallback))
    EXPECT_EQ(schema["default"].get<double>(), std::get<double>(*fallback));
  else
    EXPECT_EQ(schema["default"], std::get<std::string>(*fallback));
  if (p.unit.empty())
    EXPECT_FALSE(schema.contains("x-unit"));
  else
    EXPECT_EQ(schema["x-unit"], std::string(p.unit));
}

// A raster frame (PNG, JPEG, the live view) is bounded in pixels as well as in sides, by the server's
// limit: 422 naming width, with the product; a vector figure is not (it holds no pixels). The route
// says both bounds.
TEST_F(ViewParameterTable, ARasterFramesPixelsAreBoundedAndAFiguresAreNot) {
  const std::string frame = "/api/v1/sessions/" + session_ + "/frame";
  for (const char* kind : {".png", ".jpg"}) {
    auto over = client().Get(frame + kind + "?width=1024&height=257");
    ASSERT_TRUE(over);
    EXPECT_EQ(over->status, 422) << kind;
    const json problem = json::parse(over->body);
    EXPECT_EQ(problem["errors"][0]["field"], "width");
    EXPECT_EQ(problem["errors"][0]["value"], "1024");
    EXPECT_EQ(
        problem["errors"][0]["reason"],
        "width × height = 263168 pixels; a frame has at most 262144 (limits.max_image_pixels: the memory "
        "one frame takes)");
    EXPECT_EQ(client().Get(frame + kind + "?width=1024&height=256")->status, 200) << "at the limit";
  }
  EXPECT_EQ(client().Get(frame + ".svg?width=1024&height=1024")->status, 200);
  EXPECT_EQ(get("/api/v1/view-parameters")["max_pixels"]["frame"], kPixels);
}

// GET /api/v1/view-parameters is the table: every row with its type, unit, range, default, choices
// and help; the layers and the recording formats with theirs.
TEST_F(ViewParameterTable, TheRouteAnswersTheTables) {
  const json doc = get("/api/v1/view-parameters");
  const auto& rows = render::view_parameters();
  ASSERT_EQ(doc["parameters"].size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const render::ViewParameter& p = rows[i];
    const json& row = doc["parameters"][i];
    SCOPED_TRACE(std::string(p.name));
    EXPECT_EQ(row["name"], std::string(p.name));
    EXPECT_EQ(row["help"], std::string(p.help));
    const Range r = render::allowed_range(p, kSide);
    EXPECT_EQ(row.contains("min"), r.has_min());
    if (r.has_min()) {
      EXPECT_EQ(row["min"].get<double>(), r.min);
    }
    EXPECT_EQ(row.contains("max"), r.has_max());
    if (r.has_max()) {
      EXPECT_EQ(row["max"].get<double>(), r.max);
    }
    EXPECT_EQ(row.value("exclusive_min", false), r.min_open);
    EXPECT_EQ(row.contains("unit"), !p.unit.empty());
    const auto fallback = render::default_value(p);
    ASSERT_TRUE(row.contains("default"));
    if (!fallback)
      EXPECT_TRUE(row["default"].is_null());
    else if (std::holds_alternative<double>(*fallback))
      EXPECT_EQ(row["default"].get<double>(), std::get<double>(*fallback));
    else
      EXPECT_EQ(row["default"], std::get<std::string>(*fallback));
  }
  const json width = doc["parameters"][0];
  EXPECT_EQ(width["type"], "integer");
  EXPECT_EQ(width["max"], kSide);  // the server's limit
  EXPECT_EQ(width["default"], 640);
  EXPECT_EQ(doc["parameters"][2]["type"], "enum");
  EXPECT_EQ(doc["parameters"][2]["choices"].size(), render::views().size());
  ASSERT_EQ(doc["layers"].size(), std::size(render::kLayerTable));
  for (std::size_t i = 0; i < std::size(render::kLayerTable); ++i) {
    EXPECT_EQ(doc["layers"][i]["name"], std::string(render::kLayerTable[i].name));
    EXPECT_EQ(doc["layers"][i]["default"], render::kLayerTable[i].on_by_default);
  }
  EXPECT_EQ(doc["layers"].back()["name"], "plain");
  EXPECT_EQ(doc["layers"].back()["default"], false);  // plain words are simple mode's, asked for
  ASSERT_EQ(doc["formats"].size(), std::size(record::kFormats));
  for (std::size_t i = 0; i < std::size(record::kFormats); ++i) {
    EXPECT_EQ(doc["formats"][i]["name"], std::string(record::kFormats[i].name));
    EXPECT_EQ(doc["formats"][i]["content_type"], std::string(record::kFormats[i].content_type));
  }
}

// The OpenAPI document: each frame route takes every parameter of the table (and, of the view's
// kind, nothing else), with the table's schema; the recording body has the same fields and schemas.
TEST_F(ViewParameterTable, OpenApiQueryParametersAndRecordingBodyAreTheTable) {
  const json paths = get("/api/v1/openapi.json")["paths"];
  // Not the picture's: the JPEG's quality, the stream's pace and name, its aim, the time (`at`).
  const std::set<std::string> others = {"quality", "fps", "viewer", "aim", "at"};
  for (const auto& [path, method] :
       {std::pair{"/api/v1/sessions/{id}/frame.png", "get"},
        std::pair{"/api/v1/sessions/{id}/frame.jpg", "get"}, std::pair{"/api/v1/sessions/{id}/live", "get"},
        std::pair{"/api/v1/sessions/{id}/live", "patch"}}) {
    std::set<std::string> names;
    for (const json& q : paths[path][method]["parameters"]) {
      if (q["in"] != "query") continue;
      const std::string name = q["name"];
      if (others.contains(name)) continue;
      names.insert(name);
      json schema = q["schema"];
      if (std::string(method) == "patch") {  // absent: unchanged, so no default
        EXPECT_FALSE(schema.contains("default")) << name;
        const auto fallback = render::default_value(render::view_parameter(name));
        if (fallback && std::holds_alternative<double>(*fallback))
          schema["default"] = std::get<double>(*fallback);
        else if (fallback)
          schema["default"] = std::get<std::string>(*fallback);
      }
      expect_schema_of_table(schema, render::view_parameter(name), std::string(method) + " " + path);
      EXPECT_EQ(q["description"], std::string(render::view_parameter(name).help)) << name;
    }
    EXPECT_EQ(names, table_names()) << method << " " << path;
  }
  const json body = paths["/api/v1/sessions/{id}/recordings"]["post"]["requestBody"]["content"]
                         ["application/json"]["schema"];
  std::set<std::string> fields;
  for (const auto& [name, schema] : body["properties"].items()) {
    if (name == "t_start" || name == "t_end" || name == "fps" || name == "speed" || name == "format")
      continue;
    fields.insert(name);
    expect_schema_of_table(schema, render::view_parameter(name), "recording body");
  }
  EXPECT_EQ(fields, table_names());
  std::vector<std::string> formats;
  for (const record::FormatInfo& f : record::kFormats) formats.emplace_back(f.name);
  EXPECT_EQ(body["properties"]["format"]["enum"], formats);
}

// The CLI's render and record options: --NAME for every row (and --camera, the three camera ones at
// once), each with the table's default.
TEST(ViewOptions, TheCliOptionsAreTheTable) {
  CLI::App app;
  cli::ViewArgs args;
  cli::add_view_options(app, args);
  std::set<std::string> names;
  for (const CLI::Option* option : app.get_options()) {
    const std::string name = option->get_name();
    if (name == "--help" || name == "--camera") continue;
    ASSERT_TRUE(name.starts_with("--")) << name;
    names.insert(name.substr(2));
    const render::ViewParameter& p = render::view_parameter(name.substr(2));
    const auto fallback = render::default_value(p);
    const std::string expected = !fallback ? ""
                                 : std::holds_alternative<double>(*fallback)
                                     ? shortest(std::get<double>(*fallback))
                                     : std::get<std::string>(*fallback);
    EXPECT_EQ(option->get_default_str(), expected) << name;
    EXPECT_NE(option->get_description().find(std::string(p.help)), std::string::npos) << name;
  }
  EXPECT_EQ(names, table_names());
  EXPECT_TRUE(app.get_option("--camera"));
}

// One bad value per parameter, refused by the frame query, the recording body and the CLI: each
// names the field and the value, and gives the table's reason (its server-side range at the limit).
TEST_F(ViewParameterTable, EveryReaderRefusesABadValueInTheTablesWords) {
  const std::vector<std::pair<std::string, json>> bad = {
      {"width", 5000}, {"height", 0},       {"view", "cube"}, {"layers", "surface,sparkles"},
      {"scale", 0},    {"yaw", 200},        {"pitch", 2},     {"distance", 0.5},
      {"trail", -1},   {"motion", "orbit"}, {"shown", 8}};
  std::set<std::string> covered;
  for (const auto& [name, value] : bad) {
    SCOPED_TRACE(name);
    covered.insert(name);
    const render::ViewParameter& p = render::view_parameter(name);
    const std::string text = value.is_string() ? value.get<std::string>() : value.dump();
    render::ViewRequest r;
    const std::string reason = render::set_parameter(r, p, render::GivenValue(text), kSide).value_or("");
    ASSERT_FALSE(reason.empty());
    if (name == "layers") {
      EXPECT_NE(reason.find("hud, actions"), std::string::npos) << reason;
    }

    auto frame = client().Get("/api/v1/sessions/" + session_ + "/frame.png?" + name + "=" + text);
    ASSERT_EQ(frame->status, 422) << frame->body;
    const json query_error = json::parse(frame->body)["errors"][0];
    EXPECT_EQ(query_error, json({{"field", name}, {"value", text}, {"reason", reason}}));

    json body{{"t_end", 0.1}, {"format", "png-zip"}, {"width", 64}, {"height", 48}};
    body[name] = value;
    auto recording =
        client().Post("/api/v1/sessions/" + session_ + "/recordings", body.dump(), "application/json");
    ASSERT_EQ(recording->status, 422) << recording->body;
    EXPECT_EQ(json::parse(recording->body)["errors"][0], query_error);

    // The CLI knows the renderer's side limit only.
    CLI::App app;
    cli::ViewArgs args;
    cli::add_view_options(app, args);
    std::vector<std::string> argv{text, "--" + name};  // CLI11 takes them last first
    app.parse(argv);
    const std::string cli_reason = render::set_parameter(r, p, render::GivenValue(text)).value_or("");
    try {
      cli::view_request(args);
      ADD_FAILURE() << "the CLI took --" << name << " " << text;
    } catch (const cli::BadViewOption& e) {
      EXPECT_EQ(std::string(e.what()), "--" + name + ": " + cli_reason + " (got '" + text + "')");
    }
  }
  EXPECT_EQ(covered, table_names());
}

// A body value of the wrong JSON type is refused with the table's reason too.
TEST_F(ViewParameterTable, TheRecordingBodyRefusesAValueOfTheWrongType) {
  for (const auto& [name, value] : {std::pair{"width", json("640")}, std::pair{"layers", json(3)}}) {
    json body{{"t_end", 0.1}, {"format", "png-zip"}, {"width", 64}, {"height", 48}};
    body[name] = value;
    auto res = client().Post("/api/v1/sessions/" + session_ + "/recordings", body.dump(), "application/json");
    ASSERT_EQ(res->status, 422) << res->body;
    const json error = json::parse(res->body)["errors"][0];
    EXPECT_EQ(error["field"], name);
    EXPECT_EQ(error["reason"], render::expectation(render::view_parameter(name), kSide));
  }
}

}  // namespace
}  // namespace spinfold::server
