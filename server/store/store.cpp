#include "server/store/store.h"

#include <cstdlib>

#include "server/store/postgres_store.h"
#include "server/store/sqlite_store.h"

namespace spinfold::server {

bool is_postgres_url(const std::string& url) {
  return url.rfind("postgresql://", 0) == 0 || url.rfind("postgres://", 0) == 0;
}

std::unique_ptr<Store> open_store(const std::string& url, const std::string& data_dir) {
  if (!url.empty()) {
    if (!is_postgres_url(url))
      throw StoreError("--store '" + url +
                       "': not a postgresql:// URL (leave it out for SQLite in --data-dir)");
    return std::make_unique<PostgresStore>(url);
  }
  if (data_dir.empty()) return nullptr;
  return std::make_unique<SqliteStore>(data_dir);
}

std::string default_data_dir() {
  const char* state = std::getenv("XDG_STATE_HOME");
  if (state && *state == '/') return std::string(state) + "/spinfold";
  const char* home = std::getenv("HOME");
  if (home && *home) return std::string(home) + "/.local/state/spinfold";
  return "";
}

}  // namespace spinfold::server
