// The durable store of sessions: one SQLite database (WAL mode) in the data directory, one row per
// session holding what determines it (scene, timeline, time) and a version bumped by every write.
// Several server processes may share the file: readers never wait for the writer, writers take turns
// (busy timeout), and each write names the version it saw, so none overwrites a change it missed.
#pragma once

#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace spinfold::server {

// The store cannot be opened, read or written: a message naming the file and SQLite's reason.
struct StoreError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One row: a session as a pure function of its scene, timeline and time (sessions.h `rebuild`).
struct StoredSession {
  std::string id;
  std::int64_t version = 0;  // bumped by every write; 0: not stored yet
  std::string scene;         // JSON: the parameters at t = 0
  std::string timeline;      // JSON: [{"t", "patch"}]
  double t = 0.0;            // [time] the session's current time, bit for bit (an 8-byte REAL)
  bool playing = false;      // as last stored (a session loaded from the store starts paused)
  double rate = 1.0;         // simulated time per second of wall time while playing
};

class SessionDb {
 public:
  // Opens (creating it and the directory when missing) DIR/sessions.db in WAL mode and checks it
  // (PRAGMA quick_check); StoreError when the directory is unwritable or the file is not a sound
  // Spinfold database, or stays locked past `busy_timeout`.
  explicit SessionDb(const std::string& dir,
                     std::chrono::milliseconds busy_timeout = std::chrono::seconds(5));
  ~SessionDb();
  SessionDb(const SessionDb&) = delete;
  SessionDb& operator=(const SessionDb&) = delete;

  const std::string& path() const { return path_; }
  // The row's version, or nullopt when there is no such row.
  std::optional<std::int64_t> version(const std::string& id);
  std::optional<StoredSession> load(const std::string& id);
  std::vector<StoredSession> load_all();
  // Writes the row if its stored version is still `row.version` (0: inserts a new row) and returns
  // the new version, or 0 when another writer changed or deleted it first (nothing written).
  std::int64_t save(const StoredSession& row);
  // Marks the row used now (its version unchanged): rows unused for the idle expiry are dropped.
  void touch(const std::string& id);
  bool remove(const std::string& id);  // true when a row was deleted
  std::int64_t count();
  void expire(std::chrono::seconds idle);  // deletes rows unused for longer than `idle`

 private:
  struct Statement;
  void exec(const char* sql);
  [[noreturn]] void fail(const std::string& what);
  sqlite3_stmt* prepare(const char* sql);
  std::mutex mutex_;  // one connection, its statements used by one thread at a time
  std::string path_;
  sqlite3* db_ = nullptr;
  std::vector<sqlite3_stmt*> statements_;
};

// The per-user state directory: $XDG_STATE_HOME/spinfold, else ~/.local/state/spinfold ("" when
// neither variable is set).
std::string default_data_dir();

}  // namespace spinfold::server
