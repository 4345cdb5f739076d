// Work-precision jobs through the API in-process (small scenes, two integrators, short T: a job
// takes about a second): the job's life and result (curves falling with the tolerance, the plot as
// SVG and PNG, the CSV), its sources (a scene, a preset, a session), bad fields refused by name
// with no job made, one job per client (429), and cancelling.
#include "workprecision/work_precision.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <thread>

#include "codec/presets.h"
#include "server/api.h"

// After Eigen (through the server's headers): httplib.h brings <resolv.h>'s `_res` macro.
#include <httplib.h>

#include "test_server.h"

namespace spinfold::server {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

const std::string kPath = "/api/v1/work-precision";

class WorkPrecision : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { server_.start(test::suite_options(8, 1)); }
  static void TearDownTestSuite() { server_.stop(); }
  static httplib::Client client() { return server_.client(60); }
  static httplib::Result post(const json& body) {
    return client().Post(kPath, body.dump(), "application/json");
  }
  // A user's scene: the W5 preset (radial + abc potentials, no closed form: the oracle is the
  // reference) with a stiffer abc potential, as the CLI's test measures it.
  static json user_scene() {
    json scene = json::parse(find_preset("separable_radial_abc")->json);
    scene["potential"]["deformation"]["C"] = 0.6;
    return scene;
  }
  // Polls until the job is finished; every state seen, in order.
  static std::vector<json> follow(const std::string& url) {
    std::vector<json> seen;
    for (int i = 0; i < 12000; ++i) {
      auto res = client().Get(url);
      EXPECT_EQ(res->status, 200) << res->body;
      seen.push_back(json::parse(res->body));
      if (seen.back()["status"] != "queued" && seen.back()["status"] != "running") break;
      std::this_thread::sleep_for(5ms);
    }
    return seen;
  }
  static std::string field(const httplib::Result& res) {
    return json::parse(res->body)["errors"][0]["field"];
  }

  static test::TestServer server_;
};

test::TestServer WorkPrecision::server_;

TEST_F(WorkPrecision, AJobOnAUserSceneIsDoneWithFallingErrorsAPlotAndTheCsv) {
  auto res = post({{"scene", user_scene()}, {"integrators", {"dop853", "rk4"}}, {"t_end", 2}});
  ASSERT_EQ(res->status, 202) << res->body;
  const json created = json::parse(res->body);
  EXPECT_EQ(res->get_header_value("Location"), created["url"]);
  EXPECT_EQ(created["source"], "scene");
  EXPECT_EQ(created["t_end"], 2.0);
  EXPECT_EQ(created["target_error"], 1e-10);
  const std::vector<json> seen = follow(created["url"]);
  ASSERT_EQ(seen.back()["status"], "done") << seen.back();
  double progress = 0.0;
  for (const json& s : seen) {  // never going back, methods done / methods
    EXPECT_GE(s["progress"].get<double>(), progress) << s;
    progress = s["progress"];
  }
  const json& job = seen.back();
  EXPECT_EQ(job["progress"], 1.0);
  EXPECT_EQ(job["methods_done"], 2);
  EXPECT_EQ(job["methods"], 2);
  const json& result = job["result"];
  EXPECT_EQ(result["reference"]["kind"], "oracle");
  EXPECT_NE(result["recommendation"].get<std::string>().find("For this scene at error 1e-10 over T = 2: "),
            std::string::npos)
      << result["recommendation"];
  std::map<std::string, std::vector<json>> curves;
  for (const json& p : result["points"]) curves[p["method"]].push_back(p);
  ASSERT_EQ(curves.size(), 2u);
  EXPECT_EQ(curves["dop853"].front()["parameter"], "tol");
  EXPECT_EQ(curves["rk4"].front()["parameter"], "dt");
  for (const auto& [method, curve] : curves) {
    ASSERT_GE(curve.size(), 4u) << method;
    // coarse to fine: the error falls by orders of magnitude as the tolerance or step tightens
    EXPECT_GT(curve.front()["value"].get<double>(), curve.back()["value"].get<double>()) << method;
    EXPECT_GT(curve.front()["state_error"].get<double>(), 1e3 * curve.back()["state_error"].get<double>())
        << method;
    for (const json& p : curve) EXPECT_GT(p["seconds_per_unit_time"].get<double>(), 0.0) << p;
  }
  // The recommended setting, as PATCH takes it, reaches the target.
  const json& recommended = result["recommended"];
  ASSERT_TRUE(recommended.is_object()) << result;
  EXPECT_LE(recommended["state_error"].get<double>(), 1e-10);
  EXPECT_EQ(recommended["integrator"]["name"], recommended["method"]);
  EXPECT_TRUE(recommended["integrator"].contains(recommended["parameter"] == "dt" ? "dt" : "tolerance"));

  auto svg = client().Get(result["plot_svg"].get<std::string>());
  ASSERT_EQ(svg->status, 200);
  EXPECT_EQ(svg->get_header_value("Content-Type"), "image/svg+xml");
  EXPECT_NE(svg->body.find("<svg"), std::string::npos);
  EXPECT_NE(svg->body.find("</svg>"), std::string::npos);
  auto png = client().Get(result["plot_png"].get<std::string>());
  ASSERT_EQ(png->status, 200);
  EXPECT_EQ(png->body.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // Both say where they came from: the provenance JSON (the scene's hash; the route as the command).
  for (const std::string* body : {&svg->body, &png->body}) {
    EXPECT_NE(body->find("scene_hash"), std::string::npos) << body->substr(0, 300);
    EXPECT_NE(body->find("POST /api/v1/work-precision"), std::string::npos);
  }
  auto csv = client().Get(result["data_csv"].get<std::string>());
  ASSERT_EQ(csv->status, 200);
  EXPECT_EQ(csv->get_header_value("Content-Type"), "text/csv");
  EXPECT_EQ(csv->body.rfind("# spinfold work-precision ", 0), 0u) << csv->body;
  EXPECT_NE(csv->body.find("\n" + std::string(work_precision::kCsvColumns) + "\n"), std::string::npos);
  EXPECT_NE(csv->body.find("\ndop853,tol,"), std::string::npos);

  // Deleted: gone, files too.
  EXPECT_EQ(client().Delete(created["url"].get<std::string>())->status, 204);
  EXPECT_EQ(client().Get(created["url"].get<std::string>())->status, 404);
  EXPECT_EQ(client().Get(result["plot_svg"].get<std::string>())->status, 404);
}

// A session's parameters in force now (a PATCH after its start counts), and a preset by name.
TEST_F(WorkPrecision, ASessionsCurrentSceneAndAPresetAreMeasured) {
  auto c = client();
  auto created = c.Post("/api/v1/sessions", R"({"preset": "spinning_rigid_sphere"})", "application/json");
  ASSERT_EQ(created->status, 201);
  const std::string session = json::parse(created->body)["id"];
  ASSERT_EQ(c.Patch("/api/v1/sessions/" + session, R"({"integrator": {"name": "rk4", "dt": 0.01}})",
                    "application/merge-patch+json")
                ->status,
            200);
  auto res = post({{"session", session}, {"integrators", {"auto"}}, {"t_end", 1}});
  ASSERT_EQ(res->status, 202) << res->body;
  const json job = follow(json::parse(res->body)["url"]).back();
  ASSERT_EQ(job["status"], "done") << job;
  EXPECT_EQ(job["source"], "session");
  EXPECT_EQ(job["source_name"], "");  // a session's id is a capability: never in a job, its CSV or plot
  const std::string csv = c.Get(job["result"]["data_csv"].get<std::string>())->body;
  EXPECT_EQ(csv.find(session), std::string::npos);
  EXPECT_EQ(c.Get(job["result"]["plot_svg"].get<std::string>())->body.find(session), std::string::npos);
  EXPECT_NE(csv.find("\"rk4\""), std::string::npos) << "the provenance names the session's integrator now";

  res = post({{"preset", "spinning_rigid_sphere"}, {"integrators", {"exact", "rk4"}}, {"t_end", 0.5}});
  ASSERT_EQ(res->status, 202) << res->body;
  const json preset_job = follow(json::parse(res->body)["url"]).back();
  ASSERT_EQ(preset_job["status"], "done") << preset_job;
  EXPECT_EQ(preset_job["source_name"], "spinning_rigid_sphere");
}

// Every bad field is 422 naming it (or 400/415 for the body itself), and none makes a job: a
// valid job straight after is accepted, which one per client would refuse if any had been queued.
TEST_F(WorkPrecision, BadFieldsAreRefusedByNameAndMakeNoJob) {
  const json ok{{"preset", "spinning_rigid_sphere"}, {"integrators", {"rk4"}}, {"t_end", 0.5}};
  const auto refused = [&](const json& patch, const std::string& name, const std::string& reason_part) {
    json body = ok;
    body.merge_patch(patch);
    auto res = post(body);
    ASSERT_EQ(res->status, 422) << body << " " << res->body;
    EXPECT_EQ(res->get_header_value("Content-Type"), "application/problem+json");
    EXPECT_EQ(field(res), name) << res->body;
    EXPECT_NE(res->body.find(reason_part), std::string::npos) << res->body;
  };
  refused({{"preset", "no_such_scene"}}, "preset", "is not a preset");
  refused({{"integrators", {"rk4", "euler"}}}, "integrators", "euler");
  refused({{"integrators", {"rk4", "rk4"}}}, "integrators", "twice");
  refused({{"integrators", json::array()}}, "integrators", "non-empty");
  refused({{"t_end", -1}}, "t_end", "must be a number > 0");
  refused({{"t_end", 1e6}}, "t_end", "characteristic periods");
  refused({{"t_end", "long"}}, "t_end", "must be a number");
  refused({{"target_error", 0}}, "target_error", "from 1e-15 to 1");
  refused({{"target_error", 10}}, "target_error", "from 1e-15 to 1");
  refused({{"speed", 2}}, "speed", "not a known field");
  refused({{"preset", nullptr}, {"session", "nosuchsession"}}, "session", "is not a session");
  refused({{"preset", nullptr}, {"scene", {{"body", {{"mass", -1}}}}}}, "scene.body.mass", "");
  refused({{"scene", user_scene()}}, "scene", "only one of");
  refused({{"preset", nullptr}}, "scene", "is required");
  auto malformed = client().Post(kPath, R"({"preset": )", "application/json");
  EXPECT_EQ(malformed->status, 400);
  EXPECT_EQ(client().Post(kPath, ok.dump(), "text/plain")->status, 415);
  EXPECT_EQ(client().Get(kPath + "/nosuchjob")->status, 404);
  auto accepted = post(ok);
  ASSERT_EQ(accepted->status, 202) << accepted->body;
  EXPECT_EQ(follow(json::parse(accepted->body)["url"]).back()["status"], "done");
}

// While a job runs, the same client's next is 429 (Retry-After); a cancel stops it before its next
// run, its result never comes, and the thread moves on to the next job.
TEST_F(WorkPrecision, OneJobPerClientAndCancelStopsIt) {
  auto res = post({{"scene", user_scene()}});  // every integrator at 20 periods: many seconds
  ASSERT_EQ(res->status, 202) << res->body;
  const std::string url = json::parse(res->body)["url"];
  auto second = post({{"preset", "spinning_rigid_sphere"}, {"integrators", {"rk4"}}, {"t_end", 0.5}});
  ASSERT_EQ(second->status, 429) << second->body;
  EXPECT_EQ(field(second), "limits.max_work_precision_jobs_per_client");
  EXPECT_FALSE(second->get_header_value("Retry-After").empty());
  for (int i = 0; i < 4000 && json::parse(client().Get(url)->body)["status"] == "queued"; ++i)
    std::this_thread::sleep_for(5ms);
  EXPECT_EQ(json::parse(client().Get(url)->body)["status"], "running");
  auto cancelled = client().Delete(url);
  ASSERT_EQ(cancelled->status, 200) << cancelled->body;
  EXPECT_EQ(json::parse(cancelled->body)["status"], "cancelled");
  EXPECT_EQ(follow(url).back()["status"], "cancelled");
  auto csv = client().Get(url + "/data.csv");
  EXPECT_EQ(csv->status, 409);
  EXPECT_EQ(field(csv), "status");
  auto next = post({{"preset", "spinning_rigid_sphere"}, {"integrators", {"rk4"}}, {"t_end", 0.5}});
  ASSERT_EQ(next->status, 202) << next->body;
  EXPECT_EQ(follow(json::parse(next->body)["url"]).back()["status"], "done");
  EXPECT_EQ(follow(url).back()["status"], "cancelled");  // a cancel is final
  EXPECT_EQ(client().Delete(url)->status, 204);
}

}  // namespace
}  // namespace spinfold::server
