// The default session store: one SQLite database (WAL mode) in the data directory. Processes on one
// machine may share the file: readers never wait for the writer, writers take turns (busy timeout).
#pragma once

#include <mutex>

#include "server/store/store.h"

struct sqlite3;
struct sqlite3_stmt;

namespace spinfold::server {

class SqliteStore final : public Store {
 public:
  // Opens (creating it and the directory when missing) DIR/sessions.db in WAL mode and checks it
  // (PRAGMA quick_check); StoreError when the directory is unwritable or the file is not a sound
  // Spinfold database, or stays locked past `busy_timeout`.
  explicit SqliteStore(const std::string& dir,
                       std::chrono::milliseconds busy_timeout = std::chrono::seconds(5));
  ~SqliteStore() override;
  SqliteStore(const SqliteStore&) = delete;
  SqliteStore& operator=(const SqliteStore&) = delete;

  const std::string& path() const override { return path_; }
  std::string_view kind() const override { return "sqlite"; }
  std::optional<std::int64_t> version(const std::string& id) override;
  std::optional<StoredSession> load(const std::string& id) override;
  std::vector<StoredSession> load_all() override;
  std::int64_t save(const StoredSession& row) override;
  void touch(const std::string& id) override;
  bool remove(const std::string& id) override;
  std::int64_t count() override;
  void expire(std::chrono::seconds idle) override;
  bool reachable() override { return true; }  // a local file: errors are per call
  bool save_recording(const StoredRecording& row) override;
  std::optional<StoredRecording> load_recording(const std::string& id) override;
  bool cancel_recording(const std::string& id) override;
  void save_recording_chunk(const std::string& id, std::int64_t index, std::string_view bytes) override;
  std::optional<std::string> load_recording_chunk(const std::string& id, std::int64_t index) override;
  bool remove_recording(const std::string& id) override;
  void touch_recordings(const std::string& owner) override;
  std::int64_t recording_bytes() override;
  void expire_recordings(std::chrono::seconds age, std::chrono::seconds lost,
                         const std::string& reason) override;

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

}  // namespace spinfold::server
