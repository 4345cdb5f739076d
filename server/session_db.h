// The durable store of sessions: one row per session holding what determines it (scene, timeline,
// time) and a version bumped by every write. Several server processes may share the store: each
// write names the version it saw, so none overwrites a change it missed (a lost race is a 409).
// Two implementations: SQLite in the data directory (server/sqlite_session_db.h, the default: one
// machine, nothing to run) and PostgreSQL (server/postgres_session_db.h: replicas on several hosts).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace spinfold::server {

// The store cannot be opened, read or written: a message naming the store and the reason.
struct StoreError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One row: a session as a pure function of its scene, timeline and time (sessions.h `rebuild`).
struct StoredSession {
  std::string id;
  std::int64_t version = 0;  // bumped by every write; 0: not stored yet
  std::string scene;         // JSON: the parameters at t = 0
  std::string timeline;      // JSON: [{"t", "patch"}]
  double t = 0.0;            // [time] the session's current time, bit for bit (an 8-byte double; −0 as +0)
  bool playing = false;      // as last stored (a session loaded from the store starts paused)
  double rate = 1.0;         // simulated time per second of wall time while playing
};

// What every store does; each call is one atomic statement, safe from any thread. A call that cannot
// reach the store throws StoreError (the server answers 503 and keeps nothing half-written).
class SessionDb {
 public:
  virtual ~SessionDb() = default;
  // Where the rows are, for messages: the file, or the database URL without its password.
  virtual const std::string& path() const = 0;
  virtual std::string_view kind() const = 0;  // "sqlite" or "postgresql"
  // The row's version, or nullopt when there is no such row.
  virtual std::optional<std::int64_t> version(const std::string& id) = 0;
  virtual std::optional<StoredSession> load(const std::string& id) = 0;
  virtual std::vector<StoredSession> load_all() = 0;  // least recently used first
  // Writes the row if its stored version is still `row.version` (0: inserts a new row) and returns
  // the new version, or 0 when another writer changed or deleted it first (nothing written).
  virtual std::int64_t save(const StoredSession& row) = 0;
  // Marks the row used now (its version unchanged): rows unused for the idle expiry are dropped.
  virtual void touch(const std::string& id) = 0;
  virtual bool remove(const std::string& id) = 0;  // true when a row was deleted
  virtual std::int64_t count() = 0;
  virtual void expire(std::chrono::seconds idle) = 0;  // deletes rows unused for longer than `idle`
  // True when the store answers now (GET /health): a store that is away makes the replica unready.
  virtual bool reachable() = 0;
};

// The store `spinfold serve` was asked for: `url` "postgresql://…" (or "postgres://…") is PostgreSQL;
// "" is SQLite in `data_dir` (DIR/sessions.db); both empty: nullptr (sessions in memory only).
// StoreError when it cannot be opened (an unwritable directory, a damaged file, a malformed URL).
std::unique_ptr<SessionDb> open_session_db(const std::string& url, const std::string& data_dir);

// True for the URLs open_session_db gives to PostgreSQL.
bool is_postgres_url(const std::string& url);
// postgresql://user@host:port/db: the URL as messages show it, without its password (StoreError
// when libpq cannot read it).
std::string store_url_for_messages(const std::string& url);

// The per-user state directory: $XDG_STATE_HOME/spinfold, else ~/.local/state/spinfold ("" when
// neither variable is set).
std::string default_data_dir();

}  // namespace spinfold::server
