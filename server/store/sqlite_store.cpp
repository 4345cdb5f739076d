#include "server/store/sqlite_store.h"

#include <sqlite3.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <thread>

namespace spinfold::server {

namespace {

// 'SPNF': the file is a Spinfold store (PRAGMA application_id), and the layout of its rows.
constexpr int kApplicationId = 0x53504e46;
constexpr int kSchemaVersion = 2;  // 2: recordings and their files

constexpr const char* kSchema = R"sql(
CREATE TABLE IF NOT EXISTS sessions (
  id        TEXT PRIMARY KEY NOT NULL,
  version   INTEGER NOT NULL,  -- bumped by every write: who changed the row since I read it?
  scene     TEXT NOT NULL,     -- JSON, the parameters at t = 0
  timeline  TEXT NOT NULL,     -- JSON, [{"t", "patch"}]
  t         REAL NOT NULL,     -- the current time (8-byte IEEE double: exact)
  playing   INTEGER NOT NULL,
  rate      REAL NOT NULL,
  last_used INTEGER NOT NULL   -- Unix time [ms] of the last write or touch
) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS recordings (
  id      TEXT PRIMARY KEY NOT NULL,
  owner   TEXT NOT NULL,     -- the replica recording it
  status  TEXT NOT NULL,     -- queued, running, done, failed, cancelled
  json    TEXT NOT NULL,     -- the API's view as the owner last wrote it
  reason  TEXT NOT NULL,     -- failed: why
  bytes   INTEGER NOT NULL,  -- the file's size
  updated INTEGER NOT NULL   -- Unix time [ms] of the owner's last write or touch (or the cancel)
) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS recording_chunks (
  id    TEXT NOT NULL,
  idx   INTEGER NOT NULL,  -- 0, 1, …: kRecordingChunkBytes each, the last one shorter
  data  BLOB NOT NULL,
  PRIMARY KEY (id, idx)
))sql";

// Queued or running: the rows an owner still writes.
constexpr const char* kActive = "status IN ('queued', 'running')";

std::int64_t now_ms() {
  using namespace std::chrono;
  return duration_cast<milliseconds>(system_clock::now().time_since_epoch()).count();
}

}  // namespace

// A prepared statement in use: bound, stepped, and reset when it goes out of scope.
struct SqliteStore::Statement {
  SqliteStore& db;
  sqlite3_stmt* stmt;
  Statement(SqliteStore& owner, const char* sql) : db(owner), stmt(owner.prepare(sql)) {}
  ~Statement() {
    sqlite3_reset(stmt);
    sqlite3_clear_bindings(stmt);
  }
  Statement& text(int i, const std::string& v) {
    sqlite3_bind_text(stmt, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
    return *this;
  }
  Statement& integer(int i, std::int64_t v) {
    sqlite3_bind_int64(stmt, i, v);
    return *this;
  }
  Statement& blob(int i, std::string_view v) {
    sqlite3_bind_blob64(stmt, i, v.data(), v.size(), SQLITE_TRANSIENT);
    return *this;
  }
  Statement& real(int i, double v) {
    sqlite3_bind_double(stmt, i, v);
    return *this;
  }
  // True with a row to read, false when done; StoreError on failure.
  bool step() {
    const int rc = sqlite3_step(stmt);
    if (rc == SQLITE_ROW) return true;
    if (rc != SQLITE_DONE) db.fail(sqlite3_sql(stmt));
    return false;
  }
  std::string column_text(int i) {
    const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(stmt, i));
    return p ? std::string(p, static_cast<std::size_t>(sqlite3_column_bytes(stmt, i))) : std::string();
  }
  StoredSession session() {
    return {.id = column_text(0),
            .version = sqlite3_column_int64(stmt, 1),
            .scene = column_text(2),
            .timeline = column_text(3),
            .t = sqlite3_column_double(stmt, 4),
            .playing = sqlite3_column_int(stmt, 5) != 0,
            .rate = sqlite3_column_double(stmt, 6)};
  }
};

constexpr const char* kColumns = "SELECT id, version, scene, timeline, t, playing, rate FROM sessions";

SqliteStore::SqliteStore(const std::string& dir, std::chrono::milliseconds busy_timeout) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw StoreError("cannot create the data directory '" + dir + "': " + ec.message());
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw StoreError("the data directory '" + dir + "' is not writable: " + std::strerror(errno));
  path_ = (std::filesystem::path(dir) / "sessions.db").string();
  const int rc = sqlite3_open_v2(path_.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
  if (rc != SQLITE_OK) {
    const std::string why = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close(db_);
    throw StoreError(path_ + ": cannot open: " + why);
  }
  try {
    // Waits this long for another process's write (or its crash recovery) before SQLITE_BUSY.
    sqlite3_busy_timeout(db_, static_cast<int>(busy_timeout.count()));
    {
      Statement check(*this, "PRAGMA quick_check");
      if (!check.step() || check.column_text(0) != "ok")
        throw StoreError(path_ + ": the database is damaged (quick_check: " + check.column_text(0) +
                         "); move it away to start with an empty store");
    }
    std::int64_t application_id = 0, schema = 0;
    {
      Statement id(*this, "PRAGMA application_id");
      if (id.step()) application_id = sqlite3_column_int64(id.stmt, 0);
      Statement version(*this, "PRAGMA user_version");
      if (version.step()) schema = sqlite3_column_int64(version.stmt, 0);
    }
    if (application_id != 0 && application_id != kApplicationId)
      throw StoreError(path_ + ": not a Spinfold session store (another program's SQLite database)");
    if (schema > kSchemaVersion)
      throw StoreError(path_ + ": made by a newer Spinfold (schema " + std::to_string(schema) + ")");
    // WAL: readers never wait for the writer, so several processes can share the file. Switching a
    // new file to it while another process opens it too (replicas started together) can be
    // SQLITE_BUSY without the busy handler being asked: tried again until busy_timeout.
    for (const auto until = std::chrono::steady_clock::now() + busy_timeout;;) {
      try {
        Statement wal(*this, "PRAGMA journal_mode = WAL");
        if (!wal.step() || wal.column_text(0) != "wal")
          throw StoreError(path_ + ": cannot use WAL mode (journal_mode is '" + wal.column_text(0) +
                           "'; is the directory on a network file system?)");
        break;
      } catch (const StoreError&) {
        if (sqlite3_errcode(db_) != SQLITE_BUSY || std::chrono::steady_clock::now() > until) throw;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
    }
    // FULL: a commit is on disk (fsync) before the API acknowledges it, power loss included.
    exec("PRAGMA synchronous = FULL");
    exec(kSchema);
    exec(("PRAGMA application_id = " + std::to_string(kApplicationId)).c_str());
    exec(("PRAGMA user_version = " + std::to_string(kSchemaVersion)).c_str());
  } catch (...) {
    for (sqlite3_stmt* s : statements_) sqlite3_finalize(s);
    sqlite3_close(db_);
    throw;
  }
}

SqliteStore::~SqliteStore() {
  for (sqlite3_stmt* s : statements_) sqlite3_finalize(s);
  sqlite3_close(db_);
}

void SqliteStore::fail(const std::string& what) {
  throw StoreError(path_ + ": " + what + ": " + sqlite3_errmsg(db_));
}

sqlite3_stmt* SqliteStore::prepare(const char* sql) {
  for (sqlite3_stmt* s : statements_)
    if (std::strcmp(sqlite3_sql(s), sql) == 0) return s;
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db_, sql, -1, &s, nullptr) != SQLITE_OK) fail(sql);
  statements_.push_back(s);
  return s;
}

void SqliteStore::exec(const char* sql) {
  if (sqlite3_exec(db_, sql, nullptr, nullptr, nullptr) != SQLITE_OK) fail(sql);
}

std::optional<std::int64_t> SqliteStore::version(const std::string& id) {
  const std::lock_guard lock(mutex_);
  Statement q(*this, "SELECT version FROM sessions WHERE id = ?1");
  q.text(1, id);
  if (!q.step()) return std::nullopt;
  return sqlite3_column_int64(q.stmt, 0);
}

std::optional<StoredSession> SqliteStore::load(const std::string& id) {
  const std::lock_guard lock(mutex_);
  static const std::string sql = std::string(kColumns) + " WHERE id = ?1";
  Statement q(*this, sql.c_str());
  q.text(1, id);
  if (!q.step()) return std::nullopt;
  return q.session();
}

std::vector<StoredSession> SqliteStore::load_all() {
  const std::lock_guard lock(mutex_);
  static const std::string sql = std::string(kColumns) + " ORDER BY last_used";
  Statement q(*this, sql.c_str());
  std::vector<StoredSession> rows;
  while (q.step()) rows.push_back(q.session());
  return rows;
}

std::int64_t SqliteStore::save(const StoredSession& row) {
  const std::lock_guard lock(mutex_);
  // One statement is one transaction: the version test and the write are atomic across processes.
  Statement q(*this, row.version == 0
                         ? "INSERT INTO sessions (id, version, scene, timeline, t, playing, rate, last_used) "
                           "VALUES (?1, 1, ?2, ?3, ?4, ?5, ?6, ?7) ON CONFLICT (id) DO NOTHING"
                         : "UPDATE sessions SET version = version + 1, scene = ?2, timeline = ?3, t = ?4, "
                           "playing = ?5, rate = ?6, last_used = ?7 WHERE id = ?1 AND version = ?8");
  q.text(1, row.id).text(2, row.scene).text(3, row.timeline).real(4, row.t);
  q.integer(5, row.playing ? 1 : 0).real(6, row.rate).integer(7, now_ms());
  if (row.version != 0) q.integer(8, row.version);
  q.step();
  return sqlite3_changes(db_) == 1 ? row.version + 1 : 0;
}

void SqliteStore::touch(const std::string& id) {
  const std::lock_guard lock(mutex_);
  Statement q(*this, "UPDATE sessions SET last_used = ?2 WHERE id = ?1");
  q.text(1, id).integer(2, now_ms());
  q.step();
}

bool SqliteStore::remove(const std::string& id) {
  const std::lock_guard lock(mutex_);
  Statement q(*this, "DELETE FROM sessions WHERE id = ?1");
  q.text(1, id);
  q.step();
  return sqlite3_changes(db_) > 0;
}

std::int64_t SqliteStore::count() {
  const std::lock_guard lock(mutex_);
  Statement q(*this, "SELECT count(*) FROM sessions");
  return q.step() ? sqlite3_column_int64(q.stmt, 0) : 0;
}

void SqliteStore::expire(std::chrono::seconds idle) {
  const std::lock_guard lock(mutex_);
  Statement q(*this, "DELETE FROM sessions WHERE last_used < ?1");
  q.integer(1, now_ms() - std::chrono::duration_cast<std::chrono::milliseconds>(idle).count());
  q.step();
}

bool SqliteStore::save_recording(const StoredRecording& row) {
  const std::lock_guard lock(mutex_);
  // Only an active row changes: a cancel from another replica, or a deletion, is final.
  static const std::string insert =
      std::string(
          "INSERT INTO recordings (id, owner, status, json, reason, bytes, updated) "
          "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7) ON CONFLICT (id) DO UPDATE SET owner = ?2, status = ?3, "
          "json = ?4, reason = ?5, bytes = ?6, updated = ?7 WHERE recordings.") +
      kActive;
  static const std::string update =
      std::string(
          "UPDATE recordings SET owner = ?2, status = ?3, json = ?4, reason = ?5, bytes = ?6, "
          "updated = ?7 WHERE id = ?1 AND ") +
      kActive;
  Statement q(*this, row.status == "queued" ? insert.c_str() : update.c_str());
  q.text(1, row.id).text(2, row.owner).text(3, row.status).text(4, row.json).text(5, row.reason);
  q.integer(6, row.bytes).integer(7, now_ms());
  q.step();
  return sqlite3_changes(db_) == 1;
}

std::optional<StoredRecording> SqliteStore::load_recording(const std::string& id) {
  const std::lock_guard lock(mutex_);
  Statement q(*this,
              "SELECT id, owner, status, json, reason, bytes, ?2 - updated FROM recordings WHERE id = ?1");
  q.text(1, id).integer(2, now_ms());
  if (!q.step()) return std::nullopt;
  return StoredRecording{.id = q.column_text(0),
                         .owner = q.column_text(1),
                         .status = q.column_text(2),
                         .json = q.column_text(3),
                         .reason = q.column_text(4),
                         .bytes = sqlite3_column_int64(q.stmt, 5),
                         .silent_ms = sqlite3_column_int64(q.stmt, 6)};
}

bool SqliteStore::cancel_recording(const std::string& id) {
  const std::lock_guard lock(mutex_);
  static const std::string sql =
      std::string("UPDATE recordings SET status = 'cancelled', updated = ?2 WHERE id = ?1 AND ") + kActive;
  Statement q(*this, sql.c_str());
  q.text(1, id).integer(2, now_ms());
  q.step();
  return sqlite3_changes(db_) == 1;
}

void SqliteStore::save_recording_chunk(const std::string& id, std::int64_t index, std::string_view bytes) {
  const std::lock_guard lock(mutex_);
  Statement q(*this, "INSERT OR REPLACE INTO recording_chunks (id, idx, data) VALUES (?1, ?2, ?3)");
  q.text(1, id).integer(2, index).blob(3, bytes);
  q.step();
}

std::optional<std::string> SqliteStore::load_recording_chunk(const std::string& id, std::int64_t index) {
  const std::lock_guard lock(mutex_);
  Statement q(*this, "SELECT data FROM recording_chunks WHERE id = ?1 AND idx = ?2");
  q.text(1, id).integer(2, index);
  if (!q.step()) return std::nullopt;
  const auto* p = static_cast<const char*>(sqlite3_column_blob(q.stmt, 0));
  return std::string(p ? p : "", static_cast<std::size_t>(sqlite3_column_bytes(q.stmt, 0)));
}

bool SqliteStore::remove_recording(const std::string& id) {
  const std::lock_guard lock(mutex_);
  // The row first: a file without its row is an orphan that expire_recordings removes.
  Statement row(*this, "DELETE FROM recordings WHERE id = ?1");
  row.text(1, id);
  row.step();
  const bool removed = sqlite3_changes(db_) > 0;
  Statement chunks(*this, "DELETE FROM recording_chunks WHERE id = ?1");
  chunks.text(1, id);
  chunks.step();
  return removed;
}

void SqliteStore::touch_recordings(const std::string& owner) {
  const std::lock_guard lock(mutex_);
  static const std::string sql =
      std::string("UPDATE recordings SET updated = ?2 WHERE owner = ?1 AND ") + kActive;
  Statement q(*this, sql.c_str());
  q.text(1, owner).integer(2, now_ms());
  q.step();
}

std::int64_t SqliteStore::recording_bytes() {
  const std::lock_guard lock(mutex_);
  Statement q(*this, "SELECT coalesce(sum(bytes), 0) FROM recordings");
  return q.step() ? sqlite3_column_int64(q.stmt, 0) : 0;
}

void SqliteStore::expire_recordings(std::chrono::seconds age, std::chrono::seconds lost,
                                    const std::string& reason) {
  const std::lock_guard lock(mutex_);
  using std::chrono::milliseconds;
  const std::int64_t now = now_ms();
  static const std::string fail =
      std::string(
          "UPDATE recordings SET status = 'failed', reason = ?2, bytes = 0, updated = ?3 "
          "WHERE updated < ?1 AND ") +
      kActive;
  Statement failed(*this, fail.c_str());
  failed.integer(1, now - std::chrono::duration_cast<milliseconds>(lost).count())
      .text(2, reason)
      .integer(3, now);
  failed.step();
  static const std::string old = std::string("DELETE FROM recordings WHERE updated < ?1 AND NOT ") + kActive;
  Statement finished(*this, old.c_str());
  finished.integer(1, now - std::chrono::duration_cast<milliseconds>(age).count());
  finished.step();
  Statement orphans(*this,
                    "DELETE FROM recording_chunks WHERE id NOT IN "
                    "(SELECT id FROM recordings WHERE status IN ('queued', 'running', 'done'))");
  orphans.step();
}

}  // namespace spinfold::server
