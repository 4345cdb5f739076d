// The session store in PostgreSQL (libpq): for replicas on several hosts, which cannot share a
// SQLite file. The same rows and guarantees as the SQLite store ((store.h)): a write is one
// statement, committed before the API acknowledges it; the version test makes a lost race a 409.
// The server creates and migrates the schema (table spinfold_schema, under an advisory lock so that
// replicas starting together take turns). A lost connection is reopened with backoff (0.1 s doubling
// to 5 s); meanwhile every call throws StoreError (the API answers 503) and nothing is half-written.
#pragma once

#include <chrono>
#include <mutex>

#include "server/store/store.h"

struct pg_conn;
struct pg_result;

namespace spinfold::server {

class PostgresStore final : public Store {
 public:
  // `url`: a libpq connection URI (postgresql://user:password@host:port/db?…). StoreError when it
  // is malformed or the database holds a newer Spinfold schema; a database that does not answer
  // yet is not an error here (the first call that needs it tries again).
  explicit PostgresStore(const std::string& url);
  ~PostgresStore() override;
  PostgresStore(const PostgresStore&) = delete;
  PostgresStore& operator=(const PostgresStore&) = delete;

  const std::string& path() const override { return path_; }
  std::string_view kind() const override { return "postgresql"; }
  std::optional<std::int64_t> version(const std::string& id) override;
  std::optional<StoredSession> load(const std::string& id) override;
  std::vector<StoredSession> load_all() override;
  std::int64_t save(const StoredSession& row) override;
  void touch(const std::string& id) override;
  bool remove(const std::string& id) override;
  std::int64_t count() override;
  void expire(std::chrono::seconds idle) override;
  bool reachable() override;
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

  // The schema version this build creates and reads.
  static constexpr int kSchemaVersion = 2;

 private:
  class Result;
  enum class Retry { no, once };  // reads may be repeated on a new connection; writes never are
  // `binary`: the parameters sent as bytes (bytea), by index; `binary_result`: columns read as bytes.
  Result run(const char* sql, const std::vector<std::string>& params, Retry retry,
             const std::vector<bool>& binary = {}, bool binary_result = false);
  void connect_locked();
  void migrate_locked();
  void drop_connection_locked(const std::string& why);

  using Clock = std::chrono::steady_clock;
  std::mutex mutex_;  // one connection, used by one thread at a time
  std::string url_;
  std::string path_;  // the URL without its password
  pg_conn* conn_ = nullptr;
  Clock::time_point next_attempt_{};
  std::chrono::milliseconds backoff_{0};
  std::string last_error_;
  Clock::time_point last_warning_{};
};

}  // namespace spinfold::server
