// The stores a test can run against: a new SQLite directory, or a new database on the PostgreSQL
// server ctest starts for the run (tests/server/postgres_fixture.sh; its folder in
// SPINFOLD_TEST_POSTGRES_DIR). Shared by the conformance suite and the store tests.
#pragma once

#include <libpq-fe.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "server/store/store.h"

namespace spinfold::test {

namespace fs = std::filesystem;
using spinfold::server::open_store;
using spinfold::server::Store;

// The fixture's folder, or "" when no PostgreSQL was started for this run.
inline std::string postgres_dir() {
  const char* dir = std::getenv("SPINFOLD_TEST_POSTGRES_DIR");
  return dir ? dir : "";
}

inline std::string fixture(const std::string& action) {
  return "bash " SPINFOLD_SOURCE_DIR "/tests/server/postgres_fixture.sh " + action + " " + postgres_dir();
}

inline std::string admin_url() {
  return "postgresql:///postgres?host=" + postgres_dir() + "&port=54329&user=spinfold";
}

// Runs SQL on the fixture's server as its owner; false (and the reason on stderr) on failure.
inline bool admin(const std::string& url, const std::string& sql) {
  PGconn* c = PQconnectdb(url.c_str());
  PGresult* r = PQexec(c, sql.c_str());
  const ExecStatusType status = PQresultStatus(r);
  const bool ok = status == PGRES_COMMAND_OK || status == PGRES_TUPLES_OK;
  if (!ok) std::fprintf(stderr, "%s: %s", sql.c_str(), PQerrorMessage(c));
  PQclear(r);
  PQfinish(c);
  return ok;
}

// A store of its own for one test: a new SQLite directory, or a new PostgreSQL database.
class Backend {
 public:
  explicit Backend(const std::string& kind) : kind_(kind) {
    static int count = 0;  // one test binary at a time per database name (pid)
    const std::string name = "spinfold_test_" + std::to_string(getpid()) + "_" + std::to_string(++count);
    if (kind == "sqlite") {
      dir_ = fs::temp_directory_path() / name;
    } else {
      database_ = name;
      created_ = admin(admin_url(), "CREATE DATABASE " + name);
    }
  }
  ~Backend() {
    if (!dir_.empty()) fs::remove_all(dir_);
    if (created_) admin(admin_url(), "DROP DATABASE " + database_ + " WITH (FORCE)");
  }
  std::string url() const {
    return "postgresql:///" + database_ + "?host=" + postgres_dir() + "&port=54329&user=spinfold";
  }
  // A new handle on the test's store (a second process would open its own).
  std::unique_ptr<Store> open() const {
    return kind_ == "sqlite" ? open_store("", dir_.string()) : open_store(url(), "");
  }
  bool ready() const { return kind_ == "sqlite" || created_; }
  const std::string& kind() const { return kind_; }
  // What `spinfold serve` is given to use this store.
  std::vector<std::string> serve_args() const {
    if (kind_ == "sqlite") return {"--data-dir", dir_.string()};
    return {"--store", url()};
  }

 private:
  std::string kind_;
  fs::path dir_;
  std::string database_;
  bool created_ = false;
};

}  // namespace spinfold::test
