// Recordings through the API in-process (tiny frames: this file runs under the sanitizers too): the
// job's life, cancelling, a failure's reason, the limits, and the live session left as it was. (The
// render pool's priorities, which keep recordings from taking render time from live viewers:
// render_pool_test.cpp.)
#include "server/jobs/recordings.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <condition_variable>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "codec/presets.h"
#include "codec/scene_json.h"
#include "server/api.h"
#include "server/frames/render_pool.h"
#include "server/http/problem.h"
#include "server/http/route_table.h"
#include "tests/server/store/test_stores.h"

// After Eigen (through the server's headers): httplib.h brings <resolv.h>'s `_res` macro.
#include <httplib.h>

#include "tests/server/test_server.h"

namespace spinfold::server {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

// The spill directory is made at the first recording and removed with the jobs: a server that never
// records leaves none behind, even killed (every test server and fuzzer run left an empty
// /tmp/spinfold-recordings-* before: ~760 on this machine).
TEST(Recordings, TheDirectoryIsMadeByTheFirstRecordingAndGoesWithTheJobs) {
  const std::filesystem::path tmp =
      std::filesystem::temp_directory_path() / ("recordings_dir_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(tmp);
  const char* before = std::getenv("TMPDIR");
  const std::string saved = before ? before : "";
  ::setenv("TMPDIR", tmp.c_str(), 1);  // where temp_directory_path() looks
  const auto entries = [&] {
    return std::distance(std::filesystem::directory_iterator(tmp), std::filesystem::directory_iterator());
  };
  RenderPool pool(1);
  {
    Recordings recordings(Limits{}, pool);
    EXPECT_EQ(entries(), 0) << "a directory before any recording";
    RecordingJob job{.client = "test", .clip = {0.0, 0.1, 10.0, 1.0}, .format = record::Format::png_zip};
    job.frames.scene = *parse_scene_text(find_preset("spin_vs_geodesic_sphere")->json).scene;
    job.frames.view.width = 32;
    job.frames.view.height = 24;
    recordings.start(job);
    EXPECT_EQ(entries(), 1);
  }
  EXPECT_EQ(entries(), 0) << "the directory outlived its jobs";
  if (before)
    ::setenv("TMPDIR", saved.c_str(), 1);
  else
    ::unsetenv("TMPDIR");
  std::filesystem::remove_all(tmp);
}

// The disk allowance and the age limit, on the jobs alone (no HTTP).
TEST(Recordings, PassingTheDiskAllowanceFailsWithTheReasonAndOldOnesAreDeleted) {
  RenderPool pool(1);
  RecordingJob job{.client = "test", .clip = {0.0, 1.0, 10.0, 1.0}, .format = record::Format::png_zip};
  job.frames.scene = *parse_scene_text(find_preset("spin_vs_geodesic_sphere")->json).scene;
  job.frames.view.width = 64;
  job.frames.view.height = 48;
  const auto finished = [](Recordings& recordings, const std::string& id) {
    for (int i = 0; i < 4000; ++i) {
      const RecordingState state = recordings.state(id);
      if (state.status != RecordingStatus::queued && state.status != RecordingStatus::running) return state;
      std::this_thread::sleep_for(5ms);
    }
    return recordings.state(id);
  };
  Limits limits;
  limits.max_recording_disk_bytes = 2000;  // less than two 64×48 PNGs
  {
    Recordings recordings(limits, pool);
    const RecordingState state = finished(recordings, recordings.start(job));
    EXPECT_EQ(state.status, RecordingStatus::failed);
    EXPECT_NE(state.reason.find("limits.max_recording_disk_bytes"), std::string::npos) << state.reason;
  }
  limits = Limits{};
  limits.recording_max_age = std::chrono::seconds(0);  // deleted as soon as it is finished
  Recordings recordings(limits, pool);
  job.clip = {0.0, 0.1, 10.0, 1.0};  // one frame
  const std::string id = recordings.start(job);
  bool deleted = false;
  for (int i = 0; i < 4000 && !deleted; ++i) {
    try {
      EXPECT_NE(recordings.state(id).status, RecordingStatus::done) << "a finished one outlived its age";
    } catch (const ApiError& e) {
      EXPECT_EQ(e.status, 404);
      deleted = true;
    }
    std::this_thread::sleep_for(5ms);
  }
  EXPECT_TRUE(deleted);
}

// The API's recordings, each test against a server that keeps them in memory and against servers
// with a store (SQLite; PostgreSQL in ctest's server_tests_postgres), where the rows and files are
// the store's: the same answers either way.
class Recording : public ::testing::TestWithParam<std::string> {
 protected:
  static ServerOptions options() {
    ServerOptions options = test::suite_options(8, 2);
    options.limits.max_steps = 3000;
    options.limits.max_recording_frames = 120;
    options.limits.max_recording_pixels = 128 * 96;
    options.limits.max_recordings_per_client = 2;
    return options;
  }
  struct Running {
    std::unique_ptr<spinfold::test::Backend> store;
    std::unique_ptr<ApiServer> server;
    std::unique_ptr<std::thread> thread;
    int port = 0;
  };
  // A server on `options` (and the store `kind`, "memory" for none), serving until the suite ends.
  static Running& start(const std::string& name, const std::string& kind, ServerOptions o,
                        spinfold::test::Backend* shared_store = nullptr) {
    Running& r = servers_[name];
    if (kind != "memory" && !shared_store) {
      r.store = std::make_unique<spinfold::test::Backend>(kind);
      shared_store = r.store.get();
    }
    if (shared_store) {
      if (kind == "sqlite")
        o.data_dir = shared_store->serve_args()[1];
      else
        o.store = shared_store->url();
    }
    r.server = std::make_unique<ApiServer>(o);
    r.port = r.server->bind();
    r.thread = std::make_unique<std::thread>([&server = *r.server] { server.listen(); });
    return r;
  }
  void SetUp() override {
    if (GetParam() == "postgresql" && spinfold::test::postgres_dir().empty())
      GTEST_SKIP() << "no PostgreSQL for this run (ctest's server_tests_postgres starts one)";
    if (!servers_.count(GetParam())) start(GetParam(), GetParam(), options());
    port_ = servers_[GetParam()].port;
    ASSERT_GT(port_, 0);
  }
  static void TearDownTestSuite() {
    for (auto& [name, r] : servers_) {
      r.server->stop();
      r.thread->join();
    }
    servers_.clear();
  }
  static httplib::Client client() {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(60, 0);
    return c;
  }
  static std::string session() {
    auto res =
        client().Post("/api/v1/sessions", R"({"preset": "spin_vs_geodesic_sphere"})", "application/json");
    EXPECT_EQ(res->status, 201);
    return json::parse(res->body)["id"];
  }
  static httplib::Result post(const std::string& session, const json& body) {
    return client().Post("/api/v1/sessions/" + session + "/recordings", body.dump(), "application/json");
  }
  // Polls until the recording is finished; every status and progress seen, in order.
  static std::vector<std::pair<std::string, double>> follow(const std::string& url) {
    std::vector<std::pair<std::string, double>> seen;
    for (int i = 0; i < 6000; ++i) {
      auto res = client().Get(url);
      EXPECT_EQ(res->status, 200) << res->body;
      const json r = json::parse(res->body);
      seen.emplace_back(r["status"], r["progress"]);
      if (r["status"] != "queued" && r["status"] != "running") break;
      std::this_thread::sleep_for(5ms);
    }
    return seen;
  }
  static json problem(const httplib::Result& res) { return json::parse(res->body); }
  static std::string field(const json& problem) { return problem["errors"][0]["field"]; }

  // Byte ranges of the file by RFC 9110 §14 (each case once wrong: an underflowed Content-Length,
  // impossible Content-Range values, 416 for a clamped end or an unknown unit), and a Range header
  // on anything but a file download changes nothing.
  static void expect_ranges_by_the_rfc(const std::string& url, const std::string& whole) {
    const std::string L = std::to_string(whole.size());
    const auto get = [&](const std::string& range) { return client().Get(url, {{"Range", range}}); };
    for (const auto& [range, first, last] :
         {std::tuple<std::string, std::size_t, std::size_t>{"bytes=0-3", 0, 3},
          {"bytes=2-", 2, whole.size() - 1},
          {"bytes=-5", whole.size() - 5, whole.size() - 1},
          {"BYTES = 1-1", 1, 1},
          {"bytes=0-99999999999999999999", 0, whole.size() - 1},
          {"bytes=3-" + std::to_string(whole.size() + 5), 3, whole.size() - 1}}) {
      auto res = get(range);
      ASSERT_TRUE(res);
      EXPECT_EQ(res->status, 206) << range;
      EXPECT_EQ(res->get_header_value("Content-Range"),
                "bytes " + std::to_string(first) + "-" + std::to_string(last) + "/" + L)
          << range;
      EXPECT_EQ(res->body, whole.substr(first, last - first + 1)) << range;
      EXPECT_EQ(res->get_header_value("Content-Length"), std::to_string(last - first + 1)) << range;
    }
    for (const std::string& range : std::vector<std::string>{
             "bytes=99999999-", "bytes=" + L + "-", "bytes=" + L + "-" + std::to_string(whole.size() + 5),
             std::string("bytes=-0")}) {
      auto res = get(range);
      ASSERT_TRUE(res);
      EXPECT_EQ(res->status, 416) << range;
      EXPECT_EQ(res->get_header_value("Content-Range"), "bytes */" + L) << range;
      EXPECT_EQ(field(problem(res)), "Range") << range;
    }
    // Ignored: another unit, invalid syntax, several ranges (this server's policy: the whole file).
    for (const std::string& range : std::vector<std::string>{std::string("items=0-1"), "bytes=5-2",
                                                             "bytes=x-1", "bytes=0-1, 4-5", "bytes="}) {
      auto res = get(range);
      ASSERT_TRUE(res);
      EXPECT_EQ(res->status, 200) << range;
      EXPECT_EQ(res->body, whole) << range;
      EXPECT_FALSE(res->has_header("Content-Range")) << range;
    }
    // An If-Range is never matched here (no validator is sent): the whole file.
    auto conditional = client().Get(url, {{"Range", "bytes=0-3"}, {"If-Range", "\"x\""}});
    EXPECT_EQ(conditional->status, 200);
    EXPECT_EQ(conditional->body, whole);
    // Not a file download: a 404's and a session's answers keep their status and whole body.
    auto missing = client().Get("/api/v1/recordings/0123456789abcdef/file", {{"Range", "bytes=0-10"}});
    EXPECT_EQ(missing->status, 404);
    EXPECT_FALSE(missing->has_header("Content-Range"));
    EXPECT_TRUE(json::accept(missing->body)) << missing->body;
    auto health = client().Get("/api/v1/health", {{"Range", "bytes=0-3"}});
    EXPECT_EQ(health->status, 200);
    EXPECT_FALSE(health->has_header("Content-Range"));
    EXPECT_TRUE(json::accept(health->body)) << health->body;
  }

  static inline std::map<std::string, Running> servers_;
  static inline int port_ = 0;  // the server of the test's parameter
};

// A long recording keeps the recording thread busy, so the next one is queued; it then runs and
// is done, its progress never going back; the file comes with its type and a download name.
TEST_P(Recording, QueuedRunningDoneWithMonotoneProgressThenTheFile) {
  const std::string id = session();
  auto first = post(id, {{"t_end", 1.6}, {"fps", 25}, {"width", 128}, {"height", 96}, {"format", "png-zip"}});
  ASSERT_EQ(first->status, 202) << first->body;
  auto second = post(
      id, {{"t_start", 0.5}, {"t_end", 1.0}, {"fps", 10}, {"width", 64}, {"height", 48}, {"format", "gif"}});
  ASSERT_EQ(second->status, 202) << second->body;
  const json created = json::parse(second->body);
  EXPECT_EQ(created["status"], "queued");
  EXPECT_EQ(created["progress"], 0.0);
  EXPECT_EQ(created["frames"], 5);
  EXPECT_EQ(second->get_header_value("Location"), created["url"]);
  // The first (40 frames) is seen running while the second waits; the second's own run (5 tiny
  // frames) may be shorter than one poll.
  const std::string first_url = json::parse(first->body)["url"];
  std::string first_status = "queued";
  for (int i = 0; i < 2000 && first_status == "queued"; ++i) {
    first_status = json::parse(client().Get(first_url)->body)["status"];
    if (first_status == "queued") std::this_thread::sleep_for(2ms);
  }
  EXPECT_EQ(first_status, "running");
  EXPECT_EQ(json::parse(client().Get(created["url"].get<std::string>())->body)["status"], "queued");
  const auto seen = follow(created["url"]);
  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.back().first, "done");
  EXPECT_EQ(seen.back().second, 1.0);
  const std::vector<std::string> order{"queued", "running", "done"};
  std::size_t at = 0;
  double progress = 0;
  for (const auto& [status, p] : seen) {
    while (at < order.size() && order[at] != status) ++at;
    ASSERT_LT(at, order.size()) << "status went back to " << status;
    EXPECT_GE(p, progress) << status;
    progress = p;
  }
  auto file = client().Get(created["file"].get<std::string>());
  ASSERT_EQ(file->status, 200);
  EXPECT_EQ(file->get_header_value("Content-Type"), "image/gif");
  EXPECT_EQ(file->body.substr(0, 6), "GIF89a");
  EXPECT_NE(file->get_header_value("Content-Disposition").find("attachment; filename=\"spinfold-"),
            std::string::npos);
  EXPECT_NE(file->get_header_value("Content-Disposition").find("-t0.5-1.gif\""), std::string::npos);
  EXPECT_EQ(json::parse(client().Get(created["url"].get<std::string>())->body)["bytes"], file->body.size());
  expect_ranges_by_the_rfc(created["file"].get<std::string>(), file->body);
  EXPECT_EQ(follow(json::parse(first->body)["url"]).back().first, "done");
  EXPECT_EQ(client().Delete(created["url"].get<std::string>())->status, 204);  // deleted with its file
  EXPECT_EQ(client().Get(created["url"].get<std::string>())->status, 404);
  EXPECT_EQ(client().Get(created["file"].get<std::string>())->status, 404);
}

TEST_P(Recording, CancelStopsItAndTheFileIsNeverThere) {
  const std::string id = session();
  auto res = post(id, {{"t_end", 4.0}, {"fps", 25}, {"width", 128}, {"height", 96}, {"format", "webm"}});
  ASSERT_EQ(res->status, 202) << res->body;
  const std::string url = json::parse(res->body)["url"];
  for (int i = 0; i < 2000 && json::parse(client().Get(url)->body)["status"] == "queued"; ++i)
    std::this_thread::sleep_for(5ms);
  EXPECT_EQ(json::parse(client().Get(url)->body)["status"], "running");  // 100 frames: it runs a while
  auto cancelled = client().Delete(url);
  ASSERT_EQ(cancelled->status, 200) << cancelled->body;
  EXPECT_EQ(json::parse(cancelled->body)["status"], "cancelled");
  EXPECT_EQ(follow(url).back().first, "cancelled");
  auto file = client().Get(url + "/file");
  EXPECT_EQ(file->status, 409);
  EXPECT_EQ(field(problem(file)), "status");
  EXPECT_EQ(client().Delete(url)->status, 204);
  // The recording thread moved on: the next recording is done.
  auto next = post(id, {{"t_end", 0.2}, {"fps", 10}, {"width", 64}, {"height", 48}, {"format", "webm"}});
  ASSERT_EQ(next->status, 202) << next->body;
  EXPECT_EQ(follow(json::parse(next->body)["url"]).back().first, "done");
}

TEST_P(Recording, AFailureSaysWhy) {
  // Reaching t = 50 takes more step attempts than limits.max_steps (3000) allows per frame.
  auto res = post(
      session(),
      {{"t_start", 50}, {"t_end", 51}, {"fps", 2}, {"width", 64}, {"height", 48}, {"format", "png-zip"}});
  ASSERT_EQ(res->status, 202) << res->body;
  const std::string url = json::parse(res->body)["url"];
  EXPECT_EQ(follow(url).back().first, "failed");
  const json r = json::parse(client().Get(url)->body);
  EXPECT_NE(r["reason"].get<std::string>().find("the run stopped at t = "), std::string::npos) << r;
  EXPECT_NE(r["reason"].get<std::string>().find("step limit"), std::string::npos) << r;
  EXPECT_NE(client().Get(url + "/file")->body.find("the recording failed"), std::string::npos);
}

TEST_P(Recording, LimitsAndBadFieldsAreRefusedByName) {
  const std::string id = session();
  const json ok{{"t_end", 1.0}, {"width", 64}, {"height", 48}, {"format", "gif"}};
  const auto refused = [&](json patch, int status, const std::string& name) {
    json body = ok;
    body.merge_patch(patch);
    auto res = post(id, body);
    ASSERT_EQ(res->status, status) << body << " " << res->body;
    EXPECT_EQ(res->get_header_value("Content-Type"), "application/problem+json");
    EXPECT_EQ(field(problem(res)), name) << res->body;
  };
  refused({{"t_end", 10.0}, {"fps", 30}}, 422, "t_end");      // 300 frames > 120
  refused({{"width", 256}, {"height", 192}}, 422, "width");   // over 128 × 96 pixels
  refused({{"width", 65}, {"format", "mp4"}}, 422, "width");  // 4:2:0 needs even sides
  refused({{"format", "avi"}}, 422, "format");
  refused({{"fps", 0}}, 422, "fps");
  refused({{"t_start", 2.0}}, 422, "t_end");
  refused({{"view", "disk"}, {"layers", "surface,sparkles"}}, 422, "layers");
  refused({{"colour", "red"}}, 422, "colour");
  json no_end = ok;
  no_end.erase("t_end");
  auto missing = post(id, no_end);
  EXPECT_EQ(missing->status, 422);
  EXPECT_EQ(field(problem(missing)), "t_end");
  EXPECT_EQ(post("nosuchsession", ok)->status, 404);
  // Two at once per client (limits.max_recordings_per_client); the third waits its turn: 429.
  std::vector<std::string> urls;
  for (int i = 0; i < 2; ++i) {
    auto res = post(id, {{"t_end", 4.0}, {"fps", 25}, {"width", 128}, {"height", 96}, {"format", "png-zip"}});
    ASSERT_EQ(res->status, 202) << res->body;
    urls.push_back(json::parse(res->body)["url"]);
  }
  auto third = post(id, ok);
  ASSERT_EQ(third->status, 429) << third->body;
  EXPECT_EQ(field(problem(third)), "limits.max_recordings_per_client");
  EXPECT_FALSE(third->get_header_value("Retry-After").empty());
  for (const std::string& url : urls) client().Delete(url);
  EXPECT_EQ(client().Get("/api/v1/recordings/nosuchrecording")->status, 404);
}

// The recording replays a copy: the session's state, timeline, version and frame are as they were.
TEST_P(Recording, TheLiveSessionIsUnchangedByARecordingOfIt) {
  const std::string id = session();
  auto c = client();
  c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 0.5})", "application/json");
  ASSERT_EQ(c.Patch("/api/v1/sessions/" + id, R"({"body": {"mass": 2}})", "application/json")->status, 200);
  c.Post("/api/v1/sessions/" + id + "/advance", R"({"until": 0.8})", "application/json");
  const std::string before = c.Get("/api/v1/sessions/" + id)->body;
  const std::string etag =
      c.Get("/api/v1/sessions/" + id + "/frame.png?width=64&height=48")->get_header_value("ETag");
  auto res = post(
      id, {{"t_start", 0.2}, {"t_end", 1.4}, {"fps", 5}, {"width", 64}, {"height", 48}, {"format", "gif"}});
  ASSERT_EQ(res->status, 202) << res->body;
  EXPECT_EQ(follow(json::parse(res->body)["url"]).back().first, "done");  // through the change, past now
  EXPECT_EQ(c.Get("/api/v1/sessions/" + id)->body, before);
  EXPECT_EQ(c.Get("/api/v1/sessions/" + id + "/frame.png?width=64&height=48")->get_header_value("ETag"),
            etag);
}

INSTANTIATE_TEST_SUITE_P(Stores, Recording, testing::Values("memory", "sqlite", "postgresql"),
                         [](const testing::TestParamInfo<std::string>& p) { return p.param; });

// Two replicas on one store (in one process here; tests/server/store_test.cpp and
// tests/front/hosts_test.py do it with processes and hosts): each answers for the other's recordings.
class RecordingAcrossReplicas : public Recording {
 protected:
  void SetUp() override {
    if (GetParam() == "postgresql" && spinfold::test::postgres_dir().empty())
      GTEST_SKIP() << "no PostgreSQL for this run (ctest's server_tests_postgres starts one)";
    ServerOptions o = options();
    o.limits.max_recording_frames = 3600;
    o.limits.recording_heartbeat = 100ms;
    o.limits.recording_owner_lost = std::chrono::seconds(1);
    if (!servers_.count("a-" + GetParam())) {
      Running& a = start("a-" + GetParam(), GetParam(), o);
      start("b-" + GetParam(), GetParam(), o, a.store.get());
    }
    store_ = servers_["a-" + GetParam()].store.get();
    ASSERT_GT(port("a"), 0);
    ASSERT_GT(port("b"), 0);
  }
  int port(const std::string& replica) const { return servers_[replica + "-" + GetParam()].port; }
  httplib::Client on(const std::string& replica) const {
    httplib::Client c("127.0.0.1", port(replica));
    c.set_read_timeout(60, 0);
    return c;
  }
  json follow_on(const std::string& replica, const std::string& url) const {
    json r;
    for (int i = 0; i < 6000; ++i) {
      auto res = on(replica).Get(url);
      EXPECT_EQ(res->status, 200) << res->body;
      r = json::parse(res->body);
      if (r["status"] != "queued" && r["status"] != "running") break;
      std::this_thread::sleep_for(5ms);
    }
    return r;
  }
  spinfold::test::Backend* store_ = nullptr;
};

TEST_P(RecordingAcrossReplicas, TheOtherReplicaServesItsStatusAndTheFileByteForByte) {
  const json clip{{"t_start", 0.5}, {"t_end", 1.7}, {"fps", 10},
                  {"width", 64},    {"height", 48}, {"format", "gif"}};
  auto created =
      on("a").Post("/api/v1/sessions", R"({"preset": "spin_vs_geodesic_sphere"})", "application/json");
  ASSERT_EQ(created->status, 201);
  const std::string session = json::parse(created->body)["id"];
  auto res = on("a").Post("/api/v1/sessions/" + session + "/recordings", clip.dump(), "application/json");
  ASSERT_EQ(res->status, 202) << res->body;
  const std::string url = json::parse(res->body)["url"];
  const json done = follow_on("b", url);
  EXPECT_EQ(done["status"], "done") << done;
  EXPECT_EQ(done, json::parse(on("a").Get(url)->body)) << "both replicas say the same";
  auto file = on("b").Get(url + "/file");
  ASSERT_EQ(file->status, 200);
  EXPECT_EQ(file->get_header_value("Content-Type"), "image/gif");
  EXPECT_EQ(file->body.size(), done["bytes"].get<std::size_t>());
  EXPECT_EQ(file->get_header_value("Content-Disposition"),
            on("a").Get(url + "/file")->get_header_value("Content-Disposition"));
  // The independent check: the same clip recorded by a server without a store, from its own file on
  // disk (no store, no chunks), has the same bytes.
  if (!servers_.count("memory")) start("memory", "memory", options());
  httplib::Client alone("127.0.0.1", servers_["memory"].port);
  auto there = alone.Post("/api/v1/sessions", R"({"preset": "spin_vs_geodesic_sphere"})", "application/json");
  const std::string other = json::parse(there->body)["id"];
  auto local = alone.Post("/api/v1/sessions/" + other + "/recordings", clip.dump(), "application/json");
  ASSERT_EQ(local->status, 202) << local->body;
  const std::string local_url = json::parse(local->body)["url"];
  for (int i = 0; i < 6000 && json::parse(alone.Get(local_url)->body)["status"] != "done"; ++i)
    std::this_thread::sleep_for(5ms);
  EXPECT_TRUE(alone.Get(local_url + "/file")->body == file->body)
      << "the store's file differs from the disk's";
  // Deleted through A: gone on B, file and all.
  EXPECT_EQ(on("a").Delete(url)->status, 204);
  EXPECT_EQ(on("b").Get(url)->status, 404);
  EXPECT_EQ(on("b").Get(url + "/file")->status, 404);
  EXPECT_EQ(on("b").Delete(url)->status, 404);
}

TEST_P(RecordingAcrossReplicas, ACancelThroughTheOtherReplicaStopsTheJobWhereItRuns) {
  auto created =
      on("a").Post("/api/v1/sessions", R"({"preset": "spin_vs_geodesic_sphere"})", "application/json");
  const std::string session = json::parse(created->body)["id"];
  // 1,800 frames: minutes of work if it were not stopped.
  const json long_clip{{"t_end", 60.0}, {"fps", 30}, {"width", 64}, {"height", 48}, {"format", "webm"}};
  auto res =
      on("a").Post("/api/v1/sessions/" + session + "/recordings", long_clip.dump(), "application/json");
  ASSERT_EQ(res->status, 202) << res->body;
  const std::string url = json::parse(res->body)["url"];
  for (int i = 0; i < 4000 && json::parse(on("b").Get(url)->body)["status"] != "running"; ++i)
    std::this_thread::sleep_for(5ms);
  auto cancelled = on("b").Delete(url);
  ASSERT_EQ(cancelled->status, 200) << cancelled->body;
  EXPECT_EQ(json::parse(cancelled->body)["status"], "cancelled");
  // A's only recording thread is free again: a short recording there is done well before the long
  // one could have been.
  const auto start = std::chrono::steady_clock::now();
  auto next =
      on("a").Post("/api/v1/sessions/" + session + "/recordings",
                   json{{"t_end", 0.2}, {"fps", 10}, {"width", 64}, {"height", 48}, {"format", "gif"}}.dump(),
                   "application/json");
  ASSERT_EQ(next->status, 202) << next->body;
  EXPECT_EQ(follow_on("a", json::parse(next->body)["url"])["status"], "done");
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const json stopped = json::parse(on("a").Get(url)->body);
  EXPECT_EQ(stopped["status"], "cancelled") << "the owner did not overwrite the cancel";
  EXPECT_LT(stopped["progress"].get<double>(), 1.0);
  EXPECT_LT(took, 30.0);
}

TEST_P(RecordingAcrossReplicas, ARecordingWhoseReplicaWentSilentFailsSayingWhy) {
  // A row as a replica that was lost (SIGKILL, its host gone) leaves it: running, never touched again.
  const auto db = store_->open();
  ASSERT_TRUE(db->save_recording({.id = "lostrecording",
                                  .owner = "gone:1:x",
                                  .status = "queued",
                                  .json = R"({"id":"lostrecording","status":"queued","progress":0})"}));
  ASSERT_TRUE(db->save_recording({.id = "lostrecording",
                                  .owner = "gone:1:x",
                                  .status = "running",
                                  .json = R"({"id":"lostrecording","status":"running","progress":0.25})"}));
  const std::string url = "/api/v1/recordings/lostrecording";
  EXPECT_EQ(json::parse(on("b").Get(url)->body)["status"], "running");
  std::this_thread::sleep_for(1300ms);  // past limits.recording_owner_lost (1 s here)
  for (const char* replica : {"a", "b"}) {
    const json r = json::parse(on(replica).Get(url)->body);
    EXPECT_EQ(r["status"], "failed") << r;
    EXPECT_NE(r.value("reason", "").find("stopped answering"), std::string::npos) << r;
    EXPECT_EQ(on(replica).Get(url + "/file")->status, 409);
  }
  // The replicas' sweep wrote it so in the store too (every heartbeat, 0.1 s here).
  EXPECT_EQ(db->load_recording("lostrecording")->status, "failed");
}

INSTANTIATE_TEST_SUITE_P(Stores, RecordingAcrossReplicas, testing::Values("sqlite", "postgresql"),
                         [](const testing::TestParamInfo<std::string>& p) { return p.param; });

}  // namespace
}  // namespace spinfold::server
