// The store conformance suite: every Store (SQLite and PostgreSQL) keeps the same promises.
// PostgreSQL's cases need a server: ctest's server_tests_postgres starts one of its own
// (tests/server/postgres_fixture.sh) and names it in SPINFOLD_TEST_POSTGRES_DIR; without it they skip.
#include "server/store/store.h"

#include <gtest/gtest.h>
#include <libpq-fe.h>
#include <sqlite3.h>
#include <unistd.h>

#include <atomic>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "server/store/postgres_store.h"
#include "tests/server/store/test_stores.h"

namespace {

using spinfold::server::open_store;
using spinfold::server::Store;
using spinfold::server::StoredSession;
using spinfold::server::StoreError;
using spinfold::test::admin;
using spinfold::test::Backend;
using spinfold::test::fixture;
using spinfold::test::postgres_dir;
namespace fs = std::filesystem;

class StoreConformance : public testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (GetParam() == "postgresql" && postgres_dir().empty())
      GTEST_SKIP() << "no PostgreSQL for this run (ctest's server_tests_postgres starts one)";
    backend_ = std::make_unique<Backend>(GetParam());
    ASSERT_TRUE(backend_->ready());
    db_ = backend_->open();
    ASSERT_TRUE(db_);
  }
  std::unique_ptr<Backend> backend_;
  std::unique_ptr<Store> db_;
};

StoredSession row(const std::string& id, double t = 0.0) {
  return {.id = id, .scene = R"({"surface":{"kind":"sphere"}})", .timeline = "[]", .t = t, .rate = 1.0};
}

TEST_P(StoreConformance, TimesComeBackBitForBit) {
  // Times a session reaches: thirds, subnormals, extremes, negative zero, random bit patterns.
  std::vector<double> times = {1.0 / 3.0,
                               0.1,
                               -0.0,
                               std::numeric_limits<double>::denorm_min(),
                               std::numeric_limits<double>::max(),
                               1e-300,
                               2.5,
                               123456.789e10};
  std::mt19937_64 random(27);
  for (int i = 0; i < 200; ++i) {
    const double t = std::bit_cast<double>(random());
    if (std::isfinite(t)) times.push_back(t);
  }
  for (std::size_t i = 0; i < times.size(); ++i) {
    StoredSession r = row(std::string("s").append(std::to_string(i)), times[i]);
    r.rate = times[times.size() - 1 - i];
    ASSERT_EQ(db_->save(r), 1);
  }
  // −0 comes back as +0 from every store (SQLite keeps an integral REAL as an integer; PostgreSQL is
  // made to agree), which no session can tell apart: t ≥ 0, and a rate of ±0 is paused play.
  const auto stored = [](double v) { return std::bit_cast<std::uint64_t>(v == 0.0 ? 0.0 : v); };
  const auto second = backend_->open();  // another process's view of the rows
  for (std::size_t i = 0; i < times.size(); ++i) {
    const auto loaded = second->load(std::string("s").append(std::to_string(i)));
    ASSERT_TRUE(loaded);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(loaded->t), stored(times[i])) << times[i];
    EXPECT_EQ(std::bit_cast<std::uint64_t>(loaded->rate), stored(times[times.size() - 1 - i]));
  }
}

TEST_P(StoreConformance, TextComesBackByteForByte) {
  StoredSession r = row("unicode");
  r.scene = R"({"description":"Sławianowski–Gołubowska: ψ ∈ H², \"quoted\", \\ and \u0000"})";
  r.timeline = R"([{"t":0.5,"patch":{"body":{"mass":1.7}}}])";
  r.playing = true;
  ASSERT_EQ(db_->save(r), 1);
  const auto loaded = backend_->open()->load("unicode");
  ASSERT_TRUE(loaded);
  EXPECT_EQ(loaded->scene, r.scene);
  EXPECT_EQ(loaded->timeline, r.timeline);
  EXPECT_TRUE(loaded->playing);
  EXPECT_EQ(loaded->version, 1);
}

TEST_P(StoreConformance, AWriteNamingAnOldVersionChangesNothing) {
  ASSERT_EQ(db_->save(row("a")), 1);
  EXPECT_EQ(db_->save(row("a")), 0) << "a second insert of one id";
  const auto other = backend_->open();
  StoredSession mine = *db_->load("a");
  StoredSession theirs = *other->load("a");
  theirs.t = 2.0;
  EXPECT_EQ(other->save(theirs), 2);
  mine.t = 3.0;
  EXPECT_EQ(db_->save(mine), 0) << "the lost race must not overwrite";
  EXPECT_EQ(db_->load("a")->t, 2.0);
  EXPECT_EQ(db_->version("a"), 2);
  EXPECT_FALSE(db_->version("missing"));
  EXPECT_FALSE(db_->load("missing"));
}

TEST_P(StoreConformance, ConcurrentWritersLoseNoChange) {
  ASSERT_EQ(db_->save(row("counter")), 1);
  constexpr int kWriters = 4, kEach = 25;
  std::vector<std::thread> threads;
  std::atomic<int> conflicts{0};
  for (int w = 0; w < kWriters; ++w)
    threads.emplace_back([&] {
      const auto db = backend_->open();
      for (int done = 0; done < kEach;) {
        StoredSession r = *db->load("counter");
        r.t += 1.0;  // each write adds one: a lost update would show in the sum
        if (db->save(r) != 0)
          ++done;
        else
          ++conflicts;
      }
    });
  for (auto& t : threads) t.join();
  const auto final_row = db_->load("counter");
  EXPECT_EQ(final_row->t, kWriters * kEach);
  EXPECT_EQ(final_row->version, 1 + kWriters * kEach);
  std::printf("%d conflicts retried\n", conflicts.load());
}

TEST_P(StoreConformance, TouchRemoveCountAndExpire) {
  ASSERT_EQ(db_->save(row("old")), 1);
  ASSERT_EQ(db_->save(row("new")), 1);
  EXPECT_EQ(db_->count(), 2);
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  db_->touch("new");
  EXPECT_EQ(db_->version("new"), 1) << "a touch is not a change";
  db_->expire(std::chrono::seconds(1));  // "old" unused for over a second, "new" just touched
  EXPECT_FALSE(db_->load("old"));
  EXPECT_TRUE(db_->load("new"));
  EXPECT_EQ(db_->count(), 1);
  const auto all = db_->load_all();
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].id, "new");
  EXPECT_TRUE(db_->remove("new"));
  EXPECT_FALSE(db_->remove("new"));
  EXPECT_EQ(db_->count(), 0);
  EXPECT_TRUE(db_->reachable());
}

// Recordings: a row the owner writes while it is active, a cancel from anywhere that is final, a
// file in chunks that comes back byte for byte, a lost owner failed, old rows and orphan files gone.
using spinfold::server::kRecordingChunkBytes;
using spinfold::server::StoredRecording;

StoredRecording recording(const std::string& id, const std::string& status, std::int64_t bytes = 0) {
  return {.id = id,
          .owner = "host:1:abc",
          .status = status,
          .json = nlohmann::json{{"id", id}, {"progress", 0.5}}.dump(),
          .reason = "",
          .bytes = bytes};
}

TEST(SqliteStore, AFileOfSchemaOneIsMigratedKeepingItsSessions) {
  const fs::path dir = fs::temp_directory_path() / ("spinfold_sqlite_v1_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  {
    // Schema 1 as the first SQLite release made it: sessions only.
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open((dir / "sessions.db").c_str(), &db), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(
                  db,
                  "PRAGMA application_id = 1397771846; PRAGMA user_version = 1; "
                  "CREATE TABLE sessions (id TEXT PRIMARY KEY NOT NULL, version INTEGER NOT NULL, "
                  "scene TEXT NOT NULL, timeline TEXT NOT NULL, t REAL NOT NULL, playing INTEGER NOT NULL, "
                  "rate REAL NOT NULL, last_used INTEGER NOT NULL) WITHOUT ROWID; "
                  "INSERT INTO sessions VALUES ('kept', 3, '{}', '[]', 2.5, 0, 1.0, 0)",
                  nullptr, nullptr, nullptr),
              SQLITE_OK);
    sqlite3_close(db);
  }
  {
    const auto db = open_store("", dir.string());
    const auto kept = db->load("kept");
    ASSERT_TRUE(kept);
    EXPECT_EQ(kept->version, 3);
    EXPECT_EQ(kept->t, 2.5);
    EXPECT_TRUE(db->save_recording({.id = "r", .owner = "o", .status = "queued", .json = "{}"}));
  }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((dir / "sessions.db").c_str(), &db), SQLITE_OK);
  sqlite3_stmt* q = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "PRAGMA user_version", -1, &q, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_step(q), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int(q, 0), 2);
  sqlite3_finalize(q);
  sqlite3_close(db);
  fs::remove_all(dir);
}

// Replicas sharing a data directory start together (scripts/front.sh starts them at once): two
// openers of a store that does not exist yet, at the same instant, both open it. (Switching a new
// file to WAL while another connection holds it can be SQLITE_BUSY without the busy handler being
// asked.) Two threads, each with its own connection, as two processes would: SQLite's locks are the
// file's either way.
TEST(SqliteStore, TwoOpeningANewStoreAtOnceBothOpenIt) {
  for (int round = 0; round < 40; ++round) {
    const fs::path dir = fs::temp_directory_path() /
                         ("spinfold_sqlite_race_" + std::to_string(getpid()) + "_" + std::to_string(round));
    fs::remove_all(dir);
    std::atomic<int> waiting{2};
    std::string errors[2];
    std::thread openers[2];
    for (int k = 0; k < 2; ++k)
      openers[k] = std::thread([&, k] {
        for (--waiting; waiting > 0;) std::this_thread::yield();  // both start together
        try {
          open_store("", dir.string());
        } catch (const std::exception& e) {
          errors[k] = e.what();
        }
      });
    for (std::thread& t : openers) t.join();
    EXPECT_EQ(errors[0] + errors[1], "") << "round " << round;
    fs::remove_all(dir);
  }
}

TEST_P(StoreConformance, ARecordingsRowChangesOnlyWhileActive) {
  EXPECT_FALSE(db_->load_recording("r1"));
  ASSERT_TRUE(db_->save_recording(recording("r1", "queued")));
  EXPECT_FALSE(db_->save_recording(recording("ghost", "running"))) << "only a queued row is inserted";
  EXPECT_FALSE(db_->load_recording("ghost"));
  ASSERT_TRUE(db_->save_recording(recording("r1", "running", 1234)));
  const auto second = backend_->open();  // another replica's view
  auto r = second->load_recording("r1");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, "running");
  EXPECT_EQ(r->owner, "host:1:abc");
  EXPECT_EQ(r->json, R"({"id":"r1","progress":0.5})");
  EXPECT_EQ(r->bytes, 1234);
  EXPECT_GE(r->silent_ms, 0);
  EXPECT_LT(r->silent_ms, 5000);
  // Cancelled through the other replica: the owner's next write is refused, and says so.
  EXPECT_TRUE(second->cancel_recording("r1"));
  EXPECT_FALSE(second->cancel_recording("r1")) << "a cancel is final";
  EXPECT_FALSE(db_->save_recording(recording("r1", "running", 2000)));
  EXPECT_FALSE(db_->save_recording(recording("r1", "queued"))) << "not even re-queued";
  r = db_->load_recording("r1");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, "cancelled");
  EXPECT_EQ(r->bytes, 1234);
  // A finished row is not changed either, nor cancelled.
  ASSERT_TRUE(db_->save_recording(recording("r2", "queued")));
  ASSERT_TRUE(db_->save_recording(recording("r2", "done", 10)));
  EXPECT_FALSE(db_->save_recording(recording("r2", "running", 5)));
  EXPECT_FALSE(second->cancel_recording("r2"));
  EXPECT_EQ(db_->load_recording("r2")->status, "done");
  EXPECT_EQ(db_->recording_bytes(), 1234 + 10);
  EXPECT_TRUE(second->remove_recording("r2"));
  EXPECT_FALSE(second->remove_recording("r2"));
  EXPECT_FALSE(db_->load_recording("r2"));
}

TEST_P(StoreConformance, ARecordingsFileComesBackByteForByteInChunks) {
  // Every byte value (NULs included), across a chunk boundary: 2.5 chunks of random bytes.
  std::mt19937_64 random(26);
  std::string file(static_cast<std::size_t>(kRecordingChunkBytes * 5 / 2), '\0');
  for (char& c : file) c = static_cast<char>(random());
  file[0] = '\0';
  ASSERT_TRUE(db_->save_recording(recording("f", "queued")));
  std::int64_t chunks = 0;
  for (std::size_t at = 0; at < file.size(); at += kRecordingChunkBytes)
    db_->save_recording_chunk("f", chunks++, std::string_view(file).substr(at, kRecordingChunkBytes));
  ASSERT_TRUE(db_->save_recording(recording("f", "done", static_cast<std::int64_t>(file.size()))));
  const auto second = backend_->open();
  std::string back;
  for (std::int64_t i = 0;; ++i) {
    const auto chunk = second->load_recording_chunk("f", i);
    if (!chunk) break;
    back += *chunk;
  }
  EXPECT_EQ(chunks, 3);
  EXPECT_TRUE(back == file) << back.size() << " bytes back of " << file.size();
  EXPECT_TRUE(second->remove_recording("f"));
  EXPECT_FALSE(db_->load_recording_chunk("f", 0)) << "the file goes with its row";
}

TEST_P(StoreConformance, ALostOwnersRecordingsFailAndOldOnesAndOrphanFilesGo) {
  ASSERT_TRUE(db_->save_recording(recording("silent", "queued")));
  ASSERT_TRUE(db_->save_recording(recording("old", "queued")));
  ASSERT_TRUE(db_->save_recording(recording("old", "done", 3)));
  db_->save_recording_chunk("old", 0, "abc");
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  ASSERT_TRUE(db_->save_recording(recording("cancelled", "queued")));
  db_->save_recording_chunk("cancelled", 0, "xyz");  // stored while a cancel came
  ASSERT_TRUE(db_->cancel_recording("cancelled"));
  StoredRecording alive = recording("alive", "queued");
  alive.owner = "host:2:def";
  ASSERT_TRUE(db_->save_recording(alive));
  ASSERT_TRUE(db_->save_recording(recording("touched", "queued")));
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  db_->touch_recordings("host:1:abc");  // "silent", "touched": alive again; the finished ones: not
  db_->expire_recordings(std::chrono::seconds(2), std::chrono::seconds(1), "lost");
  EXPECT_EQ(db_->load_recording("silent")->status, "queued") << "touched just now";
  EXPECT_EQ(db_->load_recording("touched")->status, "queued");
  const auto lost = db_->load_recording("alive");  // its owner silent 1.1 s > 1 s
  ASSERT_TRUE(lost);
  EXPECT_EQ(lost->status, "failed");
  EXPECT_EQ(lost->reason, "lost");
  EXPECT_FALSE(db_->load_recording("old")) << "finished 2.2 s ago, older than 2 s";
  EXPECT_FALSE(db_->load_recording_chunk("old", 0));
  EXPECT_TRUE(db_->load_recording("cancelled")) << "not old yet";
  EXPECT_FALSE(db_->load_recording_chunk("cancelled", 0)) << "an orphan file: its row is not done";
  EXPECT_FALSE(db_->save_recording(recording("alive", "running"))) << "a lost row stays failed";
}

INSTANTIATE_TEST_SUITE_P(Stores, StoreConformance, testing::Values("sqlite", "postgresql"),
                         [](const testing::TestParamInfo<std::string>& p) { return p.param; });

// PostgreSQL's own promises: the schema it makes, the URL checks, a database that goes away.
class PostgresStore : public testing::Test {
 protected:
  void SetUp() override {
    if (postgres_dir().empty()) GTEST_SKIP() << "no PostgreSQL for this run";
    backend_ = std::make_unique<Backend>("postgresql");
    ASSERT_TRUE(backend_->ready());
  }
  std::unique_ptr<Backend> backend_;
};

TEST_F(PostgresStore, MakesItsSchemaOnceAndRefusesANewerOne) {
  // Three replicas starting together take turns at the migration (an advisory lock).
  std::vector<std::thread> threads;
  std::atomic<int> failures{0};
  for (int i = 0; i < 3; ++i)
    threads.emplace_back([&] {
      try {
        backend_->open()->count();
      } catch (const StoreError&) {
        ++failures;
      }
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(failures, 0);
  const std::string latest = std::to_string(spinfold::server::PostgresStore::kSchemaVersion);
  EXPECT_TRUE(admin(backend_->url(), "DO $$ BEGIN IF (SELECT count(*) FROM spinfold_schema) <> " + latest +
                                         " OR (SELECT max(version) FROM spinfold_schema) <> " + latest +
                                         " THEN RAISE 'schema'; END IF; END $$"));
  ASSERT_TRUE(admin(backend_->url(), "INSERT INTO spinfold_schema VALUES (99)"));
  try {
    backend_->open();
    ADD_FAILURE() << "a newer schema was opened";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("newer Spinfold (schema 99"), std::string::npos) << e.what();
  }
}

TEST_F(PostgresStore, ADatabaseOfSchemaOneIsMigratedKeepingItsSessions) {
  // Schema 1 as the first PostgreSQL release made it: sessions only.
  ASSERT_TRUE(admin(
      backend_->url(),
      "CREATE TABLE spinfold_schema (version integer NOT NULL); INSERT INTO spinfold_schema VALUES (1); "
      "CREATE TABLE sessions (id text PRIMARY KEY, version bigint NOT NULL, scene text NOT NULL, "
      "timeline text NOT NULL, t double precision NOT NULL, playing boolean NOT NULL, "
      "rate double precision NOT NULL, last_used bigint NOT NULL); "
      "INSERT INTO sessions VALUES ('kept', 3, '{}', '[]', 2.5, false, 1, 0)"));
  const auto db = backend_->open();
  const auto kept = db->load("kept");
  ASSERT_TRUE(kept);
  EXPECT_EQ(kept->version, 3);
  EXPECT_EQ(kept->t, 2.5);
  EXPECT_TRUE(db->save_recording(recording("r", "queued")));
  EXPECT_TRUE(admin(backend_->url(),
                    "DO $$ BEGIN IF (SELECT max(version) FROM spinfold_schema) <> 2 "
                    "THEN RAISE 'not migrated'; END IF; END $$"));
}

TEST_F(PostgresStore, AMalformedUrlIsAnErrorAndMessagesHideThePassword) {
  EXPECT_THROW(open_store("postgresql://[broken", ""), StoreError);
  EXPECT_THROW(open_store("mysql://localhost/x", ""), StoreError);
  EXPECT_EQ(spinfold::server::store_url_for_messages("postgresql://ann:secret@db.example:5433/spinfold"),
            "postgresql://ann@db.example:5433/spinfold");
}

TEST_F(PostgresStore, ADatabaseAwayIsAStoreErrorAtOnceAndTheStoreRecovers) {
  const auto db = backend_->open();
  ASSERT_EQ(db->save(row("kept")), 1);
  ASSERT_EQ(std::system(fixture("down").c_str()), 0);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(db->load("kept"), StoreError);
  StoredSession change = row("kept", 5.0);
  change.version = 1;
  EXPECT_THROW(db->save(change), StoreError);  // not written, not acknowledged
  EXPECT_FALSE(db->reachable());
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5)) << "calls must not hang";
  ASSERT_EQ(std::system(fixture("up").c_str()), 0);
  // Reconnection backs off up to 5 s between tries.
  bool back = false;
  for (int i = 0; i < 80 && !back; ++i) {
    back = db->reachable();
    if (!back) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_TRUE(back);
  const auto loaded = db->load("kept");
  ASSERT_TRUE(loaded);
  EXPECT_EQ(loaded->t, 0.0) << "the refused change must not have been written";
  EXPECT_EQ(db->save(change), 2);
}

}  // namespace
