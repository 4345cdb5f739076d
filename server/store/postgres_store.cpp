#include "server/store/postgres_store.h"

#include <libpq-fe.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace spinfold::server {

namespace {

// 'SPNF' (as the SQLite store's application_id): the advisory lock replicas take to migrate.
constexpr long long kMigrationLock = 0x53504e46;

// The schema, one step per version: step k takes a database from version k to k + 1.
constexpr const char* kMigrations[] = {
    R"sql(CREATE TABLE sessions (
  id        text PRIMARY KEY,
  version   bigint NOT NULL,            -- bumped by every write: who changed the row since I read it?
  scene     text NOT NULL,              -- JSON, the parameters at t = 0
  timeline  text NOT NULL,              -- JSON, [{"t", "patch"}]
  t         double precision NOT NULL,  -- the current time (8-byte IEEE double, exact in and out)
  playing   boolean NOT NULL,
  rate      double precision NOT NULL,
  last_used bigint NOT NULL             -- the database's clock [ms since 1970]: one clock for all hosts
))sql",
    // 2: recordings, so that every replica answers for every recording, and their files.
    R"sql(CREATE TABLE recordings (
  id      text PRIMARY KEY,
  owner   text NOT NULL,    -- the replica recording it
  status  text NOT NULL,    -- queued, running, done, failed, cancelled
  json    text NOT NULL,    -- the API's view as the owner last wrote it
  reason  text NOT NULL,    -- failed: why
  bytes   bigint NOT NULL,  -- the file's size
  updated bigint NOT NULL   -- the database's clock [ms] at the owner's last write or touch (or the cancel)
);
CREATE TABLE recording_chunks (
  id   text NOT NULL,
  idx  bigint NOT NULL,     -- 0, 1, …: kRecordingChunkBytes each, the last one shorter
  data bytea NOT NULL,
  PRIMARY KEY (id, idx)
))sql",
};
static_assert(std::size(kMigrations) == PostgresStore::kSchemaVersion);

// The database's clock in ms: expiry compares rows written by several hosts with one clock.
constexpr const char* kNowMs = "(extract(epoch from clock_timestamp()) * 1000)::bigint";

constexpr auto kMinBackoff = std::chrono::milliseconds(100);
constexpr auto kMaxBackoff = std::chrono::milliseconds(5000);

std::string trimmed(const char* message) {
  std::string s = message ? message : "";
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  for (char& c : s)
    if (c == '\n') c = ' ';
  return s;
}

}  // namespace

std::string store_url_for_messages(const std::string& url) {
  char* error = nullptr;
  PQconninfoOption* options = PQconninfoParse(url.c_str(), &error);
  if (!options) {
    const std::string why = trimmed(error);
    PQfreemem(error);
    throw StoreError("the PostgreSQL URL is malformed: " + why);
  }
  std::string user, host, port, db;
  for (PQconninfoOption* o = options; o->keyword; ++o) {
    if (!o->val) continue;
    if (std::strcmp(o->keyword, "user") == 0) user = o->val;
    if (std::strcmp(o->keyword, "host") == 0) host = o->val;
    if (std::strcmp(o->keyword, "port") == 0) port = o->val;
    if (std::strcmp(o->keyword, "dbname") == 0) db = o->val;
  }
  PQconninfoFree(options);
  return "postgresql://" + (user.empty() ? "" : user + "@") + host + (port.empty() ? "" : ":" + port) + "/" +
         db;
}

namespace {

// Shortest text that reads back to the same double (PostgreSQL's float8 input is exact); −0 as +0,
// as SQLite stores it, so that the two stores agree bit for bit.
std::string number_text(double v) {
  if (v == 0.0) v = 0.0;
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}

double number_of(const char* text) {
  return std::strtod(text, nullptr);
}

}  // namespace

// A statement's result, cleared when it goes out of scope.
class PostgresStore::Result {
 public:
  explicit Result(PGresult* r) : r_(r) {}
  Result(Result&& o) noexcept : r_(o.r_) { o.r_ = nullptr; }
  Result& operator=(Result&&) = delete;
  ~Result() { PQclear(r_); }
  bool ok() const {
    const ExecStatusType status = PQresultStatus(r_);
    return status == PGRES_COMMAND_OK || status == PGRES_TUPLES_OK;
  }
  std::string error() const { return trimmed(r_ ? PQresultErrorMessage(r_) : "out of memory"); }
  int rows() const { return PQntuples(r_); }
  const char* text(int row, int column) const { return PQgetvalue(r_, row, column); }
  std::string bytes(int row, int column) const {
    return std::string(text(row, column), static_cast<std::size_t>(PQgetlength(r_, row, column)));
  }
  std::int64_t integer(int row, int column) const { return std::strtoll(text(row, column), nullptr, 10); }
  // Rows the INSERT, UPDATE or DELETE changed.
  long changed() const { return std::strtol(PQcmdTuples(r_), nullptr, 10); }
  StoredSession session(int row) const {
    return {.id = text(row, 0),
            .version = integer(row, 1),
            .scene = std::string(text(row, 2), static_cast<std::size_t>(PQgetlength(r_, row, 2))),
            .timeline = std::string(text(row, 3), static_cast<std::size_t>(PQgetlength(r_, row, 3))),
            .t = number_of(text(row, 4)),
            .playing = text(row, 5)[0] == 't',
            .rate = number_of(text(row, 6))};
  }

 private:
  PGresult* r_;
};

constexpr const char* kColumns = "SELECT id, version, scene, timeline, t, playing, rate FROM sessions";

PostgresStore::PostgresStore(const std::string& url) : url_(url), path_(store_url_for_messages(url)) {
  const std::lock_guard lock(mutex_);
  try {
    connect_locked();
  } catch (const StoreError& e) {
    // A newer schema will not change by waiting; a database not up yet may (replicas may start first).
    if (!last_error_.empty()) {
      std::fprintf(stderr, "spinfold: %s (sessions answer 503 until it does)\n", e.what());
      return;
    }
    throw;
  }
}

PostgresStore::~PostgresStore() {
  PQfinish(conn_);
}

void PostgresStore::drop_connection_locked(const std::string& why) {
  PQfinish(conn_);
  conn_ = nullptr;
  last_error_ = why;
  next_attempt_ = Clock::now();  // the first reconnection is at once; backoff after it fails
  std::fprintf(stderr, "spinfold: %s: connection lost: %s\n", path_.c_str(), why.c_str());
}

void PostgresStore::connect_locked() {
  if (conn_ && PQstatus(conn_) == CONNECTION_OK) return;
  const auto now = Clock::now();
  if (now < next_attempt_) {
    const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(next_attempt_ - now);
    throw StoreError(path_ + ": unavailable (" + last_error_ + "); next try in " +
                     std::to_string(wait.count()) + " ms");
  }
  PQfinish(conn_);
  // The URL last: its own settings win over these defaults (expand_dbname = 1).
  const char* keys[] = {"connect_timeout",
                        "tcp_user_timeout",
                        "keepalives_idle",
                        "client_encoding",
                        "application_name",
                        "dbname",
                        nullptr};
  const char* values[] = {"3", "10000", "10", "UTF8", "spinfold", url_.c_str(), nullptr};
  conn_ = PQconnectdbParams(keys, values, 1);
  if (PQstatus(conn_) != CONNECTION_OK) {
    last_error_ = trimmed(PQerrorMessage(conn_));
    PQfinish(conn_);
    conn_ = nullptr;
    backoff_ = std::clamp(backoff_ * 2, std::chrono::milliseconds(kMinBackoff), kMaxBackoff);
    next_attempt_ = now + backoff_;
    if (now - last_warning_ > std::chrono::seconds(10)) {  // a database away for long: one line per 10 s
      last_warning_ = now;
      std::fprintf(stderr, "spinfold: %s: cannot connect: %s\n", path_.c_str(), last_error_.c_str());
    }
    throw StoreError(path_ + ": cannot connect: " + last_error_);
  }
  backoff_ = std::chrono::milliseconds(0);
  const bool was_lost = !last_error_.empty();
  last_error_.clear();
  try {
    migrate_locked();
  } catch (const StoreError&) {
    PQfinish(conn_);
    conn_ = nullptr;
    throw;
  }
  if (was_lost) std::fprintf(stderr, "spinfold: %s: connected again\n", path_.c_str());
}

void PostgresStore::migrate_locked() {
  const auto exec = [this](const char* sql) {
    PGresult* r = PQexec(conn_, sql);
    const ExecStatusType status = PQresultStatus(r);
    std::string value = PQntuples(r) > 0 && !PQgetisnull(r, 0, 0) ? PQgetvalue(r, 0, 0) : "";
    PQclear(r);
    if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) {
      const std::string why = trimmed(PQerrorMessage(conn_));
      PQclear(PQexec(conn_, "ROLLBACK"));
      throw StoreError(path_ + ": preparing the schema: " + why);
    }
    return value;
  };
  // Exact doubles out (PostgreSQL 12+ writes the shortest exact text for any positive value).
  exec("SET extra_float_digits = 3");
  exec("BEGIN");
  exec(("SELECT pg_advisory_xact_lock(" + std::to_string(kMigrationLock) + ")").c_str());
  exec("CREATE TABLE IF NOT EXISTS spinfold_schema (version integer NOT NULL)");
  const std::string stored = exec("SELECT max(version) FROM spinfold_schema");
  const int version = stored.empty() ? 0 : std::atoi(stored.c_str());
  if (version > kSchemaVersion) {
    PQclear(PQexec(conn_, "ROLLBACK"));
    throw StoreError(path_ + ": made by a newer Spinfold (schema " + std::to_string(version) +
                     ", this one reads " + std::to_string(kSchemaVersion) + ")");
  }
  for (int step = version; step < kSchemaVersion; ++step) {
    exec(kMigrations[step]);
    exec(("INSERT INTO spinfold_schema (version) VALUES (" + std::to_string(step + 1) + ")").c_str());
  }
  exec("COMMIT");
}

PostgresStore::Result PostgresStore::run(const char* sql, const std::vector<std::string>& params, Retry retry,
                                         const std::vector<bool>& binary, bool binary_result) {
  std::vector<const char*> values;
  std::vector<int> lengths, formats;
  for (std::size_t i = 0; i < params.size(); ++i) {
    values.push_back(params[i].c_str());
    lengths.push_back(static_cast<int>(params[i].size()));
    formats.push_back(i < binary.size() && binary[i] ? 1 : 0);
  }
  for (int attempt = 0;; ++attempt) {
    connect_locked();
    Result result(PQexecParams(conn_, sql, static_cast<int>(params.size()), nullptr, values.data(),
                               lengths.data(), formats.data(), binary_result ? 1 : 0));
    if (result.ok()) return result;
    const std::string error = result.error();
    if (PQstatus(conn_) == CONNECTION_BAD) {
      drop_connection_locked(error);
      if (retry == Retry::once && attempt == 0) continue;
      throw StoreError(path_ + ": connection lost: " + error);
    }
    throw StoreError(path_ + ": " + error);
  }
}

std::optional<std::int64_t> PostgresStore::version(const std::string& id) {
  const std::lock_guard lock(mutex_);
  const Result r = run("SELECT version FROM sessions WHERE id = $1", {id}, Retry::once);
  if (r.rows() == 0) return std::nullopt;
  return r.integer(0, 0);
}

std::optional<StoredSession> PostgresStore::load(const std::string& id) {
  const std::lock_guard lock(mutex_);
  static const std::string sql = std::string(kColumns) + " WHERE id = $1";
  const Result r = run(sql.c_str(), {id}, Retry::once);
  if (r.rows() == 0) return std::nullopt;
  return r.session(0);
}

std::vector<StoredSession> PostgresStore::load_all() {
  const std::lock_guard lock(mutex_);
  static const std::string sql = std::string(kColumns) + " ORDER BY last_used";
  const Result r = run(sql.c_str(), {}, Retry::once);
  std::vector<StoredSession> rows;
  for (int i = 0; i < r.rows(); ++i) rows.push_back(r.session(i));
  return rows;
}

std::int64_t PostgresStore::save(const StoredSession& row) {
  const std::lock_guard lock(mutex_);
  // One statement is one transaction: the version test and the write are atomic across replicas.
  static const std::string insert =
      std::string(
          "INSERT INTO sessions (id, version, scene, timeline, t, playing, rate, last_used) "
          "VALUES ($1, 1, $2, $3, $4, $5, $6, ") +
      kNowMs + ") ON CONFLICT (id) DO NOTHING";
  static const std::string update =
      std::string(
          "UPDATE sessions SET version = version + 1, scene = $2, timeline = $3, t = $4, playing = $5, "
          "rate = $6, last_used = ") +
      kNowMs + " WHERE id = $1 AND version = $7";
  std::vector<std::string> params = {row.id,
                                     row.scene,
                                     row.timeline,
                                     number_text(row.t),
                                     row.playing ? "true" : "false",
                                     number_text(row.rate)};
  if (row.version != 0) params.push_back(std::to_string(row.version));
  const Result r = run((row.version == 0 ? insert : update).c_str(), params, Retry::no);
  return r.changed() == 1 ? row.version + 1 : 0;
}

void PostgresStore::touch(const std::string& id) {
  const std::lock_guard lock(mutex_);
  static const std::string sql = std::string("UPDATE sessions SET last_used = ") + kNowMs + " WHERE id = $1";
  run(sql.c_str(), {id}, Retry::once);
}

bool PostgresStore::remove(const std::string& id) {
  const std::lock_guard lock(mutex_);
  return run("DELETE FROM sessions WHERE id = $1", {id}, Retry::no).changed() > 0;
}

std::int64_t PostgresStore::count() {
  const std::lock_guard lock(mutex_);
  const Result r = run("SELECT count(*) FROM sessions", {}, Retry::once);
  return r.integer(0, 0);
}

void PostgresStore::expire(std::chrono::seconds idle) {
  const std::lock_guard lock(mutex_);
  static const std::string sql = std::string("DELETE FROM sessions WHERE last_used < ") + kNowMs + " - $1";
  run(sql.c_str(), {std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(idle).count())},
      Retry::once);
}

bool PostgresStore::reachable() {
  const std::lock_guard lock(mutex_);
  try {
    run("SELECT 1", {}, Retry::once);
    return true;
  } catch (const StoreError&) {
    return false;
  }
}

namespace {
// Queued or running: the rows an owner still writes.
constexpr const char* kActive = "status IN ('queued', 'running')";
}  // namespace

bool PostgresStore::save_recording(const StoredRecording& row) {
  const std::lock_guard lock(mutex_);
  // Only an active row changes: a cancel from another replica, or a deletion, is final.
  static const std::string insert =
      std::string(
          "INSERT INTO recordings (id, owner, status, json, reason, bytes, updated) "
          "VALUES ($1, $2, $3, $4, $5, $6, ") +
      kNowMs +
      ") ON CONFLICT (id) DO UPDATE SET owner = $2, status = $3, json = $4, reason = $5, bytes = $6, "
      "updated = " +
      kNowMs + " WHERE recordings." + kActive;
  static const std::string update =
      std::string(
          "UPDATE recordings SET owner = $2, status = $3, json = $4, reason = $5, "
          "bytes = $6, updated = ") +
      kNowMs + " WHERE id = $1 AND " + kActive;
  const Result r =
      run((row.status == "queued" ? insert : update).c_str(),
          {row.id, row.owner, row.status, row.json, row.reason, std::to_string(row.bytes)}, Retry::no);
  return r.changed() == 1;
}

std::optional<StoredRecording> PostgresStore::load_recording(const std::string& id) {
  const std::lock_guard lock(mutex_);
  static const std::string sql = std::string("SELECT id, owner, status, json, reason, bytes, ") + kNowMs +
                                 " - updated FROM recordings WHERE id = $1";
  const Result r = run(sql.c_str(), {id}, Retry::once);
  if (r.rows() == 0) return std::nullopt;
  return StoredRecording{.id = r.text(0, 0),
                         .owner = r.text(0, 1),
                         .status = r.text(0, 2),
                         .json = r.bytes(0, 3),
                         .reason = r.bytes(0, 4),
                         .bytes = r.integer(0, 5),
                         .silent_ms = r.integer(0, 6)};
}

bool PostgresStore::cancel_recording(const std::string& id) {
  const std::lock_guard lock(mutex_);
  static const std::string sql = std::string("UPDATE recordings SET status = 'cancelled', updated = ") +
                                 kNowMs + " WHERE id = $1 AND " + kActive;
  return run(sql.c_str(), {id}, Retry::no).changed() == 1;
}

void PostgresStore::save_recording_chunk(const std::string& id, std::int64_t index, std::string_view bytes) {
  const std::lock_guard lock(mutex_);
  run("INSERT INTO recording_chunks (id, idx, data) VALUES ($1, $2, $3) "
      "ON CONFLICT (id, idx) DO UPDATE SET data = excluded.data",
      {id, std::to_string(index), std::string(bytes)}, Retry::no, {false, false, true});
}

std::optional<std::string> PostgresStore::load_recording_chunk(const std::string& id, std::int64_t index) {
  const std::lock_guard lock(mutex_);
  // Binary result: the bytea's bytes as they are (one column).
  const Result r = run("SELECT data FROM recording_chunks WHERE id = $1 AND idx = $2::bigint",
                       {id, std::to_string(index)}, Retry::once, {}, true);
  if (r.rows() == 0) return std::nullopt;
  return r.bytes(0, 0);
}

bool PostgresStore::remove_recording(const std::string& id) {
  const std::lock_guard lock(mutex_);
  // One statement: the row and its file go together.
  return run("WITH chunks AS (DELETE FROM recording_chunks WHERE id = $1) DELETE FROM recordings WHERE id = "
             "$1",
             {id}, Retry::no)
             .changed() > 0;
}

void PostgresStore::touch_recordings(const std::string& owner) {
  const std::lock_guard lock(mutex_);
  static const std::string sql =
      std::string("UPDATE recordings SET updated = ") + kNowMs + " WHERE owner = $1 AND " + kActive;
  run(sql.c_str(), {owner}, Retry::once);
}

std::int64_t PostgresStore::recording_bytes() {
  const std::lock_guard lock(mutex_);
  return run("SELECT coalesce(sum(bytes), 0) FROM recordings", {}, Retry::once).integer(0, 0);
}

void PostgresStore::expire_recordings(std::chrono::seconds age, std::chrono::seconds lost,
                                      const std::string& reason) {
  const std::lock_guard lock(mutex_);
  using std::chrono::milliseconds;
  static const std::string fail = std::string(
                                      "UPDATE recordings SET status = 'failed', reason = $2, bytes = 0, "
                                      "updated = ") +
                                  kNowMs + " WHERE updated < " + kNowMs + " - $1::bigint AND " + kActive;
  run(fail.c_str(), {std::to_string(std::chrono::duration_cast<milliseconds>(lost).count()), reason},
      Retry::once);
  static const std::string old =
      std::string("DELETE FROM recordings WHERE updated < ") + kNowMs + " - $1::bigint AND NOT " + kActive;
  run(old.c_str(), {std::to_string(std::chrono::duration_cast<milliseconds>(age).count())}, Retry::once);
  run("DELETE FROM recording_chunks WHERE id NOT IN "
      "(SELECT id FROM recordings WHERE status IN ('queued', 'running', 'done'))",
      {}, Retry::once);
}

}  // namespace spinfold::server
