// The HTTP API in-process on 127.0.0.1 with an ephemeral port and a real HTTP client.
#include "server/api.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>
#include <vector>

// Eigen (through the codec) must come before httplib.h (through bad_requests.h).
// clang-format off
#include "codec/presets.h"
#include "codec/sample_json.h"
#include "codec/sample_table.h"
#include "codec/scene_json.h"
#include "bad_requests.h"
#include "decoded_image.h"
#include "tests/render/figure_tools.h"
// clang-format on
#include "server/http/route_table.h"
#include "server/routes/routes.h"

// After Eigen (through the server's headers): httplib.h brings <resolv.h>'s `_res` macro.
#include <httplib.h>

#include "test_server.h"

namespace spinfold::server {
namespace {

using nlohmann::json;

class Api : public ::testing::Test {
 protected:
  static ServerOptions test_options() {
    ServerOptions options;
    options.port = 0;
    options.threads = 8;
    options.limits.max_sessions = 6;
    options.limits.max_body_bytes = 16 * 1024;
    options.limits.max_steps = 100000;
    // These tests were written for 4 streams; the per-client quotas have their own tests
    // (hardening_test.cpp): here every request comes from 127.0.0.1, so the rate is not limited.
    options.limits.max_streams = 4;
    options.limits.requests_per_second_per_client = 0.0;
    return options;
  }
  static void SetUpTestSuite() { server_.start(test_options()); }
  static void TearDownTestSuite() { server_.stop(); }

  static httplib::Client client() { return server_.client(30); }
  static std::string create(const std::string& body) {
    auto res = client().Post("/api/v1/sessions", body, "application/json");
    EXPECT_TRUE(res);
    EXPECT_EQ(res->status, 201) << res->body;
    return json::parse(res->body)["id"];
  }
  static void remove(const std::string& id) { client().Delete("/api/v1/sessions/" + id); }

  static test::TestServer server_;
};

test::TestServer Api::server_;

TEST_F(Api, HealthScenesAndIntegrators) {
  auto c = client();
  auto health = c.Get("/api/v1/health");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
  EXPECT_EQ(json::parse(health->body)["status"], "ok");
  EXPECT_FALSE(health->get_header_value("X-Spinfold-Version").empty());
  auto scenes = c.Get("/api/v1/scenes");
  ASSERT_TRUE(scenes);
  const json list = json::parse(scenes->body);
  EXPECT_GE(list.size(), 8u);
  // The lesson sequence: each scene's next is the one after it, the last has none, one is the default.
  int defaults = 0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    EXPECT_FALSE(list[i]["chapter"].get<std::string>().empty());
    if (i + 1 < list.size()) {
      EXPECT_EQ(list[i]["next"], list[i + 1]["name"]);
    }
    defaults += list[i]["default"].get<bool>() ? 1 : 0;
  }
  EXPECT_TRUE(list.back()["next"].is_null());
  EXPECT_EQ(defaults, 1);
  auto integrators = c.Get("/api/v1/integrators");
  ASSERT_TRUE(integrators);
  bool has_exact = false;
  for (const auto& e : json::parse(integrators->body)) has_exact = has_exact || e["name"] == "exact";
  EXPECT_TRUE(has_exact);
}

// The OpenAPI document is kept true: every operation it lists is routed (an unknown session id
// gets "Unknown session", never the router's "Not found").
TEST_F(Api, EveryOpenApiOperationIsRouted) {
  auto c = client();
  auto doc = c.Get("/api/v1/openapi.json");
  ASSERT_TRUE(doc);
  const json paths = json::parse(doc->body)["paths"];
  ASSERT_GE(paths.size(), 12u);
  for (const auto& [path_template, operations] : paths.items()) {
    std::string path = path_template;
    if (const auto at = path.find("{id}"); at != std::string::npos) path.replace(at, 4, "0123456789abcdef");
    for (const auto& [method, operation] : operations.items()) {
      httplib::Result res = method == "get"      ? c.Get(path)
                            : method == "delete" ? c.Delete(path)
                            : method == "patch"  ? c.Patch(path, "{}", "application/json")
                                                 : c.Post(path, "{}", "application/json");
      ASSERT_TRUE(res) << method << " " << path;
      if (res->status == 201) c.Delete(res->get_header_value("Location"));  // {} is a valid scene
      if (res->status >= 400) {
        EXPECT_NE(json::parse(res->body)["title"], "Not found") << method << " " << path;
      }
    }
  }
  auto schema = c.Get("/api/v1/schema");
  ASSERT_TRUE(schema);
  EXPECT_EQ(json::parse(schema->body)["title"], "Spinfold scene");
}

// The web UI's files come from a glob of web/ (cmake/embed_web.cmake): every page file on disk is
// served as it is and listed in the OpenAPI document with its own summary, and every module a
// module imports is served, so a new module needs no edit anywhere else.
TEST_F(Api, EveryFileOfWebIsServedAndListed) {
  auto c = client();
  const json paths = json::parse(c.Get("/api/v1/openapi.json")->body)["paths"];
  const std::filesystem::path web = SPINFOLD_WEB_DIR;
  std::set<std::string> served, imported;
  for (const auto& entry : std::filesystem::directory_iterator(web)) {
    const std::string name = entry.path().filename().string();
    const std::string ext = entry.path().extension().string();
    const bool page =
        name == "index.html" || ((ext == ".js" || ext == ".css") && !name.ends_with(".config.js"));
    if (!page) continue;
    const std::string url = name == "index.html" ? "/" : "/" + name;
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto res = c.Get(url);
    ASSERT_TRUE(res) << url;
    EXPECT_EQ(res->status, 200) << url;
    EXPECT_EQ(res->body, text) << url;
    ASSERT_TRUE(paths.contains(url)) << url;
    EXPECT_FALSE(paths[url]["get"]["summary"].get<std::string>().empty()) << url;
    served.insert(url);
    // import … from "./module.js"
    for (std::size_t at = text.find("from \"./"); at != std::string::npos;
         at = text.find("from \"./", at + 1)) {
      const std::size_t from = at + 8;  // after `from "./`
      imported.insert(
          std::string(1, '/').append(std::string_view(text).substr(from, text.find('"', from) - from)));
    }
  }
  EXPECT_GE(served.size(), 20u);  // index.html, the modules, the style sheets
  EXPECT_TRUE(served.contains("/main.js"));
  for (const std::string& url : imported)
    EXPECT_TRUE(served.contains(url)) << url << " is imported but not served";
  EXPECT_EQ(c.Get("/eslint.config.js")->status, 404);  // tooling is not served
}

// Becoming incompressible mid-run restarts: the constraint holds the start's area, so continuing
// would snap the body's shape (det L 0.86 → 0.91 in one step, as it did).
TEST_F(Api, BecomingIncompressibleRestartsTheRunInsteadOfSnappingTheShape) {
  auto c = client();
  const std::string id = create(R"({"preset": "breathing_ellipse_sphere"})");
  const std::string session = "/api/v1/sessions/" + id;
  auto moved = c.Post(session + "/advance", R"({"until": 1.3})", "application/json");
  ASSERT_TRUE(moved);
  const json state = json::parse(moved->body)["state"];
  const double start_area = state["det_L"].get<double>();
  auto patched =
      c.Patch(session, R"({"body": {"model": "incompressible"}, "integrator": {"name": "split6"}})",
              "application/merge-patch+json");
  ASSERT_TRUE(patched);
  ASSERT_EQ(patched->status, 200) << patched->body;
  const json after = json::parse(patched->body);
  EXPECT_EQ(after["change"]["kind"], "restarted");
  EXPECT_NE(after["change"]["reason"].get<std::string>().find("incompressible"), std::string::npos);
  EXPECT_EQ(after["state"]["t"], 0.0);
  const double area = after["state"]["det_L"].get<double>();
  EXPECT_GT(std::abs(area - start_area), 1e-3);  // the start's area, not the one at t = 1.3
  auto stepped = c.Post(session + "/advance", R"({"until": 0.5})", "application/json");
  ASSERT_TRUE(stepped);
  EXPECT_NEAR(json::parse(stepped->body)["state"]["det_L"].get<double>(), area, 1e-14);
  remove(id);
}

// The views the UI offers come from the server's one table; each H² view draws a pseudosphere.
TEST_F(Api, ViewsListTheSurfacesEachShowsAndEachH2ViewDraws) {
  auto c = client();
  auto res = c.Get("/api/v1/views");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200);
  std::vector<std::string> h2;
  for (const auto& v : json::parse(res->body)) {
    EXPECT_FALSE(v["title"].get<std::string>().empty());
    for (const auto& surface : v["surfaces"])
      if (surface == "pseudosphere") h2.push_back(v["name"]);
  }
  EXPECT_EQ(h2, (std::vector<std::string>{"disk", "hyperboloid", "klein", "halfplane", "tractricoid",
                                          "conformal"}));
  const std::string id = create(R"({"preset": "spinning_rigid_pseudosphere"})");
  std::set<std::string> bodies;
  for (const std::string& view : h2) {
    auto frame = c.Get("/api/v1/sessions/" + id + "/frame.png?width=160&height=120&view=" + view);
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->status, 200) << view << ": " << frame->body;
    EXPECT_EQ(frame->get_header_value("Content-Type"), "image/png");
    bodies.insert(frame->body);
  }
  EXPECT_EQ(bodies.size(), h2.size());  // five different pictures
  remove(id);
}

// The actions layer writes the action variables into the overlay: a taller text box, other bytes.
TEST_F(Api, TheActionsLayerAddsToTheOverlay) {
  auto c = client();
  const std::string id = create(R"({"preset": "action_variables_sphere"})");
  const std::string frame = "/api/v1/sessions/" + id + "/frame.png?width=320&height=240&layers=hud";
  auto plain = c.Get(frame);
  auto with = c.Get(frame + ",actions");
  ASSERT_TRUE(plain && with);
  EXPECT_EQ(with->status, 200);
  EXPECT_NE(plain->body, with->body);
  auto state = c.Get("/api/v1/sessions/" + id);
  ASSERT_TRUE(state);
  EXPECT_TRUE(json::parse(state->body)["state"]["actions"]["J_r"].is_number()) << state->body;
  remove(id);
}

// A frame's overlay is sized for the width it is shown at (`shown`: the page's paced picture, a
// phone's of three device pixels to one): smaller text when shown larger, the compact overlay
// (no legend) when shown small; as drawn when `shown` is the width. The live stream and the frames
// once dropped the parameter, so the page's paced and phone pictures kept the drawn size's text.
TEST_F(Api, TheOverlayFollowsTheWidthShown) {
  auto c = client();
  const std::string id = create(R"({"preset": "spin_vs_geodesic_sphere"})");
  const std::string frame = "/api/v1/sessions/" + id + "/frame.png?width=533&height=400";
  auto drawn = c.Get(frame);
  auto same = c.Get(frame + "&shown=533");
  auto paced = c.Get(frame + "&shown=1066");
  auto phone = c.Get(frame + "&shown=266");
  ASSERT_TRUE(drawn && same && paced && phone);
  for (const auto* r : {&drawn, &same, &paced, &phone}) EXPECT_EQ((*r)->status, 200) << (*r)->body;
  EXPECT_EQ(drawn->body, same->body);
  EXPECT_NE(drawn->body, paced->body);
  EXPECT_NE(drawn->body, phone->body);
  EXPECT_NE(paced->body, phone->body);
  EXPECT_NE(drawn->get_header_value("ETag"), paced->get_header_value("ETag"));
  EXPECT_NE(paced->get_header_value("ETag"), phone->get_header_value("ETag"));
  remove(id);
}

// The session names its surface resolved (server/context.cpp): the kind and radius a given K
// implies, the plane below the engine's flat threshold, and K in the kind-and-radius form; the UI
// reads these instead of re-deriving them with a copied constant.
TEST_F(Api, TheSessionNamesItsSurfaceResolved) {
  auto c = client();
  const auto surface_of = [&](const std::string& surface) {
    const std::string id = create(R"({"surface": )" + surface + R"(, "body": {"model": "rigid"}})");
    auto got = c.Get("/api/v1/sessions/" + id);
    remove(id);
    EXPECT_TRUE(got);
    const json body = json::parse(got->body);
    EXPECT_EQ(body["current"]["surface"], json::parse(surface));  // the scene as given, unchanged
    return body["surface"];
  };
  const json h2 = surface_of(R"({"curvature": -0.25})");
  EXPECT_EQ(h2["kind"], "pseudosphere");
  EXPECT_DOUBLE_EQ(h2["radius"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(h2["curvature"].get<double>(), -0.25);
  const json flat = surface_of(R"({"curvature": 1e-30})");  // below kFlatCurvature
  EXPECT_EQ(flat["kind"], "plane");
  EXPECT_EQ(flat["curvature"].get<double>(), 0.0);
  const json sphere = surface_of(R"({"kind": "sphere", "radius": 0.5})");
  EXPECT_EQ(sphere["kind"], "sphere");
  EXPECT_DOUBLE_EQ(sphere["curvature"].get<double>(), 4.0);
}

// A session on a surface whose curvature varies: it runs, patches and replays like any other; its
// state says u and K; its trajectory is the run's; its frame is the revolution view's, and a view of
// constant curvature is refused naming the one that draws it.
TEST_F(Api, TorusSessionRunsAndIsDrawnInTheRevolutionView) {
  auto c = client();
  auto created = c.Post("/api/v1/sessions",
                        R"({"surface": {"kind": "torus", "tube_radius": 0.6, "center_radius": 2},
                            "potential": {"height": {"kind": "gravity", "g": 0.5}},
                            "friction": {"translational": 0.05},
                            "initial": {"u": 0.3, "speed": 1, "heading": 1.2, "spin": 0.4, "mu": 0.8}})",
                        "application/json");
  ASSERT_TRUE(created);
  ASSERT_EQ(created->status, 201) << created->body;
  const std::string id = json::parse(created->body)["id"];
  auto advanced = c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 2})", "application/json");
  ASSERT_TRUE(advanced);
  ASSERT_EQ(advanced->status, 200) << advanced->body;
  const json state = json::parse(advanced->body)["state"];
  EXPECT_EQ(state["status"], "ok");
  EXPECT_TRUE(state.contains("u") && state.contains("K") && !state.contains("r")) << state.dump();
  EXPECT_LT(state["energy_error"].get<double>(), 0.0);  // friction: the energy fell
  auto patched =
      c.Patch("/api/v1/sessions/" + id, R"({"friction": {"translational": 0.2}})", "application/json");
  ASSERT_TRUE(patched);
  EXPECT_EQ(patched->status, 200) << patched->body;
  EXPECT_EQ(json::parse(patched->body)["change"]["kind"], "continued") << patched->body;
  auto wrong = c.Patch("/api/v1/sessions/" + id, R"({"initial": {"r": 1}})", "application/merge-patch+json");
  ASSERT_TRUE(wrong);
  EXPECT_EQ(wrong->status, 422);
  EXPECT_NE(wrong->body.find("initial.r"), std::string::npos) << wrong->body;
  auto trajectory = c.Get("/api/v1/sessions/" + id + "/trajectory?format=csv&fields=t,u,phi,K");
  ASSERT_TRUE(trajectory);
  EXPECT_EQ(trajectory->status, 200) << trajectory->body;
  EXPECT_NE(trajectory->body.find("t,u,phi,K"), std::string::npos) << trajectory->body.substr(0, 300);
  auto frame = c.Get("/api/v1/sessions/" + id + "/frame.png?layers=surface,grid,body,trail,curvature");
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->status, 200) << frame->body;
  EXPECT_EQ(frame->get_header_value("Content-Type"), "image/png");
  auto sphere_view = c.Get("/api/v1/sessions/" + id + "/frame.png?view=sphere");
  ASSERT_TRUE(sphere_view);
  EXPECT_EQ(sphere_view->status, 422);
  EXPECT_NE(sphere_view->body.find("the torus is shown in these views: revolution, chart"), std::string::npos)
      << sphere_view->body;
  auto deleted = c.Delete("/api/v1/sessions/" + id);
  ASSERT_TRUE(deleted);
  EXPECT_EQ(deleted->status, 204);
}

// A formula surface runs, samples without a chart and changes its parameters mid-run; a formula the
// language refuses is a 422 naming its position; its pictures are refused, saying why, never a 5xx.
TEST_F(Api, AFormulaSurfaceSessionRunsAndItsRefusalsNameTheField) {
  auto c = client();
  auto created = c.Post("/api/v1/sessions",
                        R"j({"surface": {"kind": "implicit", "F": "x^2/a^2 + y^2/b^2 + z^2/c^2 - 1",
                             "parameters": {"a": 2, "b": 1.5, "c": 1}},
                            "initial": {"X": [1.0, 0.8, 0.5], "speed": 0.5, "heading": 0.3, "spin": 0.2}})j",
                        "application/json");
  ASSERT_TRUE(created);
  ASSERT_EQ(created->status, 201) << created->body;
  const std::string id = json::parse(created->body)["id"];
  auto advanced = c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 2})", "application/json");
  ASSERT_TRUE(advanced);
  ASSERT_EQ(advanced->status, 200) << advanced->body;
  const json state = json::parse(advanced->body)["state"];
  EXPECT_EQ(state["status"], "ok");
  EXPECT_TRUE(state.contains("n") && state.contains("K") && state.contains("e1") && !state.contains("u") &&
              !state.contains("r"))
      << state.dump();
  EXPECT_LT(state["constraint_drift"].get<double>(), 1e-14);
  // A new parameter continues from the body's place, brought onto the new surface.
  auto patched =
      c.Patch("/api/v1/sessions/" + id, R"({"surface": {"parameters": {"c": 1.2}}})", "application/json");
  ASSERT_TRUE(patched);
  EXPECT_EQ(patched->status, 200) << patched->body;
  auto after = c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 3})", "application/json");
  ASSERT_TRUE(after);
  ASSERT_EQ(after->status, 200) << after->body;
  const json moved = json::parse(after->body)["state"];
  EXPECT_EQ(moved["status"], "ok") << moved.dump();
  EXPECT_LT(moved["constraint_drift"].get<double>(), 1e-14) << moved.dump();
  auto wrong =
      c.Patch("/api/v1/sessions/" + id, R"j({"surface": {"F": "x^2 + max(y, z) - 1"}})j", "application/json");
  ASSERT_TRUE(wrong);
  EXPECT_EQ(wrong->status, 422);
  EXPECT_NE(wrong->body.find("surface.F"), std::string::npos) << wrong->body;
  EXPECT_NE(wrong->body.find("at position 6"), std::string::npos) << wrong->body;
  auto trajectory = c.Get("/api/v1/sessions/" + id +
                          "/trajectory?format=csv&fields=t,X.0,X.1,X.2,n.0,n.1,n.2,K,constraint_drift");
  ASSERT_TRUE(trajectory);
  EXPECT_EQ(trajectory->status, 200) << trajectory->body;
  EXPECT_NE(trajectory->body.find("t,X_0,X_1,X_2,n_0,n_1,n_2,K,constraint_drift"), std::string::npos)
      << trajectory->body.substr(0, 300);
  // Its picture: the formula view by default; a view of another surface is refused naming the one.
  auto frame = c.Get("/api/v1/sessions/" + id + "/frame.png?width=320&height=240");
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->status, 200) << frame->body;
  EXPECT_EQ(frame->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(frame->body.substr(1, 3), "PNG");
  // Drag handles without a chart: the place is X, and a drop beside the body sets initial.X, which
  // a PATCH takes as it is (the page sends the drop's `initial`).
  auto handles = c.Get("/api/v1/sessions/" + id + "/handles?width=320&height=240");
  ASSERT_TRUE(handles);
  ASSERT_EQ(handles->status, 200) << handles->body;
  const json placed = json::parse(handles->body);
  ASSERT_TRUE(placed["place"]["X"].is_array()) << handles->body;
  EXPECT_EQ(placed["place"]["X"].size(), 3u);
  ASSERT_TRUE(placed["body"].is_object()) << handles->body;
  const double bx = placed["body"]["x"], by = placed["body"]["y"];
  auto drop = c.Get("/api/v1/sessions/" + id + "/drop?width=320&height=240&handle=body&x=" +
                    std::to_string(bx - 2.0) + "&y=" + std::to_string(by + 1.0));
  ASSERT_TRUE(drop);
  ASSERT_EQ(drop->status, 200) << drop->body;
  const json dropped = json::parse(drop->body);
  ASSERT_TRUE(dropped["initial"]["X"].is_array()) << drop->body;
  EXPECT_NE(dropped["text"].get<std::string>().find("X.0 = "), std::string::npos) << drop->body;
  EXPECT_EQ(dropped["plain"], "start here") << drop->body;  // simple mode's words, no coordinates
  auto moved_to =
      c.Patch("/api/v1/sessions/" + id, json{{"initial", dropped["initial"]}}.dump(), "application/json");
  ASSERT_TRUE(moved_to);
  ASSERT_EQ(moved_to->status, 200) << moved_to->body;
  const json started = json::parse(moved_to->body);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(started["state"]["X"][k].get<double>(), dropped["initial"]["X"][k].get<double>(), 1e-12) << k;
  auto other = c.Get("/api/v1/sessions/" + id + "/frame.png?view=revolution");
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 422) << other->body;
  EXPECT_NE(other->body.find("shown in these views: formula"), std::string::npos) << other->body;
  auto deleted = c.Delete("/api/v1/sessions/" + id);
  ASSERT_TRUE(deleted);
  EXPECT_EQ(deleted->status, 204);
}

TEST_F(Api, SessionLifecycle) {
  auto c = client();
  auto created = c.Post("/api/v1/sessions", R"({"preset": "separable_radial_abc"})", "application/json");
  ASSERT_TRUE(created);
  ASSERT_EQ(created->status, 201);
  const json body = json::parse(created->body);
  const std::string id = body["id"];
  EXPECT_EQ(created->get_header_value("Location"), "/api/v1/sessions/" + id);
  EXPECT_NE(created->get_header_value("X-Spinfold-Provenance").find("integrator=exact"), std::string::npos);
  EXPECT_EQ(body["state"]["t"], 0.0);
  // Where the numbers come from: the build, the scene's hash and the integrator (codec/provenance.h).
  EXPECT_EQ(body["provenance"]["software"], "spinfold");
  EXPECT_FALSE(body["provenance"]["commit"].get<std::string>().empty());
  EXPECT_EQ(body["provenance"]["scene_hash"].get<std::string>().size(), 16u);
  EXPECT_NE(created->get_header_value("X-Spinfold-Provenance").find("scene_hash="), std::string::npos);

  auto advanced = c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 2})", "application/json");
  ASSERT_TRUE(advanced);
  ASSERT_EQ(advanced->status, 200) << advanced->body;
  const json state = json::parse(advanced->body)["state"];
  EXPECT_NEAR(state["r"].get<double>(), 1.650073264590784, 1e-12);  // physics.md W5

  auto got = c.Get("/api/v1/sessions/" + id);
  ASSERT_TRUE(got);
  EXPECT_EQ(json::parse(got->body)["state"], state);

  auto steps = c.Post("/api/v1/sessions/" + id + "/advance", R"({"steps": 10})", "application/json");
  ASSERT_TRUE(steps);
  EXPECT_NEAR(json::parse(steps->body)["state"]["t"].get<double>(), 2.1, 1e-12);  // 10 × dt 0.01
  // A step count that is not a whole number >= 1 is refused in number_rule's words; t is unchanged.
  for (const char* bad : {R"({"steps": 0})", R"({"steps": 2.5})"}) {
    auto refused = c.Post("/api/v1/sessions/" + id + "/advance", bad, "application/json");
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 422) << bad;
    EXPECT_NE(refused->body.find("must be a whole number >= 1"), std::string::npos) << refused->body;
  }
  EXPECT_NEAR(json::parse(c.Get("/api/v1/sessions/" + id)->body)["state"]["t"].get<double>(), 2.1, 1e-12);

  auto csv = c.Get("/api/v1/sessions/" + id + "/trajectory?format=csv");
  ASSERT_TRUE(csv);
  EXPECT_EQ(csv->get_header_value("Content-Type"), "text/csv");
  // The header, two comment lines, and samples at 0, 0.5, …, 2 and the session's 2.1.
  EXPECT_EQ(std::count(csv->body.begin(), csv->body.end(), '\n'), 9) << csv->body;
  EXPECT_TRUE(csv->body.starts_with("t,r,phi,")) << csv->body.substr(0, 100);
  EXPECT_NE(csv->body.find("\n# spinfold trajectory "), std::string::npos) << csv->body.substr(0, 300);
  auto trajectory = c.Get("/api/v1/sessions/" + id + "/trajectory");
  ASSERT_TRUE(trajectory);
  const json samples = json::parse(trajectory->body);
  ASSERT_EQ(samples.size(), 6u);
  EXPECT_EQ(samples[4]["t"], 2.0);
  EXPECT_EQ(samples[5]["X"], json::parse(steps->body)["state"]["X"]);  // the session's state, to the bit

  auto reset = c.Post("/api/v1/sessions/" + id + "/reset", "{}", "application/json");
  ASSERT_TRUE(reset);
  EXPECT_EQ(json::parse(reset->body)["state"]["t"], 0.0);

  auto deleted = c.Delete("/api/v1/sessions/" + id);
  ASSERT_TRUE(deleted);
  EXPECT_EQ(deleted->status, 204);
  EXPECT_EQ(c.Get("/api/v1/sessions/" + id)->status, 404);
}

// An adaptive method on a stiff scene may need any number of steps: one request does at most
// max_steps attempts (100,000 here), keeps the progress and says so; the next one continues.
// The trajectory is replayed from the timeline: the same rows however the session was advanced,
// and those of the engine's own sampled run (what `spinfold simulate --every` prints).
TEST_F(Api, TrajectoryRowsDoNotDependOnHowTheSessionWasAdvanced) {
  httplib::Client c = client();
  const auto create = [&] {
    auto created =
        c.Post("/api/v1/sessions", R"({"preset": "spinning_rigid_pseudosphere"})", "application/json");
    EXPECT_EQ(created->status, 201);
    return json::parse(created->body)["id"].get<std::string>();
  };
  const std::string a = create(), b = create();
  for (const char* until : {"0.37", "1.1", "1.95", "3"})
    ASSERT_EQ(c.Post("/api/v1/sessions/" + a + "/advance", std::string(R"({"until": )") + until + "}",
                     "application/json")
                  ->status,
              200);
  ASSERT_EQ(c.Post("/api/v1/sessions/" + b + "/advance", R"({"until": 3})", "application/json")->status, 200);
  const std::string query = "/trajectory?format=csv&every=0.25&fields=t,r,phi,X.0,L.1.1,energy_error,events";
  auto ta = c.Get("/api/v1/sessions/" + a + query);
  auto tb = c.Get("/api/v1/sessions/" + b + query);
  ASSERT_EQ(ta->status, 200) << ta->body;
  EXPECT_EQ(ta->body, tb->body);
  // The engine's run of the same scene sampled at k·0.25.
  Simulation run =
      start_simulation(*parse_scene_text(find_preset("spinning_rigid_pseudosphere")->json).scene);
  std::vector<nlohmann::ordered_json> samples = {sample_to_json(run, -1.0)};
  for (int k = 1; k <= 12; ++k) {
    advance_to(run, 0.25 * k);
    samples.push_back(sample_to_json(run, 0.25 * (k - 1)));
  }
  const SampleTable table = make_sample_table("t,r,phi,X.0,L.1.1,energy_error,events", samples.front());
  std::string rows;
  for (const auto& sample : samples) rows += table.csv_row(sample);
  EXPECT_TRUE(ta->body.starts_with(table.csv_header())) << ta->body;
  EXPECT_TRUE(ta->body.ends_with(rows)) << ta->body;
  // Too many samples: 422 naming `every`; an unknown field: 400 naming `fields`.
  auto many = c.Get("/api/v1/sessions/" + a + "/trajectory?every=1e-5");
  EXPECT_EQ(many->status, 422);
  EXPECT_NE(many->body.find("\"every\""), std::string::npos) << many->body;
  // A group names its members, as `simulate --fields` does: X is X.0, X.1, X.2; L.1 is L.1.0, L.1.1.
  auto grouped = c.Get("/api/v1/sessions/" + a + "/trajectory?fields=t,X,L.1");
  auto listed = c.Get("/api/v1/sessions/" + a + "/trajectory?fields=t,X.0,X.1,X.2,L.1.0,L.1.1");
  ASSERT_TRUE(grouped && listed);
  EXPECT_EQ(grouped->status, 200) << grouped->body;
  EXPECT_EQ(grouped->body, listed->body);
  EXPECT_NE(grouped->body.find(R"({"t":0.0,"X.0":)"), std::string::npos) << grouped->body;
  EXPECT_NE(grouped->body.find(R"("X.2":)"), std::string::npos) << grouped->body;
  EXPECT_NE(grouped->body.find(R"("L.1.1":)"), std::string::npos) << grouped->body;
  auto unknown = c.Get("/api/v1/sessions/" + a + "/trajectory?fields=t,rr");
  EXPECT_EQ(unknown->status / 100, 4);
  EXPECT_NE(unknown->body.find("fields"), std::string::npos) << unknown->body;
  remove(a);
  remove(b);
}

TEST_F(Api, AdvanceStopsAtTheStepLimitAndKeepsTheProgress) {
  auto c = client();
  c.set_read_timeout(180, 0);  // 10⁵ stiff steps a request: seconds under the sanitizers on 2 busy cores
  const std::string id = create(R"({"potential": {"deformation": {"kind": "abc", "C": 1e8}},
      "initial": {"lambda": 1.3, "mu": 0.7}, "integrator": {"name": "dop853", "tolerance": 1e-14}})");
  auto first = c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 1000})", "application/json");
  ASSERT_TRUE(first);
  ASSERT_EQ(first->status, 200) << first->body;
  const json a = json::parse(first->body);
  EXPECT_EQ(a["advance"]["complete"], false);
  EXPECT_EQ(a["advance"]["until"], 1000.0);
  EXPECT_NE(a["advance"]["reason"].get<std::string>().find("advance again"), std::string::npos);
  EXPECT_EQ(a["state"]["status"], "ok");
  const double t1 = a["state"]["t"];
  EXPECT_GT(t1, 0.0);
  EXPECT_LT(t1, 1000.0);
  auto second = c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 1000})", "application/json");
  ASSERT_TRUE(second);
  const double t2 = json::parse(second->body)["state"]["t"];
  EXPECT_GT(t2, t1);
  auto short_one =
      c.Post("/api/v1/sessions/" + id + "/advance", json{{"until", t2 + 1e-3}}.dump(), "application/json");
  ASSERT_TRUE(short_one);
  const json b = json::parse(short_one->body);
  EXPECT_EQ(b["advance"]["complete"], true);
  EXPECT_FALSE(b["advance"].contains("reason"));
  EXPECT_EQ(b["state"]["t"], t2 + 1e-3);
  remove(id);
}

// The work of one advance request is bounded in seconds as well as in attempts (a formula
// surface's step costs several times a chart's): past its seconds the answer says so, keeps the
// progress, and continuing gives the bits of one uncut advance.
TEST(ApiLimits, AdvanceStopsAfterItsSecondsOfWorkAndKeepsTheProgress) {
  ServerOptions options;
  options.port = 0;
  options.threads = 2;
  options.limits.max_steps = 1'000'000'000;
  options.limits.max_advance_seconds = 0.05;
  options.limits.requests_per_second_per_client = 0.0;
  test::TestServer server;
  server.start(options);
  auto c = server.client(180);
  const std::string scene = R"({"potential": {"deformation": {"kind": "abc", "C": 1e8}},
      "initial": {"lambda": 1.3, "mu": 0.7}, "integrator": {"name": "dop853", "tolerance": 1e-14}})";
  auto created = c.Post("/api/v1/sessions", scene, "application/json");
  ASSERT_TRUE(created);
  ASSERT_EQ(created->status, 201) << created->body;
  const std::string id = json::parse(created->body)["id"];
  const std::string advance = "/api/v1/sessions/" + id + "/advance";
  auto first = c.Post(advance, R"({"until": 1000})", "application/json");
  ASSERT_TRUE(first);
  ASSERT_EQ(first->status, 200) << first->body;
  const json a = json::parse(first->body);
  EXPECT_EQ(a["advance"]["complete"], false);
  const std::string reason = a["advance"]["reason"];
  EXPECT_NE(reason.find("0.05 s of work, the limit per request"), std::string::npos) << reason;
  EXPECT_NE(reason.find("advance again"), std::string::npos) << reason;
  const double t1 = a["state"]["t"];
  ASSERT_GT(t1, 0.0);
  ASSERT_LT(t1, 1000.0);
  auto second = c.Post(advance, R"({"until": 1000})", "application/json");
  ASSERT_TRUE(second);
  const double t2 = json::parse(second->body)["state"]["t"];
  EXPECT_GT(t2, t1);
  auto last = c.Post(advance, json{{"until", t2 + 1e-3}}.dump(), "application/json");
  ASSERT_TRUE(last);
  const json b = json::parse(last->body);
  EXPECT_EQ(b["advance"]["complete"], true);
  // The same scene advanced in one go to the same time, here.
  Simulation run = start_simulation(*parse_scene_text(scene).scene);
  ASSERT_TRUE(advance_to(run, t2 + 1e-3));
  const nlohmann::ordered_json uncut = sample_to_json(run, run.state.t);
  for (const auto& [key, value] : uncut.items()) EXPECT_EQ(b["state"][key], json::parse(value.dump())) << key;
  server.stop();
}

TEST_F(Api, PatchContinuesFromTheCurrentStateUnderNewParameters) {
  const std::string id = create(R"({"preset": "breathing_ellipse_sphere"})");
  auto c = client();
  const json before = json::parse(
      c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 1.5})", "application/json")->body)["state"];
  auto patched = c.Patch("/api/v1/sessions/" + id,
                         R"({"body": {"mass": 3}, "integrator": {"name": "dop853"}})", "application/json");
  ASSERT_TRUE(patched);
  ASSERT_EQ(patched->status, 200) << patched->body;
  const json after = json::parse(patched->body);
  EXPECT_EQ(after["current"]["body"]["mass"], 3.0);  // in force from now
  EXPECT_EQ(after["scene"]["body"]["mass"], 1.0);    // the scene at t = 0 is what it was
  EXPECT_EQ(after["timeline"],
            json::parse(R"([{"t": 1.5, "patch": {"body": {"mass": 3}, "integrator": {"name": "dop853"}}}])"));
  EXPECT_EQ(after["change"]["kind"], "continued");
  EXPECT_EQ(after["change"]["reason"], "new parameters from t = 1.5 on, continuing from the current state");
  EXPECT_EQ(after["state"]["t"], 1.5);             // the clock goes on
  EXPECT_EQ(after["state"]["energy_error"], 0.0);  // measured from the change
  EXPECT_NEAR(after["state"]["r"].get<double>(), before["r"].get<double>(), 1e-12);
  EXPECT_NEAR(after["state"]["lambda"].get<double>(), before["lambda"].get<double>(), 1e-12);
  EXPECT_NEAR(after["state"]["phi_dot"].get<double>(), before["phi_dot"].get<double>(), 1e-12);
  EXPECT_NE(patched->get_header_value("X-Spinfold-Provenance").find("integrator=dop853"), std::string::npos);
  // A new start restarts the run at t = 0 with the parameters in force and that start.
  auto set = c.Patch("/api/v1/sessions/" + id, R"({"initial": {"r": 0.7, "lambda": 1.1, "mu": 0.9}})",
                     "application/json");
  ASSERT_TRUE(set);
  const json restarted = json::parse(set->body);
  EXPECT_EQ(restarted["change"]["kind"], "restarted");
  EXPECT_NE(restarted["change"]["reason"].get<std::string>().find("initial"), std::string::npos);
  EXPECT_EQ(restarted["state"]["t"], 0.0);
  EXPECT_NEAR(restarted["state"]["r"].get<double>(), 0.7, 1e-15);
  EXPECT_EQ(restarted["scene"]["body"]["mass"], 3.0);
  EXPECT_EQ(restarted["timeline"], json::array());
  auto moved = c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 2.5})", "application/json");
  EXPECT_EQ(json::parse(moved->body)["state"]["t"], 2.5);
  // Reset goes back to t = 0 with the parameters in force.
  auto reset = c.Post("/api/v1/sessions/" + id + "/reset", "{}", "application/json");
  ASSERT_TRUE(reset);
  const json back = json::parse(reset->body);
  EXPECT_EQ(back["state"]["t"], 0.0);
  EXPECT_NEAR(back["state"]["r"].get<double>(), 0.7, 1e-15);
  EXPECT_EQ(back["scene"]["body"]["mass"], 3.0);
  remove(id);
}

// RK4 far beyond its stability: the run stops as diverged, says why in a sentence, and keeps the
// last good state (the one before the request that blew up).
TEST_F(Api, DivergedRunStopsWithItsReason) {
  const std::string id = create(R"({"surface": {"kind": "plane", "radius": 0.001},
      "initial": {"r": 0, "phi": -3.568627450980415, "alpha": 0.5, "beta": 1, "alpha_dot": 1, "beta_dot": 1,
                  "lambda_dot": 1, "mu_dot": 1},
      "integrator": {"name": "rk4", "dt": 1.5707963267948966}})");
  auto c = client();
  json state;
  for (int k = 1; k <= 10; ++k) {
    auto res =
        c.Post("/api/v1/sessions/" + id + "/advance", json{{"until", 0.5 * k}}.dump(), "application/json");
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200) << res->body;
    state = json::parse(res->body)["state"];
    if (state["status"] != "ok") break;
  }
  EXPECT_EQ(state["status"], "diverged");
  // The run's own steps are dt = π/2 long; the server samples the trail every 0.01, so the last
  // state seen good is the trail sample at 3.16, in the cut step from 2 dt where the blow-up shows.
  EXPECT_EQ(state["t"], 316 * 0.01);
  EXPECT_NE(state["status_detail"].get<std::string>().find("energy error"), std::string::npos);
  EXPECT_LT(std::abs(state["energy_error"].get<double>()), 1.0);
  remove(id);
}

// A patch that changes nothing (the same values, written differently) leaves the run untouched:
// the same state bits and no timeline entry, where a change would start a new segment at t = 1.5.
TEST_F(Api, PatchThatChangesNothingLeavesTheRunAsItIs) {
  const std::string id = create(R"({"preset": "breathing_ellipse_sphere"})");
  auto c = client();
  const json before = json::parse(
      c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 1.5})", "application/json")->body);
  auto patched = c.Patch("/api/v1/sessions/" + id, R"({"body": {"mass": 1}, "surface": {"kind": "sphere"}})",
                         "application/json");
  ASSERT_TRUE(patched);
  ASSERT_EQ(patched->status, 200) << patched->body;
  const json after = json::parse(patched->body);
  EXPECT_EQ(after["change"]["kind"], "unchanged");
  EXPECT_EQ(after["timeline"], json::array());
  EXPECT_EQ(after["state"], before["state"]);
  EXPECT_EQ(after["scene"], before["scene"]);
  remove(id);
}

TEST_F(Api, PlayAdvancesInRealTimeAndEventsStreamIt) {
  const std::string id = create(R"({"preset": "spinning_rigid_sphere"})");
  auto c = client();
  auto played = c.Post("/api/v1/sessions/" + id + "/play", R"({"rate": 2})", "application/json");
  ASSERT_TRUE(played);
  ASSERT_EQ(played->status, 200) << played->body;
  std::vector<double> times;
  std::string buffer;
  auto stream =
      client().Get("/api/v1/sessions/" + id + "/events?rate=20", [&](const char* data, std::size_t n) {
        buffer.append(data, n);
        for (std::size_t at; (at = buffer.find("\n\n")) != std::string::npos; buffer.erase(0, at + 2)) {
          const std::string event = buffer.substr(0, at);
          if (event.rfind("event: state\ndata: ", 0) == 0)
            times.push_back(json::parse(event.substr(19))["t"]);
        }
        return times.size() < 4;
      });
  ASSERT_GE(times.size(), 4u);
  for (std::size_t i = 1; i < times.size(); ++i) EXPECT_GT(times[i], times[i - 1]);
  auto paused = c.Post("/api/v1/sessions/" + id + "/pause", "", "application/json");
  ASSERT_TRUE(paused);
  const double t1 = json::parse(paused->body)["state"]["t"];
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(json::parse(c.Get("/api/v1/sessions/" + id)->body)["state"]["t"], t1);
  EXPECT_GT(t1, 0.0);
  remove(id);
}

TEST_F(Api, OpenStreamsAreLimited) {
  const std::string id = create(R"({"preset": "spinning_rigid_sphere"})");
  std::atomic<bool> done{false};
  std::atomic<int> connected{0};
  std::vector<std::thread> streams;
  for (int i = 0; i < 4; ++i)
    streams.emplace_back([&] {
      bool counted = false;
      client().Get("/api/v1/sessions/" + id + "/events?rate=20", [&](const char*, std::size_t) {
        if (!counted) counted = true, ++connected;
        return !done.load();
      });
    });
  for (int wait = 0; wait < 200 && connected < 4; ++wait)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_EQ(connected, 4);
  auto over = client().Get("/api/v1/sessions/" + id + "/events");
  ASSERT_TRUE(over);
  EXPECT_EQ(over->status, 429);
  EXPECT_FALSE(over->get_header_value("Retry-After").empty());
  done = true;
  for (auto& t : streams) t.join();
  remove(id);
}

// `at`: the picture of the run at an earlier time (the page's scrubber), replayed from t = 0 through
// the timeline: the same bytes the session's frame had then, across a parameter change; past the
// session's time it is refused naming `at`.
TEST_F(Api, AFrameAtAnEarlierTimeIsTheRunThenToTheByte) {
  const std::string id = create(R"({"preset": "spin_vs_geodesic_sphere"})");
  const std::string session = "/api/v1/sessions/" + id;
  auto c = client();
  const std::string picture = "/frame.png?width=320&height=240";
  ASSERT_EQ(c.Post(session + "/advance", R"({"until": 1.5})", "application/json")->status, 200);
  const auto then = c.Get(session + picture);
  ASSERT_EQ(then->status, 200);
  // A change after t = 1.5 (a change's own time shows the run after it, as a sample there does).
  ASSERT_EQ(c.Post(session + "/advance", R"({"until": 2})", "application/json")->status, 200);
  ASSERT_EQ(c.Patch(session, R"({"body": {"mass": 2}})", "application/merge-patch+json")->status, 200);
  ASSERT_EQ(c.Post(session + "/advance", R"({"until": 3})", "application/json")->status, 200);
  const auto now = c.Get(session + picture);
  const auto at_then = c.Get(session + picture + "&at=1.5");
  ASSERT_EQ(at_then->status, 200) << at_then->body;
  EXPECT_TRUE(at_then->body == then->body);  // (bytes: not printed)
  EXPECT_NE(at_then->get_header_value("ETag"), now->get_header_value("ETag"));
  EXPECT_TRUE(c.Get(session + picture + "&at=3")->body == now->body);
  EXPECT_TRUE(at_then->body != now->body);

  const auto jpeg = c.Get(session + "/frame.jpg?width=320&height=240&at=0.5");
  EXPECT_EQ(jpeg->status, 200);
  EXPECT_EQ(jpeg->get_header_value("Content-Type"), "image/jpeg");
  // Long after: the session's trail has halved its samples (past 8192), the replay's has not yet.
  ASSERT_EQ(c.Post(session + "/advance", R"({"until": 90})", "application/json")->status, 200);
  EXPECT_TRUE(c.Get(session + picture + "&at=1.5")->body == then->body);
  for (const std::string bad : {"90.5", "-1"}) {
    const auto refused = c.Get(session + picture + "&at=" + bad);
    EXPECT_EQ(refused->status, 422) << bad;
    EXPECT_NE(refused->body.find("\"at\""), std::string::npos) << refused->body;
  }
  remove(id);
}

// Direct manipulation (server/routes/drag.cpp): the handles are where the frame paints the body,
// and a drop sent back in the PATCH starts the run where the frame of the same camera then paints
// it (pixels of the server's own PNGs, not the pick's arithmetic).
TEST_F(Api, ADropOnAFrameStartsTheRunWhereTheFramePaintsTheBody) {
  const std::string id = create(R"({"preset": "spinning_rigid_sphere"})");
  const std::string session = "/api/v1/sessions/" + id;
  auto c = client();
  ASSERT_EQ(c.Post(session + "/advance", R"({"until": 1})", "application/json")->status, 200);
  const std::string view = "?width=320&height=240&yaw=0.7&pitch=0.45&distance=3.4&layers=surface,grid,body";
  const auto orange_near = [&](double x, double y) {
    int w = 0, h = 0;
    const auto frame = c.Get(session + "/frame.png" + view);
    const std::vector<std::uint8_t> rgb = png_pixels(frame->body, w, h);
    int orange = 0;
    for (int j = static_cast<int>(y) - 3; j <= static_cast<int>(y) + 3; ++j)
      for (int i = static_cast<int>(x) - 3; i <= static_cast<int>(x) + 3; ++i) {
        const std::uint8_t* p = &rgb[3 * (static_cast<std::size_t>(j) * w + i)];
        orange += p[0] > 200 && p[1] > 100 && p[1] < 190 && p[2] < 130;
      }
    return orange;
  };
  const auto handles = c.Get(session + "/handles" + view);
  ASSERT_EQ(handles->status, 200) << handles->body;
  const json h = json::parse(handles->body);
  const double bx = h["body"]["x"], by = h["body"]["y"];
  EXPECT_GT(orange_near(bx, by), 25) << handles->body;
  EXPECT_EQ(h["t"], 1.0);
  EXPECT_TRUE(h["arrow"].is_object());
  EXPECT_EQ(h["place"]["speed"], 0.5);

  // The body dropped 60 px left and 40 down: sent back as the form would send it.
  char at[64];
  std::snprintf(at, sizeof at, "&x=%.3f&y=%.3f", bx - 60, by + 40);
  const auto drop = c.Get(session + "/drop" + view + at);
  ASSERT_EQ(drop->status, 200) << drop->body;
  const json fields = json::parse(drop->body);
  for (const char* f : {"r", "phi", "speed", "heading", "spin"})
    EXPECT_TRUE(fields["initial"].contains(f)) << f;
  EXPECT_EQ(fields["text"].get<std::string>().rfind("r = ", 0), 0u) << fields["text"];
  EXPECT_EQ(fields["text"].get<std::string>().find("speed"), std::string::npos) << fields["text"];
  const auto patched =
      c.Patch(session, json{{"initial", fields["initial"]}}.dump(), "application/merge-patch+json");
  ASSERT_EQ(patched->status, 200) << patched->body;
  EXPECT_EQ(json::parse(patched->body)["change"]["kind"], "restarted");
  EXPECT_GT(orange_near(bx - 60, by + 40), 25);
  EXPECT_LT(orange_near(bx, by), 5);  // and no longer where it was

  // The arrow: a longer one gives a larger speed, from the body's place now.
  const json h0 = json::parse(c.Get(session + "/handles" + view)->body);
  const double ax = h0["arrow"]["x"], ay = h0["arrow"]["y"], x0 = h0["body"]["x"], y0 = h0["body"]["y"];
  std::snprintf(at, sizeof at, "&x=%.3f&y=%.3f&handle=arrow", x0 + 2 * (ax - x0), y0 + 2 * (ay - y0));
  const auto arrow = c.Get(session + "/drop" + view + at);
  ASSERT_EQ(arrow->status, 200) << arrow->body;
  const json motion = json::parse(arrow->body)["initial"];
  EXPECT_EQ(json::parse(arrow->body)["text"].get<std::string>().rfind("speed = ", 0), 0u) << arrow->body;
  EXPECT_GT(motion["speed"].get<double>(), 1.5 * h0["place"]["speed"].get<double>());
  EXPECT_NEAR(motion["heading"].get<double>(), h0["place"]["heading"].get<double>(), 1e-4);  // %.3f px
  EXPECT_EQ(motion["r"], h0["place"]["r"]);

  // Refusals name the field; none changes the session.
  const std::string version_before = json::parse(c.Get(session)->body)["state"].dump();
  for (const auto& [query, field] :
       std::vector<std::pair<std::string, std::string>>{{"&x=2&y=2", "x"},
                                                        {"&y=5", "x"},
                                                        {"&x=5", "y"},
                                                        {"&x=321&y=5", "x"},
                                                        {"&x=5&y=-1", "y"},
                                                        {"&x=5&y=5&handle=tip", "handle"}}) {
    const auto refused = c.Get(session + "/drop" + view + query);
    EXPECT_EQ(refused->status, 422) << query;
    EXPECT_NE(refused->body.find("\"field\":\"" + field + "\""), std::string::npos) << query << refused->body;
  }
  EXPECT_EQ(json::parse(c.Get(session)->body)["state"].dump(), version_before);
  remove(id);
}

// Issue 48: each of these sessions was accepted and its first revolution frame never answered (the
// render thread looped, taking memory without bound), again after every restart. Now every view's
// frame, the handles and a figure answer at once; the HUD says the body is too far out to draw.
TEST_F(Api, AFrameOfABodyFarOutOnAnUnboundedSurfaceAnswersAtOnce) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  // Their aiming runs ~200x slower: the first scene's revolution frame alone, without a clock.
  const std::vector<const char*> scenes = {
      R"({"surface":{"kind":"bump","height":1,"width":1},"initial":{"u":1e17,"speed":0.5,"heading":0}})"};
  const std::vector<const char*> views = {"revolution"}, routes = {"/frame.png"};
  const double bound = 600.0;
#else
  const std::vector<const char*> scenes = {
      R"({"surface":{"kind":"bump","height":1,"width":1},"initial":{"u":1e17,"speed":0.5,"heading":0}})",
      R"({"surface":{"kind":"bump","height":1,"width":1e-100},"initial":{"u":1,"speed":0.5,"heading":0}})",
      R"({"surface":{"kind":"catenoid","neck_radius":1},"initial":{"u":100,"speed":0.5,"heading":0}})"};
  const std::vector<const char*> views = {"revolution", "chart"},
                                 routes = {"/frame.png", "/handles", "/frame.svg"};
  const double bound = 5.0;  // the six requests take ~0.15 s
#endif
  for (const char* scene : scenes) {
    const std::string session = "/api/v1/sessions/" + create(scene);
    auto c = client();
    c.set_read_timeout(static_cast<time_t>(bound), 0);
    const auto started = std::chrono::steady_clock::now();
    for (const char* view : views) {
      const std::string q = std::string("?view=") + view + "&width=160&height=120";
      for (const std::string route : routes) {
        const auto res = c.Get(session + route + q);
        ASSERT_TRUE(res) << scene << route << q;
        EXPECT_EQ(res->status, 200) << scene << route << q << res->body.substr(0, 200);
      }
    }
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), bound)
        << scene;
    remove(session.substr(session.rfind('/') + 1));
  }
}

// A merge patch of surface.curvature on a spheroid is refused naming curvature, the field it gave
// (it named equatorial_radius and polar_radius), and the session is unchanged.
TEST_F(Api, ACurvaturePatchOnASpheroidIsRefusedNamingCurvature) {
  const std::string id = create(R"({"preset": "opposite_spins_spheroid"})");
  auto c = client();
  const std::string before = c.Get("/api/v1/sessions/" + id)->body;
  const auto res =
      c.Patch("/api/v1/sessions/" + id, R"({"surface": {"curvature": 1, "kind": null, "radius": null}})",
              "application/merge-patch+json");
  ASSERT_EQ(res->status, 422) << res->body;
  const json problem = json::parse(res->body);
  ASSERT_EQ(problem["errors"].size(), 1u) << res->body;
  EXPECT_EQ(problem["errors"][0]["field"], "surface.curvature") << res->body;
  EXPECT_EQ(c.Get("/api/v1/sessions/" + id)->body, before);
  remove(id);
}

TEST_F(Api, FrameWithEtagAnd304) {
  const std::string id = create(R"({"preset": "spinning_rigid_sphere"})");
  auto c = client();
  auto frame = c.Get("/api/v1/sessions/" + id + "/frame.png?width=320&height=240&layers=surface,body");
  ASSERT_TRUE(frame);
  ASSERT_EQ(frame->status, 200) << frame->body;
  EXPECT_EQ(frame->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(frame->body.substr(1, 3), "PNG");
  const std::string etag = frame->get_header_value("ETag");
  ASSERT_FALSE(etag.empty());
  // Asked again without the ETag: served from the frame cache, the same bytes.
  auto cached = c.Get("/api/v1/sessions/" + id + "/frame.png?width=320&height=240&layers=surface,body");
  ASSERT_TRUE(cached);
  EXPECT_EQ(cached->body, frame->body);
  EXPECT_EQ(cached->get_header_value("ETag"), etag);
  auto again = c.Get("/api/v1/sessions/" + id + "/frame.png?width=320&height=240&layers=surface,body",
                     {{"If-None-Match", etag}});
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 304);
  EXPECT_TRUE(again->body.empty());
  // Weak (replicas on other CPUs render the state within a tolerance, not to the same bytes), and
  // compared weakly: without its W/, in a list, or "*".
  ASSERT_EQ(etag.rfind("W/\"", 0), 0u) << etag;
  for (const std::string& asked : {etag.substr(2), "\"other\", " + etag, std::string("*")})
    EXPECT_EQ(c.Get("/api/v1/sessions/" + id + "/frame.png?width=320&height=240&layers=surface,body",
                    {{"If-None-Match", asked}})
                  ->status,
              304)
        << asked;
  EXPECT_EQ(c.Get("/api/v1/sessions/" + id + "/frame.png?width=320&height=240&layers=surface,body",
                  {{"If-None-Match", "\"other\""}})
                ->status,
            200);
  // A new state is a new picture.
  c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 1})", "application/json");
  auto moved = c.Get("/api/v1/sessions/" + id + "/frame.png?width=320&height=240&layers=surface,body",
                     {{"If-None-Match", etag}});
  ASSERT_TRUE(moved);
  EXPECT_EQ(moved->status, 200);
  EXPECT_NE(moved->get_header_value("ETag"), etag);
  remove(id);
}

// The camera is part of the picture: another yaw, pitch or distance is another ETag and other
// pixels, never the cached frame of the first camera.
TEST_F(Api, FrameEtagNamesTheCamera) {
  const std::string id = create(R"({"preset": "spinning_rigid_sphere"})");
  auto c = client();
  const std::string base = "/api/v1/sessions/" + id + "/frame.png?width=160&height=120";
  std::set<std::string> etags, bodies;
  for (const char* camera : {"", "&yaw=2", "&yaw=1", "&yaw=1&pitch=0.5", "&yaw=1&pitch=0.5&distance=6"}) {
    auto frame = c.Get(base + camera);
    ASSERT_TRUE(frame);
    ASSERT_EQ(frame->status, 200) << camera << ": " << frame->body;
    etags.insert(frame->get_header_value("ETag"));
    bodies.insert(frame->body);
  }
  EXPECT_EQ(etags.size(), 5u);
  EXPECT_EQ(bodies.size(), 5u);
  remove(id);
}

TEST_F(Api, ConcurrentClientsSteerDifferentSessions) {
  std::vector<std::string> ids;
  for (int i = 0; i < 4; ++i) ids.push_back(create(R"({"preset": "breathing_ellipse_sphere"})"));
  std::vector<std::thread> clients;
  std::vector<double> final_t(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i)
    clients.emplace_back([&, i] {
      auto c = client();
      for (int k = 1; k <= 20; ++k)
        c.Post("/api/v1/sessions/" + ids[i] + "/advance",
               "{\"until\": " + std::to_string(0.1 * k * (i + 1)) + "}", "application/json");
      final_t[i] = json::parse(c.Get("/api/v1/sessions/" + ids[i])->body)["state"]["t"];
    });
  for (auto& t : clients) t.join();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    EXPECT_NEAR(final_t[i], 2.0 * (i + 1), 1e-12);
    remove(ids[i]);
  }
}

using test::BadRequest;

class BadRequests : public Api, public ::testing::WithParamInterface<BadRequest> {};

TEST_P(BadRequests, ProblemJsonAndTheSessionIsUnchanged) {
  const std::string id = create(R"({"preset": "spinning_rigid_sphere"})");
  auto c = client();
  const std::string before = c.Get("/api/v1/sessions/" + id)->body;
  test::expect_problem(c, GetParam(), id);
  EXPECT_EQ(c.Get("/api/v1/sessions/" + id)->body, before);  // nothing lost, nothing changed
  remove(id);
}

INSTANTIATE_TEST_SUITE_P(Table, BadRequests, ::testing::ValuesIn(test::bad_requests()));

// A client that leaves mid-request (a frame being rendered, an open event stream) does not take
// the server down.
TEST_F(Api, DroppedClientsDoNotHurtTheServer) {
  const std::string id = create(R"({"preset": "spinning_rigid_sphere"})");
  for (const std::string& path : {"/api/v1/sessions/" + id + "/frame.png?width=1024&height=768&scale=0.3",
                                  "/api/v1/sessions/" + id + "/events?rate=50"}) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(server_.port()));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    const std::string request = "GET " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n";
    ASSERT_GT(::send(fd, request.data(), request.size(), 0), 0);
    ::close(fd);  // gone before the answer
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  auto health = client().Get("/api/v1/health");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
  remove(id);
}

TEST_F(Api, SessionLimitAnswers503WithRetryAfter) {
  std::vector<std::string> ids;
  for (int i = 0; i < 6; ++i) {
    auto res =
        client().Post("/api/v1/sessions", R"({"preset": "geodesic_rigid_sphere"})", "application/json");
    ASSERT_TRUE(res);
    if (res->status == 201) ids.push_back(json::parse(res->body)["id"]);
  }
  auto over = client().Post("/api/v1/sessions", R"({"preset": "geodesic_rigid_sphere"})", "application/json");
  ASSERT_TRUE(over);
  EXPECT_EQ(over->status, 503);
  EXPECT_FALSE(over->get_header_value("Retry-After").empty());
  for (const std::string& id : ids) remove(id);
}

// ---- The route table: one source for routing, 405s, query checks and the OpenAPI document.

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// operationIds name the methods of generated clients: each a snake_case verb and noun, unique.
TEST(RouteTable, EveryOperationHasAUniqueSnakeCaseVerbId) {
  const std::vector<Route> table = route_table(ServerOptions{}.limits);
  const std::set<std::string> verbs = {"get",  "list",  "create", "update", "delete", "advance",
                                       "play", "pause", "reset",  "stream", "steer"};
  std::set<std::string> ids;
  for (const Route& route : table) {
    const std::string& id = route.operation_id;
    EXPECT_TRUE(ids.insert(id).second) << "duplicate " << id;
    EXPECT_FALSE(id.empty()) << route.method << " " << route.path;
    EXPECT_TRUE(verbs.contains(id.substr(0, id.find('_')))) << id;
    bool snake = !id.empty() && id.front() != '_' && id.back() != '_' && id.find("__") == std::string::npos;
    for (const char c : id) snake = snake && ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_');
    EXPECT_TRUE(snake) << id;
  }
  // The names clients already use for the main operations.
  for (const char* id :
       {"create_session", "get_session", "update_session", "delete_session", "advance_session", "get_frame",
        "create_recording", "get_scene_schema", "get_openapi_document", "get_frame_svg", "get_frame_pdf"})
    EXPECT_TRUE(ids.contains(id)) << id;
}

// Every row of the table is an operation of openapi.json, with each of its query parameters and
// their schemas (the test iterates the table itself, so it cannot drift).
TEST_F(Api, OpenApiDocumentsEveryRouteAndQueryParameterOfTheTable) {
  auto doc = client().Get("/api/v1/openapi.json");
  ASSERT_TRUE(doc);
  const json paths = json::parse(doc->body)["paths"];
  const std::vector<Route> table = route_table(test_options().limits);
  ASSERT_GE(table.size(), 15u);
  std::size_t query_parameters = 0;
  for (const Route& route : table) {
    ASSERT_TRUE(paths.contains(route.path)) << route.path;
    ASSERT_TRUE(paths[route.path].contains(lower(route.method))) << route.method << " " << route.path;
    const json operation = paths[route.path][lower(route.method)];
    EXPECT_EQ(operation["summary"], route.summary);
    EXPECT_EQ(operation["operationId"], route.operation_id);
    EXPECT_EQ(operation.contains("requestBody"), route.body.has_value()) << route.path;
    if (route.body) {
      for (const std::string& type : route.body->content_types)
        EXPECT_TRUE(operation["requestBody"]["content"].contains(type)) << route.path << " " << type;
    }
    for (const auto& [status, description] : route.responses)
      EXPECT_EQ(operation["responses"][std::to_string(status)]["description"], description) << route.path;
    for (const QueryParam& p : route.query) {
      ++query_parameters;
      json documented;
      for (const json& q : operation["parameters"])
        if (q.value("name", std::string()) == p.name && q.value("in", std::string()) == "query")
          documented = q;
      ASSERT_FALSE(documented.is_null()) << route.method << " " << route.path << " ?" << p.name;
      EXPECT_EQ(documented["description"], p.description);
      const json schema = documented["schema"];
      EXPECT_EQ(schema["type"], p.type == ParamType::integer  ? "integer"
                                : p.type == ParamType::number ? "number"
                                                              : "string")
          << p.name;
      if (p.minimum) {  // JSON Schema 2020-12: an exclusive bound is a number of its own keyword
        EXPECT_EQ(schema[p.exclusive_minimum ? "exclusiveMinimum" : "minimum"], *p.minimum) << p.name;
        EXPECT_FALSE(schema.contains(p.exclusive_minimum ? "minimum" : "exclusiveMinimum")) << p.name;
      }
      if (p.maximum) {
        EXPECT_EQ(schema["maximum"], *p.maximum) << p.name;
      }
      if (p.type == ParamType::enumeration) {
        EXPECT_EQ(schema["enum"], p.values) << p.name;
      }
      if (!p.unit.empty()) {
        EXPECT_EQ(schema["x-unit"], p.unit) << p.name;
      }
      EXPECT_EQ(schema.contains("default"), p.default_value.has_value()) << p.name;
    }
  }
  EXPECT_GE(query_parameters, 11u);
  // The operations the API has always had, with the parameters the UI and clients send.
  const auto query_names = [&](const std::string& path, const std::string& method) {
    std::set<std::string> names;
    for (const json& q : paths[path][method].value("parameters", json::array()))
      if (q["in"] == "query") names.insert(q["name"].get<std::string>());
    return names;
  };
  EXPECT_EQ(query_names("/api/v1/sessions/{id}/frame.png", "get"),
            (std::set<std::string>{"width", "height", "view", "layers", "scale", "yaw", "pitch", "distance",
                                   "trail", "motion", "shown", "at"}));
  // The figures draw the state now: the raster frames' `at` (the scrubber's) is not theirs.
  std::set<std::string> figure_names = query_names("/api/v1/sessions/{id}/frame.png", "get");
  figure_names.erase("at");
  for (const char* figure : {"/api/v1/sessions/{id}/frame.svg", "/api/v1/sessions/{id}/frame.pdf"})
    EXPECT_EQ(query_names(figure, "get"), figure_names) << figure;
  EXPECT_EQ(query_names("/api/v1/sessions/{id}/events", "get"), std::set<std::string>{"rate"});
  EXPECT_EQ(query_names("/api/v1/sessions/{id}/trajectory", "get"),
            (std::set<std::string>{"format", "every", "fields"}));
  EXPECT_EQ(query_names("/api/v1/sessions", "post"), std::set<std::string>{});
  EXPECT_EQ(query_names("/api/v1/sessions/{id}", "get"), std::set<std::string>{});
  // And nothing is documented that the table does not have.
  std::size_t operations = 0;
  for (const auto& [path, methods] : paths.items()) operations += methods.size();
  EXPECT_EQ(operations, table.size());
}

TEST(RouteTable, PathsBecomeRegexes) {
  EXPECT_EQ(path_regex("/api/v1/sessions/{id}/frame.png"),
            "/api/v1/sessions/([A-Za-z0-9_-]{1,44})/frame\\.png");
  EXPECT_EQ(path_regex("/"), "/");
  // One row per method and path.
  std::set<std::string> seen;
  for (const Route& route : route_table(Limits{}))
    EXPECT_TRUE(seen.insert(route.method + " " + route.path).second) << route.method << " " << route.path;
}

json problem_of(const httplib::Result& res) {
  EXPECT_TRUE(res);
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/problem+json");
  return json::parse(res->body);
}

bool names_field(const json& problem, const std::string& field) {
  for (const auto& e : problem["errors"])
    if (e["field"] == field) return true;
  return false;
}

TEST_F(Api, UnknownQueryParametersAreRefusedByName) {
  const std::string id = create(R"({"preset": "spinning_rigid_sphere"})");
  auto c = client();
  for (const std::string& path :
       std::vector<std::string>{"/api/v1/sessions/" + id + "/frame.png?width=160&nocache=12345",
                                "/api/v1/sessions/" + id + "?nocache=12345", "/api/v1/health?nocache=12345",
                                "/api/v1/sessions/" + id + "/trajectory?format=csv&nocache=12345"}) {
    auto res = c.Get(path);
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 422) << path;
    const json problem = problem_of(res);
    EXPECT_TRUE(names_field(problem, "nocache")) << res->body;
    EXPECT_NE(problem["detail"].get<std::string>().find("nocache"), std::string::npos) << res->body;
    EXPECT_NE(problem["detail"].get<std::string>().find("(got 12345)"), std::string::npos) << res->body;
  }
  // On a POST too, and nothing is created.
  auto post =
      c.Post("/api/v1/sessions?start=1", R"({"preset": "spinning_rigid_sphere"})", "application/json");
  ASSERT_TRUE(post);
  EXPECT_EQ(post->status, 422);
  EXPECT_TRUE(names_field(problem_of(post), "start"));
  // Each parameter once.
  auto twice = c.Get("/api/v1/sessions/" + id + "/frame.png?width=160&width=320");
  ASSERT_TRUE(twice);
  EXPECT_EQ(twice->status, 422);
  EXPECT_TRUE(names_field(problem_of(twice), "width"));
  remove(id);
}

// The UI page is opened by people from links that may carry parameters it does not use.
TEST_F(Api, TheUiPageIgnoresUnknownQueryParameters) {
  auto page = client().Get("/?utm_source=slides&v=2");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("<html"), std::string::npos);
}

TEST_F(Api, QueryValuesOutOfRangeOrOfTheWrongTypeNameTheValue) {
  const std::string id = create(R"({"preset": "spinning_rigid_sphere"})");
  auto c = client();
  const std::string frame = "/api/v1/sessions/" + id + "/frame.png?";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {frame + "scale=11", "scale: must be a number in (0, 10] (got 11)"},
      {frame + "scale=0", "scale: must be a number in (0, 10] (got 0)"},
      {frame + "distance=0.5", "distance: must be a number from 1.2 to 100 [radii] (got 0.5)"},
      {frame + "pitch=2", "pitch: must be a number from -1.55 to 1.55 [rad] (got 2)"},
      {frame + "width=5000", "width: must be a whole number from 16 to 4096 [pixels] (got 5000)"},
      {frame + "height=2.5", "height: must be a whole number from 16 to 4096 [pixels] (got 2.5)"},
      {frame + "yaw=nan", "yaw: must be a number from -100 to 100 [rad] (got nan)"},
      {frame + "view=cube",
       "view: must be sphere, disk, hyperboloid, klein, halfplane, tractricoid, plane, conformal, "
       "revolution, chart or formula (got cube)"},
      {frame + "view=klein", "view: the sphere is shown in these views: sphere, disk, conformal (got klein)"},
      {frame + "layers=body,glitter",
       "layers: 'glitter' is not one of surface, grid, body, frame, trail, hud, actions, curvature, bending, "
       "drift, plain (got "
       "body,glitter)"},
      {"/api/v1/sessions/" + id + "/events?rate=1000",
       "rate: must be a number from 0.5 to 60 [Hz] (got 1000)"},
      {"/api/v1/sessions/" + id + "/trajectory?format=xml", "format: must be json or csv (got xml)"},
      // Commas alone name no column (they were a 500).
      {"/api/v1/sessions/" + id + "/trajectory?format=csv&fields=,,",
       "fields: names nothing: must be a comma-separated list of t, r, phi"},
      {"/api/v1/sessions/" + id + "/trajectory?format=json&fields=%2C",
       "fields: names nothing: must be a comma-separated list of t, r, phi"},
      {frame + "layers=,", "layers: names nothing: must be a comma-separated list of surface, grid"},
  };
  for (const auto& [path, detail] : cases) {
    auto res = c.Get(path);
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 422) << path;
    const std::string said = problem_of(res)["detail"];
    if (detail.find("names nothing") != std::string::npos)
      EXPECT_TRUE(said.starts_with(detail)) << said;  // the list of every column follows
    else
      EXPECT_EQ(said, detail) << path;
  }
  auto span = c.Get(frame + "trail=-1");
  ASSERT_TRUE(span);
  EXPECT_EQ(span->status, 422);
  EXPECT_EQ(problem_of(span)["detail"], "trail: must be a number >= 0 [time] (got -1)");
  // Several bad values: every one is named.
  auto both = c.Get(frame + "width=1&scale=99");
  ASSERT_TRUE(both);
  const json problem = problem_of(both);
  EXPECT_TRUE(names_field(problem, "width"));
  EXPECT_TRUE(names_field(problem, "scale"));
  remove(id);
}

TEST_F(Api, PatchAcceptsMergePatchJson) {
  const std::string id = create(R"({"preset": "breathing_ellipse_sphere"})");
  auto c = client();
  auto patched =
      c.Patch("/api/v1/sessions/" + id, R"({"body": {"mass": 2}})", "application/merge-patch+json");
  ASSERT_TRUE(patched);
  ASSERT_EQ(patched->status, 200) << patched->body;
  EXPECT_EQ(json::parse(patched->body)["scene"]["body"]["mass"], 2.0);
  auto with_charset = c.Patch("/api/v1/sessions/" + id, R"({"body": {"mass": 3}})",
                              "application/merge-patch+json; charset=utf-8");
  ASSERT_TRUE(with_charset);
  EXPECT_EQ(with_charset->status, 200) << with_charset->body;
  // Other routes take JSON only, and the 415 says which types a route takes.
  auto advance =
      c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 1})", "application/merge-patch+json");
  ASSERT_TRUE(advance);
  EXPECT_EQ(advance->status, 415);
  auto xml = c.Patch("/api/v1/sessions/" + id, "<mass/>", "application/xml");
  ASSERT_TRUE(xml);
  EXPECT_EQ(xml->status, 415);
  EXPECT_EQ(problem_of(xml)["detail"],
            "Content-Type: must be application/json or application/merge-patch+json (got application/xml)");
  remove(id);
}

TEST_F(Api, AnEmptyBodySaysAJsonObjectIsExpected) {
  const std::string id = create(R"({"preset": "spinning_rigid_sphere"})");
  auto c = client();
  for (const auto& [method, path] : {std::pair<std::string, std::string>{"POST", "/api/v1/sessions"},
                                     {"PATCH", "/api/v1/sessions/" + id},
                                     {"POST", "/api/v1/sessions/" + id + "/advance"}}) {
    auto res =
        method == "PATCH" ? c.Patch(path, "", "application/json") : c.Post(path, "", "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 400) << path;
    EXPECT_NE(problem_of(res)["detail"].get<std::string>().find("a JSON object is expected"),
              std::string::npos)
        << res->body;
  }
  remove(id);
}

// A key repeated in one object is 422 naming its path, whichever value comes last, and changes
// nothing (nlohmann-json alone would take the last: a session with mass 1 from {"mass":-1,"mass":1}).
TEST_F(Api, ARepeatedJsonKeyIsRefusedNamingIt) {
  const std::string id = create(R"({"preset": "spinning_rigid_sphere"})");
  auto c = client();
  const std::string before = c.Get("/api/v1/sessions/" + id)->body;
  for (const char* body : {R"({"scene": {"body": {"mass": -1, "mass": 1}}})",
                           R"({"scene": {"body": {"mass": 1, "mass": -1}}})"}) {
    auto res = c.Post("/api/v1/sessions", body, "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 422) << body;
    EXPECT_TRUE(names_field(problem_of(res), "scene.body.mass")) << res->body;
  }
  auto patch = c.Patch("/api/v1/sessions/" + id, R"({"body": {"mass": 2, "mass": 3}})", "application/json");
  ASSERT_TRUE(patch);
  EXPECT_EQ(patch->status, 422);
  EXPECT_TRUE(names_field(problem_of(patch), "body.mass")) << patch->body;
  EXPECT_EQ(c.Get("/api/v1/sessions/" + id)->body, before);
  remove(id);
}

TEST_F(Api, EveryRouteAnswersAnUnknownSessionTheSameWay) {
  auto c = client();
  const std::string path = "/api/v1/sessions/0123456789abcdef";
  std::vector<httplib::Result> answers;
  answers.push_back(c.Get(path));
  answers.push_back(c.Delete(path));
  answers.push_back(c.Patch(path, R"({"body": {"mass": 2}})", "application/json"));
  answers.push_back(c.Post(path + "/advance", R"({"until": 1})", "application/json"));
  answers.push_back(c.Post(path + "/play", R"({"rate": 1})", "application/json"));
  answers.push_back(c.Post(path + "/pause", "", "application/json"));
  answers.push_back(c.Post(path + "/reset", "{}", "application/json"));
  answers.push_back(c.Get(path + "/trajectory"));
  answers.push_back(c.Get(path + "/frame.png"));
  answers.push_back(c.Get(path + "/events"));
  for (const auto& res : answers) {
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 404);
    EXPECT_EQ(res->body, answers.front()->body);
  }
  const json problem = problem_of(answers.front());
  EXPECT_EQ(problem["title"], "Unknown session");
  EXPECT_TRUE(names_field(problem, "id"));
  EXPECT_NE(problem["detail"].get<std::string>().find("(got 0123456789abcdef)"), std::string::npos);
}

// Numbers written for people: the shortest form that reads back (1e-10, not 0.000000).
TEST_F(Api, NumbersInHeadersAndMessagesAreInShortestForm) {
  const std::string id = create(R"({"preset": "breathing_ellipse_sphere"})");
  auto c = client();
  auto got = c.Get("/api/v1/sessions/" + id);
  ASSERT_TRUE(got);
  const std::string provenance = got->get_header_value("X-Spinfold-Provenance");
  EXPECT_NE(provenance.find("tolerance=1e-10"), std::string::npos) << provenance;
  c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 1.5})", "application/json");
  auto before = c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 0.25})", "application/json");
  ASSERT_TRUE(before);
  EXPECT_EQ(problem_of(before)["detail"], "until: is before the session's time (t = 1.5) (got 0.25)");
  auto far = c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 1e12})", "application/json");
  ASSERT_TRUE(far);
  EXPECT_EQ(problem_of(far)["detail"],
            "until: advances more than 1e+06 time units in one request (got 1e+12)");
  auto fast = c.Post("/api/v1/sessions/" + id + "/play", R"({"rate": 5000})", "application/json");
  ASSERT_TRUE(fast);
  EXPECT_EQ(problem_of(fast)["detail"], "rate: must be > 0 and <= 1000 (got 5000)");
  for (const auto* res : {&before, &far, &fast})
    EXPECT_EQ((*res)->body.find("000000,"), std::string::npos) << (*res)->body;
  remove(id);
}

// httplib refuses a POST without Content-Length before any route sees it: the answer says why.
TEST_F(Api, APostWithoutContentLengthIsToldWhy) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(server_.port()));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  const std::string request =
      "POST /api/v1/sessions/0123456789abcdef/pause HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
  ASSERT_GT(::send(fd, request.data(), request.size(), 0), 0);
  std::string answer;
  char buffer[4096];
  for (ssize_t n; (n = ::recv(fd, buffer, sizeof buffer, 0)) > 0;)
    answer.append(buffer, static_cast<std::size_t>(n));
  ::close(fd);
  EXPECT_EQ(answer.rfind("HTTP/1.1 400", 0), 0u) << answer;
  EXPECT_NE(answer.find("needs a Content-Length header"), std::string::npos) << answer;
}

TEST_F(Api, KnownPathsWithAnotherMethodAnswer405WithAllow) {
  auto c = client();
  auto sessions = c.Delete("/api/v1/sessions");
  ASSERT_TRUE(sessions);
  EXPECT_EQ(sessions->status, 405);
  EXPECT_EQ(sessions->get_header_value("Allow"), "POST, OPTIONS");
  auto session = c.Put("/api/v1/sessions/0123456789abcdef", "{}", "application/json");
  ASSERT_TRUE(session);
  EXPECT_EQ(session->status, 405);
  EXPECT_EQ(session->get_header_value("Allow"), "GET, PATCH, DELETE, OPTIONS");
  EXPECT_TRUE(names_field(problem_of(session), "method"));
  auto frame = c.Post("/api/v1/sessions/0123456789abcdef/frame.png", "{}", "application/json");
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->status, 405);
  EXPECT_EQ(frame->get_header_value("Allow"), "GET, OPTIONS");
  // OPTIONS on a known path: 204 with the same Allow (RFC 9110 §9.3.7); an unknown path stays 404.
  auto options = c.Options("/api/v1/sessions/0123456789abcdef");
  ASSERT_TRUE(options);
  EXPECT_EQ(options->status, 204);
  EXPECT_EQ(options->get_header_value("Allow"), "GET, PATCH, DELETE, OPTIONS");
  EXPECT_TRUE(options->body.empty());
  EXPECT_FALSE(options->has_header("Content-Length")) << "RFC 9110 §8.6: never with 204";
  auto unknown = c.Options("/api/v1/nothing-here");
  ASSERT_TRUE(unknown);
  EXPECT_EQ(unknown->status, 404);
}

// The trail follows the true path whatever the advances: one to t = 6 and sixty of 0.1 draw the
// same frame, byte for byte (the spinning body circles; chords would cut across).
TEST_F(Api, TrailIsTheSameHoweverTheRunWasAdvanced) {
  auto c = client();
  for (const char* preset : {"spinning_rigid_sphere", "deforming_spin_pseudosphere"}) {
    SCOPED_TRACE(preset);
    const std::string once = create(json{{"preset", preset}}.dump());
    const std::string many = create(json{{"preset", preset}}.dump());
    ASSERT_EQ(c.Post("/api/v1/sessions/" + once + "/advance", R"({"until": 6})", "application/json")->status,
              200);
    for (int k = 1; k <= 60; ++k)
      ASSERT_EQ(
          c.Post("/api/v1/sessions/" + many + "/advance", json{{"until", k * 0.1}}.dump(), "application/json")
              ->status,
          200);
    c.Post("/api/v1/sessions/" + many + "/advance", R"({"until": 6})", "application/json");
    const json a = json::parse(c.Get("/api/v1/sessions/" + once)->body)["state"];
    const json b = json::parse(c.Get("/api/v1/sessions/" + many)->body)["state"];
    EXPECT_EQ(a, b);
    const std::string query = "/frame.png?width=320&height=240";
    auto fa = c.Get("/api/v1/sessions/" + once + query);
    auto fb = c.Get("/api/v1/sessions/" + many + query);
    ASSERT_EQ(fa->status, 200);
    ASSERT_EQ(fb->status, 200);
    EXPECT_TRUE(fa->body == fb->body) << "frames differ";
    // A span of the trail is a different picture, and the same for both.
    auto sa = c.Get("/api/v1/sessions/" + once + query + "&trail=1");
    auto sb = c.Get("/api/v1/sessions/" + many + query + "&trail=1");
    EXPECT_TRUE(sa->body == sb->body);
    EXPECT_FALSE(sa->body == fa->body);
    remove(once);
    remove(many);
  }
}

// A session rebuilt from its scene, timeline and time equals the original: state and frame bytes.
TEST_F(Api, RebuiltSessionEqualsTheOriginalAfterSeveralPatches) {
  auto c = client();
  for (const char* integrator : {"auto", "dop853"}) {
    SCOPED_TRACE(integrator);
    const std::string id = create(json{
        {"surface", {{"kind", "sphere"}, {"radius", 1.0}}},
        {"body", {{"mass", 1.0}, {"inertia", 0.2}}},
        {"potential", {{"deformation", {{"kind", "abc"}, {"C", 0.5}}}}},
        {"initial", {{"r", 1.2}, {"lambda", 1.3}, {"mu", 0.7}, {"phi_dot", 0.3}, {"alpha_dot", 0.8}}},
        {"integrator",
         {{"name", integrator}}}}.dump());
    const std::string session = "/api/v1/sessions/" + id;
    const char* patches[] = {R"({"body": {"mass": 2}})", R"({"potential": {"deformation": {"C": 0.2}}})",
                             R"({"surface": {"radius": 1.5}})", R"({"body": {"inertia": 0.3}})"};
    double t = 0.0;
    for (const char* patch : patches) {
      for (int k = 0; k < 7; ++k) {
        t += 0.137;
        c.Post(session + "/advance", json{{"until", t}}.dump(), "application/json");
      }
      auto patched = c.Patch(session, patch, "application/merge-patch+json");
      ASSERT_EQ(patched->status, 200) << patched->body;
      EXPECT_EQ(json::parse(patched->body)["change"]["kind"], "continued");
    }
    c.Post(session + "/advance", json{{"until", t + 0.5}}.dump(), "application/json");
    const json original = json::parse(c.Get(session)->body);
    ASSERT_EQ(original["timeline"].size(), 4u);
    auto copy = c.Post("/api/v1/sessions",
                       json{{"scene", original["scene"]},
                            {"timeline", original["timeline"]},
                            {"until", original["state"]["t"]}}
                           .dump(),
                       "application/json");
    ASSERT_EQ(copy->status, 201) << copy->body;
    const json rebuilt = json::parse(copy->body);
    EXPECT_EQ(rebuilt["advance"]["complete"], true);
    EXPECT_EQ(rebuilt["state"], original["state"]);
    EXPECT_EQ(rebuilt["current"], original["current"]);
    EXPECT_EQ(rebuilt["timeline"], original["timeline"]);
    const std::string query = "/frame.png?width=320&height=240";
    auto fa = c.Get(session + query);
    auto fb = c.Get("/api/v1/sessions/" + rebuilt["id"].get<std::string>() + query);
    ASSERT_EQ(fa->status, 200);
    EXPECT_TRUE(fa->body == fb->body) << "frames differ";
    remove(id);
    remove(rebuilt["id"]);
  }
}

// Changes at a pole (where the paper's coordinates are undefined) and after det L = 0 (a mirrored
// frame no initial state can be) continue the run at its time and place.
TEST_F(Api, PatchAtAPoleAndAfterAFrameCrossingContinues) {
  auto c = client();
  for (const auto& [preset, until] :
       {std::pair{"pole_crossing_sphere", 2.0}, std::pair{"degenerate_crossing", 0.8}}) {
    SCOPED_TRACE(preset);
    const std::string id = create(json{{"preset", preset}}.dump());
    const std::string session = "/api/v1/sessions/" + id;
    const json before = json::parse(
        c.Post(session + "/advance", json{{"until", until}}.dump(), "application/json")->body)["state"];
    auto patched = c.Patch(session, R"({"body": {"mass": 2}})", "application/json");
    ASSERT_EQ(patched->status, 200) << patched->body;
    const json after = json::parse(patched->body)["state"];
    EXPECT_EQ(after["t"], until);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(after["X"][i].get<double>(), before["X"][i].get<double>(), 1e-12);
    EXPECT_EQ(after["status"], "ok");
    auto on = c.Post(session + "/advance", json{{"until", until + 1}}.dump(), "application/json");
    EXPECT_EQ(json::parse(on->body)["state"]["status"], "ok");
    remove(id);
  }
}

TEST_F(Api, ABadTimelineIsRefusedNamingTheEntry) {
  auto c = client();
  const auto refused = [&](const std::string& timeline, const std::string& field) {
    auto res =
        c.Post("/api/v1/sessions",
               R"({"scene": {"preset": "spinning_rigid_sphere"}, "until": 3, "timeline": )" + timeline + "}",
               "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 422) << res->body;
    EXPECT_EQ(json::parse(res->body)["errors"][0]["field"], field) << res->body;
  };
  refused(R"([{"t": 1, "patch": {"initial": {"r": 0.5}}}])", "timeline[0].patch");
  refused(R"([{"t": 2, "patch": {"body": {"mass": 2}}}, {"t": 1, "patch": {"body": {"mass": 3}}}])",
          "timeline[1].t");
  refused(R"([{"t": 1, "patch": {"body": {"mass": -2}}}])", "timeline[0].patch.body.mass");
  refused(R"([{"t": 4, "patch": {"body": {"mass": 2}}}])", "timeline[0].t");
  refused(R"([{"t": 1, "patch": {}, "extra": 1}])", "timeline[0].extra");
  EXPECT_EQ(json::parse(c.Get("/api/v1/health")->body)["sessions"], 0);  // nothing left behind
}

// Companions through the API: created from a preset, carried through a PATCH of the main body (the
// geodesic companion inherits the mass), replayed from scene + timeline to the same state and
// frame bytes; a bad companion is 422 naming its path, and the session is unchanged.
TEST_F(Api, CompanionsThroughPostPatchAndTimelineReplay) {
  auto c = client();
  const std::string id = create(R"({"preset": "spin_vs_geodesic_sphere"})");
  const std::string session = "/api/v1/sessions/" + id;
  ASSERT_EQ(c.Post(session + "/advance", R"({"until": 1.5})", "application/json")->status, 200);
  auto patched = c.Patch(session, R"({"body": {"mass": 2}})", "application/merge-patch+json");
  ASSERT_EQ(patched->status, 200) << patched->body;
  const json after = json::parse(patched->body);
  EXPECT_EQ(after["change"]["kind"], "continued");
  ASSERT_EQ(after["state"]["companions"].size(), 1u);
  EXPECT_EQ(after["state"]["companions"][0]["label"], "geodesic (s = 0)");
  EXPECT_EQ(after["state"]["companions"][0]["t"], 1.5);
  EXPECT_EQ(after["state"]["companions"][0]["spin"], 0.0);
  ASSERT_EQ(c.Post(session + "/advance", R"({"until": 3.25})", "application/json")->status, 200);
  const json original = json::parse(c.Get(session)->body);
  EXPECT_EQ(original["state"]["companions"][0]["t"], 3.25);

  const json before_bad = original;
  auto bad_patch =
      c.Patch(session, R"({"companions": [{"geodesic": true}, {"body": {"mass": -1}}]})", "application/json");
  ASSERT_EQ(bad_patch->status, 422);
  EXPECT_EQ(json::parse(bad_patch->body)["errors"][0]["field"], "companions[1].body.mass");
  EXPECT_EQ(json::parse(c.Get(session)->body), before_bad);

  auto copy =
      c.Post("/api/v1/sessions",
             json{{"scene", original["scene"]}, {"timeline", original["timeline"]}, {"until", 3.25}}.dump(),
             "application/json");
  ASSERT_EQ(copy->status, 201) << copy->body;
  const json rebuilt = json::parse(copy->body);
  EXPECT_EQ(rebuilt["state"], original["state"]);
  const std::string query = "/frame.png?width=320&height=240";
  auto fa = c.Get(session + query);
  auto fb = c.Get("/api/v1/sessions/" + rebuilt["id"].get<std::string>() + query);
  ASSERT_EQ(fa->status, 200);
  EXPECT_TRUE(fa->body == fb->body) << "frames differ";

  // The CSV has a column block per body.
  auto csv = c.Get(session + "/trajectory?format=csv");
  ASSERT_EQ(csv->status, 200);
  EXPECT_NE(csv->body.find("geodesic (s = 0)_r,"), std::string::npos) << csv->body.substr(0, 300);

  // A change of companions restarts the run.
  auto restarted = c.Patch(session, R"({"vary": {"field": "initial.spin", "values": [0.5, 2]}})",
                           "application/merge-patch+json");
  ASSERT_EQ(restarted->status, 200) << restarted->body;
  const json r = json::parse(restarted->body);
  EXPECT_EQ(r["change"]["kind"], "restarted");
  EXPECT_EQ(r["state"]["companions"].size(), 3u);
  remove(id);
  remove(rebuilt["id"]);
}

// frame.jpg is the same picture as frame.png within JPEG's error, in a third of the bytes; it has
// its own ETag per quality, and the same state gives the same bytes.
TEST_F(Api, JpegFrameIsThePngsPictureInAThirdOfTheBytes) {
  auto c = client();
  const std::string id = create(R"({"preset": "spin_vs_geodesic_sphere"})");
  const std::string session = "/api/v1/sessions/" + id;
  ASSERT_EQ(c.Post(session + "/advance", R"({"until": 2})", "application/json")->status, 200);
  auto png = c.Get(session + "/frame.png");
  auto jpeg = c.Get(session + "/frame.jpg");
  ASSERT_EQ(png->status, 200);
  ASSERT_EQ(jpeg->status, 200);
  EXPECT_EQ(jpeg->get_header_value("Content-Type"), "image/jpeg");
  EXPECT_LE(static_cast<double>(jpeg->body.size()), 0.35 * static_cast<double>(png->body.size()));
  int width = 0, height = 0;
  const std::vector<std::uint8_t> lossless = png_pixels(png->body, width, height);
  ASSERT_EQ(width, 640);
  const std::vector<std::uint8_t> lossy = jpeg_pixels(jpeg->body, width, height);
  ASSERT_EQ(lossy.size(), lossless.size());
  double error = 0.0;
  for (std::size_t i = 0; i < lossy.size(); ++i) error += std::abs(int(lossy[i]) - int(lossless[i]));
  EXPECT_LT(error / static_cast<double>(lossy.size()), 4.0);  // mean per channel, of 255 (measured ~3)

  const std::string etag = jpeg->get_header_value("ETag");
  EXPECT_NE(etag, png->get_header_value("ETag"));
  EXPECT_NE(etag, c.Get(session + "/frame.jpg?quality=90")->get_header_value("ETag"));
  auto again = c.Get(session + "/frame.jpg", {{"If-None-Match", etag}});
  EXPECT_EQ(again->status, 304);
  // Rendered anew (a quality not cached yet, then the default again after a change and back), the
  // same state gives the same bytes.
  auto other = c.Get(session + "/frame.jpg?quality=71");
  auto other_again = c.Get(session + "/frame.jpg?quality=71", {{"If-None-Match", "\"x\""}});
  EXPECT_TRUE(other->body == other_again->body);
  EXPECT_EQ(c.Get(session + "/frame.jpg?quality=101")->status, 422);
  remove(id);
}

// frame.svg and frame.pdf: the frame's request as a vector figure for a paper (render/figure.h),
// with its own ETag; a bad parameter is refused as for frame.png.
TEST_F(Api, SvgAndPdfFramesAreVectorFiguresOfTheState) {
  auto c = client();
  const std::string id = create(R"({"preset": "spin_vs_geodesic_pseudosphere"})");
  const std::string session = "/api/v1/sessions/" + id;
  ASSERT_EQ(c.Post(session + "/advance", R"({"until": 2})", "application/json")->status, 200);
  auto svg = c.Get(session + "/frame.svg?view=disk&width=480&height=360");
  auto pdf = c.Get(session + "/frame.pdf?view=halfplane");
  ASSERT_EQ(svg->status, 200) << svg->body;
  ASSERT_EQ(pdf->status, 200) << pdf->body;
  EXPECT_EQ(svg->get_header_value("Content-Type"), "image/svg+xml");
  EXPECT_EQ(pdf->get_header_value("Content-Type"), "application/pdf");
  EXPECT_TRUE(svg->body.starts_with("<?xml")) << svg->body.substr(0, 40);
  EXPECT_NE(svg->body.find("width=\"360pt\""), std::string::npos);  // 480 px at 0.75 pt each
  EXPECT_NE(svg->body.find("<title>spin_vs_geodesic_pseudosphere"), std::string::npos);
  EXPECT_TRUE(pdf->body.starts_with("%PDF-"));
  EXPECT_FALSE(svg->get_header_value("X-Spinfold-Provenance").empty());
  const std::string etag = svg->get_header_value("ETag");
  EXPECT_NE(etag, c.Get(session + "/frame.png?view=disk&width=480&height=360")->get_header_value("ETag"));
  EXPECT_NE(etag, c.Get(session + "/frame.pdf?view=disk&width=480&height=360")->get_header_value("ETag"));
  EXPECT_EQ(c.Get(session + "/frame.svg?view=disk&width=480&height=360", {{"If-None-Match", etag}})->status,
            304);
  EXPECT_EQ(c.Get(session + "/frame.svg?width=5")->status, 422);
  EXPECT_EQ(c.Get(session + "/frame.pdf?view=sphere")->status, 422);  // no sphere view of H²
  if (figure_test::have_tool("xmllint") && figure_test::have_tool("pdfinfo")) {
    const std::string svg_file =
        figure_test::temporary_file(std::vector<std::uint8_t>(svg->body.begin(), svg->body.end()), ".svg");
    const std::string pdf_file =
        figure_test::temporary_file(std::vector<std::uint8_t>(pdf->body.begin(), pdf->body.end()), ".pdf");
    const auto xml = figure_test::run_tool("xmllint --noout " + svg_file);
    EXPECT_EQ(xml.exit_code, 0) << xml.out;
    const auto info = figure_test::run_tool("pdfinfo " + pdf_file);
    EXPECT_EQ(info.exit_code, 0) << info.out;
    std::filesystem::remove(svg_file);
    std::filesystem::remove(pdf_file);
  }
  remove(id);
}

}  // namespace
}  // namespace spinfold::server
