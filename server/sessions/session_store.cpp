// SessionStore with a durable store (server/store/store.h): what a session is made of goes to its
// row, a session another process changed is rebuilt from its row, and sessions come back at start.
// Memory is a cache of the store: each request compares the row's version with the one the memory
// was built from (one SELECT by primary key) and rebuilds when they differ.
#include "server/sessions/session_store.h"

#include <cstdio>

#include "codec/json_text.h"
#include "codec/scene_json.h"
#include "server/sessions/session_id.h"
#include "server/store/store.h"

namespace spinfold::server {

namespace {

using Clock = std::chrono::steady_clock;

// How often the player stores the time of a playing session [s]: a crash loses at most this much play.
constexpr auto kPlaySaveInterval = std::chrono::seconds(1);
// How often a session only read (GET, frames, streams) marks its row used, against expiry.
constexpr auto kTouchInterval = std::chrono::seconds(60);

void warn(const std::string& what) {
  std::fprintf(stderr, "spinfold: %s\n", what.c_str());
}

// One line a second at most: a store away for a while would otherwise log every tick of the player.
void warn_store_error(const std::string& what) {
  static std::mutex mutex;
  static Clock::time_point last{};
  static int held = 0;
  const std::lock_guard lock(mutex);
  const auto now = Clock::now();
  if (now - last < std::chrono::seconds(1)) {
    ++held;
    return;
  }
  last = now;
  if (held > 0) std::fprintf(stderr, "spinfold: (%d more store errors in the last second)\n", held);
  held = 0;
  warn(what);
}

StoredSession row_of(const std::string& id, const Session& s) {
  return {.id = id,
          .version = s.stored_version,
          .scene = scene_to_json(s.scene).dump(),
          .timeline = s.timeline.dump(),
          .t = s.run.state.t,
          .playing = s.playing,
          .rate = s.rate};
}

// Rebuilds the session from its row (its lock held): the replay of scene and timeline to the stored
// time, bit for bit, paused. False (on stderr) when the row does not parse.
bool load_row(Session& s, const StoredSession& row) {
  const auto refuse = [&row](const std::string& why) {
    warn("stored session " + row.id + " cannot be restored: " + why);
    return false;
  };
  // The same strict reading as a request body: a row cut short or with bytes appended is refused
  // rather than read in part.
  nlohmann::json scene_json;
  nlohmann::json timeline;
  try {
    scene_json = parse_json_text(row.scene);
    timeline = parse_json_text(row.timeline);
  } catch (const JsonTextError& e) {
    return refuse(e.what());
  }
  const SceneParse scene = parse_scene(scene_json);
  if (!scene.scene) return refuse(describe_errors(scene.errors));
  const Rebuild rebuilt = rebuild(s, *scene.scene, timeline, row.t, kNoStepLimit);
  if (!rebuilt.errors.empty()) return refuse(describe_errors(rebuilt.errors));
  // Paused: the owner that was playing it may be gone (a crash) or still alive (another replica).
  s.playing = false;
  s.rate = row.rate;
  s.stored_version = row.version;
  s.stored_at = Clock::now();
  s.unsaved = false;
  return true;
}

// A session rebuilt from its row, or nullptr when the row does not parse.
std::shared_ptr<Session> loaded(const StoredSession& row) {
  auto s = std::make_shared<Session>();
  const std::lock_guard lock(s->mutex);
  if (!load_row(*s, row)) return nullptr;
  s->last_used = Clock::now();
  return s;
}

// Writes the session's row if it is still the version this memory was built from: false when
// another process changed or deleted it first; StoreError when the store cannot be written.
bool write(Store& db, const std::string& id, Session& s) {
  const std::int64_t version = db.save(row_of(id, s));
  if (version == 0) return false;
  s.stored_version = version;
  s.stored_at = Clock::now();
  s.unsaved = false;
  return true;
}

}  // namespace

std::size_t SessionStore::count_locked() {
  if (db_) try {
      return static_cast<std::size_t>(db_->count());
    } catch (const StoreError& e) {
      warn_store_error(e.what());
    }
  return sessions_.size();
}

void SessionStore::expire_stored() {
  if (db_) try {
      db_->expire(idle_expiry_);
    } catch (const StoreError& e) {
      warn_store_error(e.what());
    }
}

void SessionStore::forget(const std::string& id, const Session* session) {
  const std::lock_guard lock(mutex_);
  const auto it = sessions_.find(id);
  if (it != sessions_.end() && it->second.get() == session) sessions_.erase(it);
}

std::shared_ptr<Session> SessionStore::checked(const std::string& id, std::shared_ptr<Session> memory) {
  try {
    if (memory) {
      const std::lock_guard lock(memory->mutex);
      const std::optional<std::int64_t> version = db_->version(id);
      if (version && *version == memory->stored_version) {
        if (Clock::now() - memory->stored_at > kTouchInterval) {
          db_->touch(id);
          memory->stored_at = Clock::now();
        }
        return memory;
      }
      // Changed by another process (or a write here failed): rebuild; deleted: forget.
      const std::optional<StoredSession> row = version ? db_->load(id) : std::nullopt;
      if (row && load_row(*memory, *row)) return memory;
      forget(id, memory.get());
      return nullptr;
    }
    // Not in memory: created by another process, or this one forgot it.
    const std::optional<StoredSession> row = db_->load(id);
    if (!row) return nullptr;
    auto s = loaded(*row);
    if (!s) return nullptr;
    const std::lock_guard lock(mutex_);
    return sessions_.emplace(id, s).first->second;  // another thread's load if it came first
  } catch (const StoreError& e) {
    // The store cannot be read: what this process has, when it is what the store holds (no other
    // process can change the row while the store is away); otherwise the error (find_session: 503):
    // this process has nothing, or memory ahead of the store (a refused change must not be served).
    if (!memory) throw;
    {
      const std::lock_guard lock(memory->mutex);
      if (memory->stored_version == 0) throw;
    }
    warn_store_error(e.what());
    return memory;
  }
}

SessionStore::Saved SessionStore::save(const std::string& id, Session& s) {
  if (!db_) return Saved::stored;
  const bool fresh = s.stored_version == 0;
  Saved saved = Saved::conflict;
  try {
    if (write(*db_, id, s)) return Saved::stored;
  } catch (const StoreError& e) {
    warn_store_error(e.what());
    saved = Saved::failed;
  }
  s.stored_version = 0;  // the memory is ahead of the store: the next find reloads it
  s.playing = false;
  if (fresh) forget(id, &s);
  return saved;
}

void SessionStore::save_played(const std::string& id, Session& s, bool now) {
  if (!db_ || !s.unsaved || s.stored_version == 0) return;
  if (!now && s.playing && Clock::now() - s.stored_at < kPlaySaveInterval) return;
  try {
    if (!write(*db_, id, s)) {
      // Another process changed the session: it is theirs now; this one stops playing it.
      s.stored_version = 0;
      s.playing = false;
    }
  } catch (const StoreError& e) {
    warn_store_error(e.what());  // kept unsaved: the next tick tries again
  }
}

bool SessionStore::deleted_elsewhere(const std::string& id) {
  if (!db_) return false;
  std::shared_ptr<Session> memory;
  {
    const std::lock_guard lock(mutex_);
    const auto it = sessions_.find(id);
    if (it != sessions_.end()) memory = it->second;
  }
  if (memory) {
    const std::lock_guard lock(memory->mutex);
    if (memory->stored_version == 0) return false;  // being created (or ahead of the store): not gone
  }
  try {
    if (db_->version(id)) return false;
  } catch (const StoreError& e) {
    warn_store_error(e.what());
    return false;
  }
  const std::lock_guard lock(mutex_);
  sessions_.erase(id);
  return true;
}

void SessionStore::sweep_deleted_elsewhere() {
  constexpr auto kSweepInterval = std::chrono::seconds(30);
  if (!db_) return;
  std::vector<std::string> idle;
  {
    const std::lock_guard lock(mutex_);
    const auto now = Clock::now();
    if (now - last_sweep_ < kSweepInterval) return;
    last_sweep_ = now;
    for (const auto& [id, s] : sessions_)
      if (now - s->last_used > kSweepInterval) idle.push_back(id);
  }
  for (const std::string& id : idle) deleted_elsewhere(id);
}

void SessionStore::flush() {
  for (const auto& [id, s] : entries()) {
    const std::lock_guard lock(s->mutex);
    save_played(id, *s, true);
  }
}

std::size_t SessionStore::restore() {
  if (!db_) return 0;
  const auto start = Clock::now();
  std::size_t restored = 0;
  std::vector<StoredSession> rows;
  try {
    rows = db_->load_all();
  } catch (const StoreError& e) {
    if (db_->kind() != "postgresql") throw;  // a local file that cannot be read is a start error
    // A database not up yet: replicas may start first; each session loads when first asked for.
    warn(std::string(e.what()) + "; sessions load when first asked for");
    return 0;
  }
  for (const StoredSession& row : rows) {
    auto s = loaded(row);
    if (!s) continue;
    const std::lock_guard lock(mutex_);
    sessions_[row.id] = s;
    ++restored;
  }
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  std::fprintf(stderr, "spinfold: restored %zu sessions from %s in %.0f ms\n", restored, db_->path().c_str(),
               ms);
  return restored;
}

// ---- Memory: creation, lookup, expiry (with the rows of the store when there is one).

std::shared_ptr<Session> SessionStore::create(const Scene& scene, std::string& id) {
  const std::lock_guard lock(mutex_);
  expire_idle_locked();
  if (count_locked() >= max_sessions_) return nullptr;
  do id = new_session_id();  // 128 random bits: a repeat is never expected, but never reused
  while (sessions_.count(id) > 0);
  auto session = std::make_shared<Session>();
  restart(*session, scene);
  session->last_used = std::chrono::steady_clock::now();
  sessions_[id] = session;
  return session;
}

std::shared_ptr<Session> SessionStore::find(const std::string& id) {
  std::shared_ptr<Session> session;
  {
    const std::lock_guard lock(mutex_);
    const auto it = sessions_.find(id);
    if (it != sessions_.end()) {
      it->second->last_used = std::chrono::steady_clock::now();
      session = it->second;
    }
  }
  return db_ ? checked(id, std::move(session)) : session;
}

bool SessionStore::erase(const std::string& id) {
  const bool row = db_ && db_->remove(id);  // first: a failure (StoreError) changes nothing
  const std::lock_guard lock(mutex_);
  return sessions_.erase(id) > 0 || row;
}

std::size_t SessionStore::size() {
  const std::lock_guard lock(mutex_);
  return sessions_.size();
}

std::vector<std::shared_ptr<Session>> SessionStore::all() {
  const std::lock_guard lock(mutex_);
  std::vector<std::shared_ptr<Session>> list;
  for (const auto& [id, session] : sessions_) list.push_back(session);
  return list;
}

std::vector<std::pair<std::string, std::shared_ptr<Session>>> SessionStore::entries() {
  const std::lock_guard lock(mutex_);
  return {sessions_.begin(), sessions_.end()};
}

void SessionStore::expire_idle_locked() {
  const auto now = std::chrono::steady_clock::now();
  for (auto it = sessions_.begin(); it != sessions_.end();)
    it = now - it->second->last_used > idle_expiry_ ? sessions_.erase(it) : std::next(it);
  expire_stored();  // rows no process used for as long
}

}  // namespace spinfold::server
