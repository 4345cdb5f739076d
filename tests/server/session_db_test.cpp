// The store conformance suite: every SessionDb (SQLite and PostgreSQL) keeps the same promises.
// PostgreSQL's cases need a server: ctest's server_tests_postgres starts one of its own
// (tests/server/postgres_fixture.sh) and names it in SPINFOLD_TEST_POSTGRES_DIR; without it they skip.
#include "server/session_db.h"

#include <gtest/gtest.h>
#include <libpq-fe.h>
#include <unistd.h>

#include <atomic>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "server/postgres_session_db.h"
#include "tests/server/test_stores.h"

namespace {

using spinfold::server::open_session_db;
using spinfold::server::SessionDb;
using spinfold::test::admin;
using spinfold::test::Backend;
using spinfold::test::fixture;
using spinfold::test::postgres_dir;
using spinfold::server::StoredSession;
using spinfold::server::StoreError;
namespace fs = std::filesystem;

class SessionDbConformance : public testing::TestWithParam<std::string> {
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
  std::unique_ptr<SessionDb> db_;
};

StoredSession row(const std::string& id, double t = 0.0) {
  return {.id = id, .scene = R"({"surface":{"kind":"sphere"}})", .timeline = "[]", .t = t, .rate = 1.0};
}

TEST_P(SessionDbConformance, TimesComeBackBitForBit) {
  // Times a session reaches: thirds, subnormals, extremes, negative zero, random bit patterns.
  std::vector<double> times = {1.0 / 3.0, 0.1, -0.0, std::numeric_limits<double>::denorm_min(),
                               std::numeric_limits<double>::max(), 1e-300, 2.5, 123456.789e10};
  std::mt19937_64 random(27);
  for (int i = 0; i < 200; ++i) {
    const double t = std::bit_cast<double>(random());
    if (std::isfinite(t)) times.push_back(t);
  }
  for (std::size_t i = 0; i < times.size(); ++i) {
    StoredSession r = row("s" + std::to_string(i), times[i]);
    r.rate = times[times.size() - 1 - i];
    ASSERT_EQ(db_->save(r), 1);
  }
  // −0 comes back as +0 from every store (SQLite keeps an integral REAL as an integer; PostgreSQL is
  // made to agree), which no session can tell apart: t ≥ 0, and a rate of ±0 is paused play.
  const auto stored = [](double v) { return std::bit_cast<std::uint64_t>(v == 0.0 ? 0.0 : v); };
  const auto second = backend_->open();  // another process's view of the rows
  for (std::size_t i = 0; i < times.size(); ++i) {
    const auto loaded = second->load("s" + std::to_string(i));
    ASSERT_TRUE(loaded);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(loaded->t), stored(times[i])) << times[i];
    EXPECT_EQ(std::bit_cast<std::uint64_t>(loaded->rate), stored(times[times.size() - 1 - i]));
  }
}

TEST_P(SessionDbConformance, TextComesBackByteForByte) {
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

TEST_P(SessionDbConformance, AWriteNamingAnOldVersionChangesNothing) {
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

TEST_P(SessionDbConformance, ConcurrentWritersLoseNoChange) {
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
        if (db->save(r) != 0) ++done;
        else ++conflicts;
      }
    });
  for (auto& t : threads) t.join();
  const auto final_row = db_->load("counter");
  EXPECT_EQ(final_row->t, kWriters * kEach);
  EXPECT_EQ(final_row->version, 1 + kWriters * kEach);
  std::printf("%d conflicts retried\n", conflicts.load());
}

TEST_P(SessionDbConformance, TouchRemoveCountAndExpire) {
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

INSTANTIATE_TEST_SUITE_P(Stores, SessionDbConformance, testing::Values("sqlite", "postgresql"),
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
  EXPECT_TRUE(admin(backend_->url(), "DO $$ BEGIN IF (SELECT count(*) FROM spinfold_schema) <> 1 OR "
                                     "(SELECT max(version) FROM spinfold_schema) <> 1 THEN RAISE 'schema'; END IF; END $$"));
  ASSERT_TRUE(admin(backend_->url(), "INSERT INTO spinfold_schema VALUES (99)"));
  try {
    backend_->open();
    ADD_FAILURE() << "a newer schema was opened";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("newer Spinfold (schema 99"), std::string::npos) << e.what();
  }
}

TEST_F(PostgresStore, AMalformedUrlIsAnErrorAndMessagesHideThePassword) {
  EXPECT_THROW(open_session_db("postgresql://[broken", ""), StoreError);
  EXPECT_THROW(open_session_db("mysql://localhost/x", ""), StoreError);
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
