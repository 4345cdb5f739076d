// The durable store of sessions: one row per session holding what determines it (scene, timeline,
// time) and a version bumped by every write. Several server processes may share the store: each
// write names the version it saw, so none overwrites a change it missed (a lost race is a 409).
// Two implementations: SQLite in the data directory (server/store/sqlite_store.h, the default: one
// machine, nothing to run) and PostgreSQL (server/store/postgres_store.h: replicas on several hosts).
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

// A recording's row: written by the replica that records it (its owner), read by any replica, so that
// every replica answers for every recording; its finished file is in the store too, in chunks
// (server/jobs/recordings.h says why the store and not a shared path).
struct StoredRecording {
  std::string id{};
  std::string owner{};         // the replica recording it (Recordings::instance)
  std::string status{};        // queued, running, done, failed or cancelled
  std::string json{};          // the API's view of it as the owner last wrote it (its status and reason
                               // are the columns': a cancel or a lost owner changes only those)
  std::string reason{};        // failed: why
  std::int64_t bytes = 0;      // the file's size: so far (running), in the store (done)
  std::int64_t silent_ms = 0;  // read only: since the owner last wrote or touched the row (database clock)
};

// A recording's file is stored in chunks of this size [bytes] (the last one shorter).
constexpr std::int64_t kRecordingChunkBytes = 1 << 20;

// What every store does; each call is one atomic statement, safe from any thread. A call that cannot
// reach the store throws StoreError (the server answers 503 and keeps nothing half-written).
class Store {
 public:
  virtual ~Store() = default;
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

  // Recordings. Inserts or updates the owner's row unless it is cancelled or gone meanwhile (false:
  // a cancel from another replica, or a deletion; nothing written).
  virtual bool save_recording(const StoredRecording& row) = 0;
  virtual std::optional<StoredRecording> load_recording(const std::string& id) = 0;
  // Queued or running → cancelled (true); false when it was neither (finished, or no such row).
  virtual bool cancel_recording(const std::string& id) = 0;
  // Chunk `index` (0, 1, …) of the file: written by the owner before its row says done.
  virtual void save_recording_chunk(const std::string& id, std::int64_t index, std::string_view bytes) = 0;
  virtual std::optional<std::string> load_recording_chunk(const std::string& id, std::int64_t index) = 0;
  virtual bool remove_recording(const std::string& id) = 0;  // the row and its file; true when a row went
  // Marks the owner's queued and running rows as alive now (its heartbeat).
  virtual void touch_recordings(const std::string& owner) = 0;
  virtual std::int64_t recording_bytes() = 0;  // the files in the store, all rows [bytes]
  // Active rows whose owner was silent longer than `lost` become failed with `reason`; finished rows
  // older than `age` are deleted with their files, and so are files whose row is neither active nor
  // done (a cancel that came while the owner stored the file).
  virtual void expire_recordings(std::chrono::seconds age, std::chrono::seconds lost,
                                 const std::string& reason) = 0;
};

// The store `spinfold serve` was asked for: `url` "postgresql://…" (or "postgres://…") is PostgreSQL;
// "" is SQLite in `data_dir` (DIR/sessions.db); both empty: nullptr (sessions in memory only).
// StoreError when it cannot be opened (an unwritable directory, a damaged file, a malformed URL).
std::unique_ptr<Store> open_store(const std::string& url, const std::string& data_dir);

// True for the URLs open_store gives to PostgreSQL.
bool is_postgres_url(const std::string& url);
// postgresql://user@host:port/db: the URL as messages show it, without its password (StoreError
// when libpq cannot read it).
std::string store_url_for_messages(const std::string& url);

// The per-user state directory: $XDG_STATE_HOME/spinfold, else ~/.local/state/spinfold ("" when
// neither variable is set).
std::string default_data_dir();

}  // namespace spinfold::server
