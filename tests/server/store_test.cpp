// The durable session store, tested on the real binary: `spinfold serve --data-dir DIR` processes
// killed with SIGKILL and restarted, two processes sharing one directory, a damaged database, SIGTERM.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "server/session_db.h"

// After Eigen (none here, but the same order as the other server tests): httplib.h brings <resolv.h>.
#include <httplib.h>

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
  explicit Server(const std::vector<std::string>& args) {
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
    c.set_read_timeout(30, 0);
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

TEST(Store, KillNineAndRestartGiveTheSameSessionsBitForBit) {
  TempDir dir;
  std::string id, played;
  Seen before;
  {
    Server a(store_args(dir));
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
  Server b(store_args(dir));
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

TEST(Store, TwoServersOnOneDirectoryServeTheSameSessions) {
  TempDir dir;
  Server a(store_args(dir));
  Server b(store_args(dir));
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

// A row is read as strictly as a request body: a NUL byte and what follows it, text after the value
// or a second value make it a row that is not restored (said on stderr), rather than one read in
// part; a sound row beside them is restored.
TEST(Store, ARowOfMoreThanOneJsonValueIsNotRestored) {
  TempDir dir;
  const std::string nul(1, '\0');
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"{}" + nul + "garbage", "[]"}, {"{} {}", "[]"}, {"{}", "[] x"}, {"{}", "[]" + nul}};
  {
    spinfold::server::SessionDb db((dir.path / "data").string());
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

}  // namespace
