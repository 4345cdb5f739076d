// The durable session store, tested on the real binary: `spinfold serve --data-dir DIR` processes
// killed with SIGKILL and restarted, two processes sharing one directory, a damaged database, SIGTERM.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "server/store/sqlite_store.h"
#include "server/store/store.h"

// After Eigen (none here, but the same order as the other server tests): httplib.h brings <resolv.h>.
#include <httplib.h>

#include "tests/render/frame_compare.h"
#include "tests/server/store/test_stores.h"

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const std::string kSessions = "/api/v1/sessions";

// A scratch directory, removed at the end of the test.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "spinfold_store_XXXXXX").string();
    path = mkdtemp(pattern.data());
  }
  ~TempDir() { fs::remove_all(path); }
};

// `spinfold serve --port 0 ARGS…` as a child process: the port it printed, its stderr, its exit.
class Server {
 public:
  // `env`: NAME=VALUE settings added to the child's environment (another CPU's, for one).
  explicit Server(const std::vector<std::string>& args, const std::vector<std::string>& env = {}) {
    err_file_ = fs::temp_directory_path() /
                ("spinfold_store_err_" + std::to_string(getpid()) + "_" + std::to_string(++count_));
    int out[2];
    EXPECT_EQ(pipe(out), 0);
    pid_ = fork();
    if (pid_ == 0) {
      dup2(out[1], 1);
      const int err = open(err_file_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(err, 2);
      close(out[0]);
      for (const std::string& setting : env) putenv(strdup(setting.c_str()));
      std::vector<std::string> all = {SPINFOLD_BINARY, "serve", "--port", "0"};
      all.insert(all.end(), args.begin(), args.end());
      std::vector<char*> argv;
      for (std::string& a : all) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(argv[0], argv.data());
      _exit(127);
    }
    close(out[1]);
    // The first line: "Spinfold VERSION serving on http://127.0.0.1:PORT/" (nothing when it fails).
    std::string line;
    char c;
    while (read(out[0], &c, 1) == 1 && c != '\n') line += c;
    out_ = out[0];
    const auto colon = line.rfind(':');
    if (colon != std::string::npos) port_ = std::atoi(line.c_str() + colon + 1);
  }
  ~Server() {
    if (pid_ > 0 && !exit_code_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    close(out_);
    fs::remove(err_file_);
  }
  int port() const { return port_; }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(120, 0);  // the sanitizer builds on a loaded 2-core machine: minutes, not seconds
    return c;
  }
  // Sends the signal and waits for the exit: the exit code (128 + signal when killed).
  int stop(int signal) {
    kill(pid_, signal);
    return wait();
  }
  int wait() {
    int status = 0;
    waitpid(pid_, &status, 0);
    exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return *exit_code_;
  }
  std::string err() const {
    std::ifstream in(err_file_);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

 private:
  static inline int count_ = 0;
  pid_t pid_ = -1;
  int out_ = -1;
  int port_ = 0;
  std::optional<int> exit_code_;
  fs::path err_file_;
};

std::vector<std::string> store_args(const TempDir& dir) {
  return {"--data-dir", (dir.path / "data").string()};
}

httplib::Result post(const Server& s, const std::string& path, const json& body) {
  return s.client().Post(path.c_str(), body.dump(), "application/json");
}

std::string create(const Server& s, const json& body) {
  const auto res = post(s, kSessions, body);
  EXPECT_TRUE(res);
  EXPECT_EQ(res->status, 201) << res->body;
  return json::parse(res->body)["id"];
}

// The GET body of a session (200 expected) and its frame's bytes.
struct Seen {
  std::string session;
  std::string frame;
};

Seen look(const Server& s, const std::string& id) {
  auto c = s.client();
  const auto session = c.Get((kSessions + "/" + id).c_str());
  const auto frame = c.Get((kSessions + "/" + id + "/frame.png?width=160&height=120").c_str());
  EXPECT_TRUE(session && frame);
  if (!session || !frame) return {};
  EXPECT_EQ(session->status, 200) << session->body;
  EXPECT_EQ(frame->status, 200);
  return {session->body, frame->body};
}

int status_of(const Server& s, const std::string& id) {
  const auto res = s.client().Get((kSessions + "/" + id).c_str());
  return res ? res->status : -1;
}

// The runs a session goes through here: an adaptive integrator, advances, a continuing change.
void work_on(const Server& s, const std::string& id) {
  ASSERT_EQ(post(s, kSessions + "/" + id + "/advance", {{"until", 0.7}})->status, 200);
  const auto patch = s.client().Patch((kSessions + "/" + id).c_str(), R"({"body": {"mass": 1.7}})",
                                      "application/merge-patch+json");
  ASSERT_TRUE(patch);
  ASSERT_EQ(patch->status, 200) << patch->body;
  EXPECT_EQ(json::parse(patch->body)["change"]["kind"], "continued");
  ASSERT_EQ(post(s, kSessions + "/" + id + "/advance", {{"steps", 37}})->status, 200);
}

// The store tests run against each store: SQLite in a directory, PostgreSQL (a database on the server
// ctest starts: server_tests_postgres).
class StoreOn : public testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (GetParam() == "postgresql" && spinfold::test::postgres_dir().empty())
      GTEST_SKIP() << "no PostgreSQL for this run (ctest's server_tests_postgres starts one)";
    store_ = std::make_unique<spinfold::test::Backend>(GetParam());
    ASSERT_TRUE(store_->ready());
  }
  std::vector<std::string> args() const { return store_->serve_args(); }
  std::unique_ptr<spinfold::test::Backend> store_;
};

TEST_P(StoreOn, KillNineAndRestartGiveTheSameSessionsBitForBit) {
  std::string id, played;
  Seen before;
  {
    Server a(args());
    ASSERT_GT(a.port(), 0) << a.err();
    id = create(a, {{"preset", "deforming_spin_pseudosphere"}});
    work_on(a, id);
    // Played for a while and paused: the pause stores the time played.
    ASSERT_EQ(post(a, kSessions + "/" + id + "/play", {{"rate", 2}})->status, 200);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    ASSERT_EQ(post(a, kSessions + "/" + id + "/pause", json::object())->status, 200);
    before = look(a, id);
    played = create(a, {{"preset", "spinning_rigid_sphere"}});
    ASSERT_EQ(post(a, kSessions + "/" + played + "/play", json::object())->status, 200);
    std::this_thread::sleep_for(std::chrono::milliseconds(1600));
    EXPECT_EQ(a.stop(SIGKILL), 128 + SIGKILL);
  }
  Server b(args());
  ASSERT_GT(b.port(), 0) << b.err();
  EXPECT_NE(b.err().find("restored"), std::string::npos) << b.err();
  const Seen after = look(b, id);
  EXPECT_EQ(after.session, before.session);  // same id, time, state bits, scene and timeline
  EXPECT_TRUE(after.frame == before.frame) << "the frame's bytes differ";
  // A session killed while playing comes back paused at a time stored in the last second.
  const json first = json::parse(look(b, played).session);
  const double t = first["state"]["t"];
  EXPECT_GE(t, 0.5);
  EXPECT_LE(t, 1.7);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(json::parse(look(b, played).session)["state"]["t"], t);
}

TEST_P(StoreOn, TwoServersOnOneStoreServeTheSameSessions) {
  Server a(args());
  Server b(args());
  ASSERT_GT(a.port(), 0) << a.err();
  ASSERT_GT(b.port(), 0) << b.err();
  const std::string id = create(a, {{"preset", "deforming_spin_pseudosphere"}});
  work_on(a, id);
  EXPECT_EQ(look(b, id).session, look(a, id).session);  // loaded by B from the store
  // Changed on A: B does not serve its stale copy.
  ASSERT_EQ(post(a, kSessions + "/" + id + "/advance", {{"until", 2.5}})->status, 200);
  const Seen on_a = look(a, id);
  const Seen on_b = look(b, id);
  EXPECT_EQ(on_b.session, on_a.session);
  EXPECT_TRUE(on_b.frame == on_a.frame);
  EXPECT_EQ(json::parse(on_b.session)["state"]["t"], 2.5);
  // And back: changed on B, served so by A.
  const auto reset = post(b, kSessions + "/" + id + "/reset", json::object());
  ASSERT_EQ(reset->status, 200);
  EXPECT_EQ(json::parse(look(a, id).session)["state"]["t"], 0.0);
  EXPECT_EQ(look(a, id).session, look(b, id).session);
  // Deleted on A: gone for both.
  ASSERT_EQ(a.client().Delete((kSessions + "/" + id).c_str())->status, 204);
  EXPECT_EQ(status_of(a, id), 404);
  EXPECT_EQ(status_of(b, id), 404);
  EXPECT_EQ(b.client().Delete((kSessions + "/" + id).c_str())->status, 404);
}

// A client's session quota is kept by the replica that created the sessions; those deleted through
// another replica (the front hashes a session's requests elsewhere than its creation) count no more.
TEST_P(StoreOn, SessionsDeletedThroughAnotherReplicaLeaveTheCreatorsQuota) {
  Server a(args());
  Server b(args());
  ASSERT_GT(a.port(), 0) << a.err();
  ASSERT_GT(b.port(), 0) << b.err();
  std::vector<std::string> ids;
  for (int i = 0; i < 48; ++i) ids.push_back(create(a, {{"preset", "spinning_rigid_sphere"}}));
  const auto over = post(a, kSessions, {{"preset", "spinning_rigid_sphere"}});
  ASSERT_TRUE(over);
  EXPECT_EQ(over->status, 429) << "the quota of 48 sessions per client";
  for (const std::string& id : ids) ASSERT_EQ(b.client().Delete((kSessions + "/" + id).c_str())->status, 204);
  const auto again = post(a, kSessions, {{"preset", "spinning_rigid_sphere"}});
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 201) << again->body;
  EXPECT_EQ(status_of(a, ids.front()), 404);
}

INSTANTIATE_TEST_SUITE_P(Stores, StoreOn, testing::Values("sqlite", "postgresql"),
                         [](const testing::TestParamInfo<std::string>& p) { return p.param; });

// The database goes away for a few seconds: changes answer 503 problem+json and nothing is
// acknowledged that was not committed; a session only the store knows is 503, not 404; when the
// database is back, the same server serves and stores again, and a new server restores it all.
TEST(PostgresServe, ChangesAnswer503WhileTheDatabaseIsAwayAndNothingIsLost) {
  if (spinfold::test::postgres_dir().empty()) GTEST_SKIP() << "no PostgreSQL for this run";
  spinfold::test::Backend store("postgresql");
  ASSERT_TRUE(store.ready());
  std::string id, other;
  {
    Server a(store.serve_args());
    Server b(store.serve_args());
    ASSERT_GT(a.port(), 0) << a.err();
    ASSERT_GT(b.port(), 0) << b.err();
    id = create(a, {{"preset", "deforming_spin_pseudosphere"}});
    work_on(a, id);
    other = create(b, {{"preset", "spinning_rigid_sphere"}});
    const std::string before = look(a, id).session;
    ASSERT_EQ(std::system(spinfold::test::fixture("down").c_str()), 0);
    const auto patch = a.client().Patch((kSessions + "/" + id).c_str(), R"({"body": {"mass": 2.5}})",
                                        "application/merge-patch+json");
    ASSERT_TRUE(patch);
    EXPECT_EQ(patch->status, 503) << patch->body;
    EXPECT_EQ(patch->get_header_value("Content-Type"), "application/problem+json");
    EXPECT_EQ(post(a, kSessions, {{"preset", "spinning_rigid_sphere"}})->status, 503);
    EXPECT_EQ(status_of(a, other), 503) << "a session the store holds is not unknown";
    ASSERT_EQ(std::system(spinfold::test::fixture("up").c_str()), 0);
    // Back within the reconnection backoff (at most 5 s).
    int status = 0;
    for (int i = 0; i < 80 && status != 200; ++i) {
      status = status_of(a, other);
      if (status != 200) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    ASSERT_EQ(status, 200);
    EXPECT_EQ(look(a, id).session, before) << "the refused change must not show";
    EXPECT_EQ(look(b, id).session, before);
    const auto again = a.client().Patch((kSessions + "/" + id).c_str(), R"({"body": {"mass": 2.5}})",
                                        "application/merge-patch+json");
    ASSERT_TRUE(again);
    EXPECT_EQ(again->status, 200) << again->body;
    EXPECT_EQ(look(b, id).session, look(a, id).session);
  }
  Server c(store.serve_args());
  ASSERT_GT(c.port(), 0) << c.err();
  EXPECT_EQ(json::parse(look(c, id).session)["current"]["body"]["mass"], 2.5);
  EXPECT_EQ(status_of(c, other), 200);
}

// A row is read as strictly as a request body: a NUL byte and what follows it, text after the value
// or a second value make it a row that is not restored (said on stderr), rather than one read in
// part; a sound row beside them is restored.
TEST(Store, ARowOfMoreThanOneJsonValueIsNotRestored) {
  TempDir dir;
  const std::string nul(1, '\0');
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"{}" + nul + "garbage", "[]"}, {"{} {}", "[]"}, {"{}", "[] x"}, {"{}", "[]" + nul}};
  {
    spinfold::server::SqliteStore db((dir.path / "data").string());
    ASSERT_GT(db.save({.id = "GoodGoodGoodGoodGoodGo", .scene = "{}", .timeline = "[]"}), 0);
    for (std::size_t i = 0; i < bad.size(); ++i)
      ASSERT_GT(db.save({.id = "BadRowBadRowBadRow000" + std::to_string(i),
                         .scene = bad[i].first,
                         .timeline = bad[i].second}),
                0);
  }
  Server server(store_args(dir));
  ASSERT_GT(server.port(), 0) << server.err();
  EXPECT_EQ(status_of(server, "GoodGoodGoodGoodGoodGo"), 200);
  for (std::size_t i = 0; i < bad.size(); ++i)
    EXPECT_EQ(status_of(server, "BadRowBadRowBadRow000" + std::to_string(i)), 404) << i;
  EXPECT_NE(server.err().find("cannot be restored: malformed JSON: a NUL byte"), std::string::npos)
      << server.err();
  EXPECT_NE(server.err().find("restored 1 sessions"), std::string::npos) << server.err();
}

TEST(Store, ADamagedDatabaseOrAnUnwritableDirectoryIsAStartError) {
  TempDir dir;
  fs::create_directories(dir.path / "data");
  std::ofstream(dir.path / "data" / "sessions.db") << std::string(8192, 'x');
  Server damaged(store_args(dir));
  EXPECT_EQ(damaged.port(), 0);
  EXPECT_EQ(damaged.wait(), 2);
  EXPECT_NE(damaged.err().find("sessions.db"), std::string::npos) << damaged.err();
  EXPECT_NE(damaged.err().find("not a database"), std::string::npos) << damaged.err();

  std::ofstream(dir.path / "file") << "a file, not a directory";
  Server unwritable({"--data-dir", (dir.path / "file" / "data").string()});
  EXPECT_EQ(unwritable.wait(), 2);
  EXPECT_NE(unwritable.err().find("data directory"), std::string::npos) << unwritable.err();
}

TEST(Store, SigtermEndsStreamsStoresAndExitsWithinTwoSeconds) {
  TempDir dir;
  std::string id;
  {
    Server a(store_args(dir));
    ASSERT_GT(a.port(), 0) << a.err();
    id = create(a, {{"preset", "spinning_rigid_sphere"}});
    ASSERT_EQ(post(a, kSessions + "/" + id + "/play", json::object())->status, 200);
    bool streamed = false;
    std::thread stream([&] {
      auto c = a.client();
      c.Get((kSessions + "/" + id + "/events").c_str(), [&](const char*, std::size_t) {
        streamed = true;
        return true;
      });
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(400));
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(a.stop(SIGTERM), 0) << a.err();
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
    stream.join();
    EXPECT_TRUE(streamed);
  }
  // The time played up to the signal was stored.
  Server b(store_args(dir));
  ASSERT_GT(b.port(), 0) << b.err();
  EXPECT_GE(json::parse(look(b, id).session)["state"]["t"].get<double>(), 0.35);
}

// A replica on another CPU: glibc's libm without its FMA/AVX2 variants (the tunable that hides them;
// glibc 2.36 takes the bare names) and llvmpipe compiling for SSE4.1. Its replay of a session differs
// in the last bits (docs/performance.md, "Across CPUs"); nothing that crosses processes may rely on
// those bits.
const std::vector<std::string> kOtherCpu = {"GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA,-AVX",
                                            "GALLIUM_OVERRIDE_CPU_CAPS=sse4.1"};

// The frame's ETag, or what a conditional GET with `etag` answers (200 or 304).
httplib::Result frame(const Server& s, const std::string& id, const std::string& if_none_match = "") {
  httplib::Headers headers;
  if (!if_none_match.empty()) headers.emplace("If-None-Match", if_none_match);
  return s.client().Get((kSessions + "/" + id + "/frame.png?width=160&height=120").c_str(), headers);
}

// Two states of one session: the same time, scene and timeline; numbers within `bound` (relative).
// Returns how many numbers differ at all (0 on one CPU class).
int expect_same_state(const std::string& a_text, const std::string& b_text, double bound) {
  int differing = 0;
  const json a = json::parse(a_text), b = json::parse(b_text);
  EXPECT_EQ(a["state"]["t"], b["state"]["t"]);
  EXPECT_EQ(a["scene"], b["scene"]);
  EXPECT_EQ(a["timeline"], b["timeline"]);
  const auto compare = [&](const json& x, const json& y, const std::string& at, const auto& self) -> void {
    if (x.is_number_float() && y.is_number_float()) {
      const double u = x, v = y;
      differing += u != v;
      EXPECT_LE(std::abs(u - v), bound * std::max(1.0, std::abs(u))) << at << ": " << u << " against " << v;
    } else if (x.is_object() && y.is_object()) {
      for (const auto& [key, value] : x.items())
        if (y.contains(key)) self(value, y[key], at + "." + key, self);
    } else if (x.is_array() && y.is_array() && x.size() == y.size()) {
      for (std::size_t i = 0; i < x.size(); ++i) self(x[i], y[i], at + "[" + std::to_string(i) + "]", self);
    } else {
      EXPECT_EQ(x, y) << at;
    }
  };
  compare(a["state"], b["state"], "state", compare);
  return differing;
}

void expect_same_picture(const std::string& a, const std::string& b) {
  using spinfold::test::decode_png;
  const auto pa = decode_png({a.begin(), a.end()}), pb = decode_png({b.begin(), b.end()});
  ASSERT_TRUE(pa && pb);
  const spinfold::test::FrameTolerance tolerance;
  const auto d = spinfold::test::compare_frames(*pa, *pb, tolerance);
  EXPECT_TRUE(spinfold::test::within(d, tolerance)) << spinfold::test::describe(d, tolerance);
}

TEST(Store, AReplicaOnAnotherCpuReplaysSessionsWithoutBreakingEtagsOrVersions) {
  TempDir dir;
  Server a(store_args(dir));
  Server b(store_args(dir), kOtherCpu);
  ASSERT_GT(a.port(), 0) << a.err();
  ASSERT_GT(b.port(), 0) << b.err();
  const std::string id = create(a, {{"preset", "deforming_spin_pseudosphere"}});
  const auto first = frame(a, id);
  ASSERT_EQ(first->status, 200);
  const std::string at_start = first->get_header_value("ETag");
  // Adaptive steps on H² (the closed form would be the same on every CPU), to t = 60.
  const auto patch = a.client().Patch((kSessions + "/" + id).c_str(), R"({"integrator": {"name": "dop853"}})",
                                      "application/merge-patch+json");
  ASSERT_TRUE(patch) << "no answer: " << httplib::to_string(patch.error());
  ASSERT_EQ(patch->status, 200) << patch->body;
  work_on(a, id);
  const auto advanced = post(a, kSessions + "/" + id + "/advance", {{"until", 60}});
  ASSERT_TRUE(advanced) << "no answer: " << httplib::to_string(advanced.error());
  ASSERT_EQ(advanced->status, 200);
  const Seen on_a = look(a, id);
  const std::string etag_a = frame(a, id)->get_header_value("ETag");

  // B replays the session from its row on its CPU: the same session, within the measured bound
  // (1e-12 at t = 100 for dop853), and the same picture within the golden frames' tolerance.
  const Seen on_b = look(b, id);
  const int differing = expect_same_state(on_a.session, on_b.session, 1e-9);
  std::printf("numbers of the state differing between the two CPUs' replays: %d\n", differing);
  expect_same_picture(on_a.frame, on_b.frame);
  // The ETag names the stored state, not the bytes of this CPU's replay: A's is valid at B (a
  // failover keeps the client's frame), weak, since B's bytes may differ within the tolerance.
  EXPECT_EQ(frame(b, id)->get_header_value("ETag"), etag_a);
  EXPECT_EQ(etag_a.rfind("W/\"", 0), 0u) << etag_a;
  EXPECT_EQ(frame(b, id, etag_a)->status, 304);
  // A stale ETag (the state at t = 0) is never a 304 where the state has moved on.
  EXPECT_NE(at_start, etag_a);
  EXPECT_EQ(frame(b, id, at_start)->status, 200);
  EXPECT_EQ(frame(a, id, at_start)->status, 200);

  // Changed on B (from its own replay): A sees the row's new version, rebuilds, and its ETag for the
  // old state no longer matches, on either replica.
  ASSERT_EQ(post(b, kSessions + "/" + id + "/advance", {{"until", 80}})->status, 200);
  const Seen b_later = look(b, id);
  const Seen a_later = look(a, id);
  EXPECT_EQ(json::parse(a_later.session)["state"]["t"], 80.0);
  expect_same_state(b_later.session, a_later.session, 1e-9);
  expect_same_picture(b_later.frame, a_later.frame);
  EXPECT_EQ(frame(a, id, etag_a)->status, 200);
  EXPECT_EQ(frame(b, id, etag_a)->status, 200);
  // And writes keep working from both sides: each names the row version it saw, so neither
  // gets a 409 from the other's write, and both serve the last one.
  const auto patched = a.client().Patch((kSessions + "/" + id).c_str(), R"({"body": {"mass": 1.2}})",
                                        "application/merge-patch+json");
  ASSERT_EQ(patched->status, 200) << patched->body;
  ASSERT_EQ(post(b, kSessions + "/" + id + "/advance", {{"until", 90}})->status, 200);
  ASSERT_EQ(post(a, kSessions + "/" + id + "/advance", {{"until", 100}})->status, 200);
  const Seen a_end = look(a, id), b_end = look(b, id);
  EXPECT_EQ(json::parse(b_end.session)["state"]["t"], 100.0);
  expect_same_state(a_end.session, b_end.session, 1e-9);
  EXPECT_EQ(json::parse(b_end.session)["current"]["body"]["mass"], 1.2);
  const auto tag = frame(a, id)->get_header_value("ETag");
  EXPECT_EQ(frame(b, id, tag)->status, 304);
}

}  // namespace
