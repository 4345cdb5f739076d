#include "server/jobs/recordings.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "codec/provenance.h"
#include "engine/number_text.h"
#include "render/view.h"
#include "server/frames/render_pool.h"
#include "server/http/problem.h"
#include "server/sessions/session_id.h"

namespace spinfold::server {

namespace {

// The recording threads' CPU priority (nice): encoding yields the cores to the HTTP workers and
// the render threads that serve live viewers.
constexpr int kRecordingNice = 10;

const std::string kRecordings = "/api/v1/recordings";

// At most one row write per job this often while it runs (its progress as other replicas see it).
constexpr auto kProgressWriteInterval = std::chrono::milliseconds(200);

ApiError over_limit(const std::string& limit, long long value, const std::string& reason) {
  return job_over_limit(limit, value, reason, "10");
}

ApiError unknown_recording(const std::string& id, const Limits& limits) {
  return bad(404, "Unknown recording", "id", id,
             "no recording with this id (finished recordings are deleted after " +
                 std::to_string(limits.recording_max_age.count()) + " s)");
}

// The store is away: nothing was started, changed or deleted.
ApiError store_away(const std::string& id, const StoreError& e) {
  std::fprintf(stderr, "spinfold: %s\n", e.what());
  return ApiError{503,
                  "Store unavailable",
                  {{"id", id, "the store of recordings cannot be reached now; retry later"}},
                  "2"};
}

bool active(std::string_view status) {
  return status == "queued" || status == "running";
}

// This process's name in its rows: host, process id and a random part (a restarted process is another).
std::string instance_name() {
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  return std::string(host) + ":" + std::to_string(getpid()) + ":" + new_session_id().substr(0, 8);
}

std::filesystem::path new_directory() {
  std::string pattern = (std::filesystem::temp_directory_path() / "spinfold-recordings-XXXXXX").string();
  if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a directory for recordings");
  return pattern;
}

std::string download_name(const std::string& session, double t_start, double t_end, record::Format format) {
  char name[160];
  std::snprintf(name, sizeof name, "spinfold-%s-t%s-%s.%s", session.substr(0, 8).c_str(),
                shortest(t_start).c_str(), shortest(t_end).c_str(),
                std::string(record::file_extension(format)).c_str());
  return name;
}

}  // namespace

nlohmann::ordered_json recording_json(const RecordingState& r) {
  nlohmann::ordered_json out{{"id", r.id},
                             {"status", job_status_name(r.status)},
                             {"progress", r.progress},
                             {"url", kRecordings + "/" + r.id},
                             {"file", kRecordings + "/" + r.id + "/file"},
                             {"session", r.job.session},
                             {"format", record::format_name(r.job.format)},
                             {"frames", r.frames},
                             {"t_start", r.job.clip.t_start},
                             {"t_end", r.job.clip.t_end},
                             {"fps", r.job.clip.fps},
                             {"speed", r.job.clip.speed},
                             {"width", r.job.frames.view.width},
                             {"height", r.job.frames.view.height},
                             {"bytes", r.bytes}};
  if (r.status == RecordingStatus::failed) out["reason"] = r.reason;
  return out;
}

Recordings::Recordings(const Limits& limits, RenderPool& pool, Store* db)
    : limits_(limits),
      pool_(pool),
      db_(db),
      instance_(instance_name()),
      queue_(
          {.threads = limits.recording_threads,
           .nice = kRecordingNice,
           .max_age = limits.recording_max_age,
           .sync_every = limits.recording_heartbeat,
           .sync = db ? std::function<void()>([this] { heartbeat(); }) : std::function<void()>()},
          [this](Queue::Entry& entry) { run(entry); },
          [](Queue::Entry& entry) {
            std::error_code ignored;
            if (!entry.extra.path.empty()) std::filesystem::remove(entry.extra.path, ignored);
          }) {}

Recordings::~Recordings() {
  queue_.stop();  // before the directory goes
  std::error_code ignored;
  if (!dir_.empty()) std::filesystem::remove_all(dir_, ignored);
}

std::filesystem::path Recordings::directory() {
  std::call_once(dir_made_, [this] { dir_ = new_directory(); });
  return dir_;
}

void Recordings::heartbeat() {
  const std::string lost = "the server recording it stopped answering (no word from it for " +
                           std::to_string(limits_.recording_owner_lost.count()) + " s): record again";
  try {
    db_->touch_recordings(instance_);
    db_->expire_recordings(limits_.recording_max_age, limits_.recording_owner_lost, lost);
    heartbeat_warned_ = false;
  } catch (const StoreError& e) {
    if (!heartbeat_warned_) std::fprintf(stderr, "spinfold: recordings: %s\n", e.what());
    heartbeat_warned_ = true;
  }
}

bool Recordings::save_row(const RecordingState& state) {
  return db_->save_recording({.id = state.id,
                              .owner = instance_,
                              .status = std::string(job_status_name(state.status)),
                              .json = recording_json(state).dump(),
                              .reason = state.reason,
                              .bytes = static_cast<std::int64_t>(state.bytes)});
}

std::string Recordings::start(RecordingJob job) {
  const long long frames = record::frame_count(job.clip);
  if (frames > limits_.max_recording_frames)
    throw bad(422, "Invalid value", "t_end", shortest(job.clip.t_end),
              "the window would take " + std::to_string(frames) + " frames at this fps and speed; at most " +
                  std::to_string(limits_.max_recording_frames) +
                  " (limits.max_recording_frames): shorten it, lower fps or raise speed");
  const long long pixels = static_cast<long long>(job.frames.view.width) * job.frames.view.height;
  if (pixels > limits_.max_recording_pixels)
    throw bad(422, "Invalid value", "width", std::to_string(job.frames.view.width),
              "width × height = " + std::to_string(pixels) + " pixels; at most " +
                  std::to_string(limits_.max_recording_pixels) + " (limits.max_recording_pixels)");
  auto entry = std::make_shared<Queue::Entry>();
  // The session's id (22 characters) first: the front's consistent hashing sends the recording's
  // requests to the replica that records it, the one its session's go to (deploy/nginx/spinfold.conf).
  entry->state.id = job.session + new_session_id();
  entry->state.frames = frames;
  entry->extra.path = directory() / (entry->state.id + "." + std::string(record::file_extension(job.format)));
  entry->state.job = std::move(job);
  queue_.admit(
      entry,
      {.per_client_limit = "max_recordings_per_client",
       .per_client = limits_.max_recordings_per_client,
       .per_client_reason = "this address has that many recordings queued or running: wait for one to "
                            "finish or cancel it (DELETE /api/v1/recordings/{id})",
       .total_limit = "max_recordings",
       .total = limits_.max_recordings,
       .total_reason = "the server keeps that many recordings: delete finished ones, or wait until "
                       "they expire (" +
                       std::to_string(limits_.recording_max_age.count()) + " s after finishing)",
       .retry_after = "10"},
      [this](const Queue::Entries& entries) {
        if (disk_bytes(entries) >= static_cast<std::uint64_t>(limits_.max_recording_disk_bytes))
          throw over_limit("max_recording_disk_bytes", limits_.max_recording_disk_bytes,
                           "the recordings kept fill the disk space allowed to them: delete finished "
                           "ones, or wait until they expire");
      });
  if (db_) {
    // The row before the job is queued (its first progress write updates it); the store's files
    // count against the same allowance.
    try {
      if (db_->recording_bytes() >= limits_.max_recording_disk_bytes) {
        queue_.forget(entry->state.id);
        throw over_limit("max_recording_disk_bytes", limits_.max_recording_disk_bytes,
                         "the recordings kept in the store fill the space allowed to them: delete finished "
                         "ones, or wait until they expire");
      }
      save_row(entry->state);
    } catch (const StoreError& e) {
      queue_.forget(entry->state.id);
      throw store_away(entry->state.id, e);
    }
  }
  queue_.enqueue(entry);
  return entry->state.id;
}

RecordingState Recordings::state(const std::string& id) {
  std::optional<RecordingState> s = queue_.find(id);
  if (!s) throw unknown_recording(id, limits_);
  return std::move(*s);
}

namespace {

ApiError not_ready(const std::string& status, const std::string& reason) {
  return bad(
      409, "Not ready", "status", status,
      status == "failed" ? "the recording failed: " + reason : "the file is there once the status is done");
}

}  // namespace

nlohmann::ordered_json Recordings::describe(const std::string& id) {
  if (!db_) return recording_json(state(id));
  std::optional<StoredRecording> row;
  try {
    row = db_->load_recording(id);
  } catch (const StoreError& e) {
    throw store_away(id, e);
  }
  if (!row) throw unknown_recording(id, limits_);
  auto out = nlohmann::ordered_json::parse(row->json);
  std::string status = row->status, reason = row->reason;
  // Its owner silent too long: lost, whether or not a replica's sweep has said so yet.
  if (active(status) && row->silent_ms > std::chrono::milliseconds(limits_.recording_owner_lost).count()) {
    status = "failed";
    reason = "the server recording it stopped answering (no word from it for " +
             std::to_string(row->silent_ms / 1000) + " s): record again";
  }
  out["status"] = status;
  out.erase("reason");
  if (status == "failed") out["reason"] = reason;
  if (status == "done") out["progress"] = 1.0;
  out["bytes"] = status == "failed" || status == "cancelled" ? 0 : row->bytes;
  return out;
}

RecordingDownload Recordings::file(const std::string& id) {
  if (!db_) {
    const RecordingState s = state(id);
    if (s.status != RecordingStatus::done) throw not_ready(std::string(job_status_name(s.status)), s.reason);
    const std::filesystem::path path = queue_.locked([&](const Queue::Entries& entries) {
      const auto it = entries.find(id);
      return it == entries.end() ? std::filesystem::path() : it->second->extra.path;
    });
    auto stream =
        std::make_shared<std::ifstream>(path, std::ios::binary);  // readable even if deleted meanwhile
    if (!*stream) throw bad(404, "Unknown recording", "id", id, "the recording's file is gone");
    return {.bytes = s.bytes,
            .content_type = std::string(record::content_type(s.job.format)),
            .file_name = download_name(s.job.session, s.job.clip.t_start, s.job.clip.t_end, s.job.format),
            .read = [stream](std::uint64_t offset, std::uint64_t length) {
              std::string buffer(std::min<std::uint64_t>(length, 64 * 1024), '\0');
              stream->seekg(static_cast<std::streamoff>(offset));
              stream->read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
              buffer.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, stream->gcount())));
              return buffer;
            }};
  }
  const nlohmann::ordered_json view = describe(id);
  const std::string status = view["status"];
  if (status != "done") throw not_ready(status, view.value("reason", ""));
  const auto format = record::parse_format(view["format"].get<std::string>()).value_or(record::Format::webm);
  // One chunk at a time from the store, the last one kept for the reads within it.
  struct Chunks {
    std::mutex mutex;
    std::int64_t index = -1;
    std::string data;
  };
  auto chunks = std::make_shared<Chunks>();
  return {.bytes = view["bytes"].get<std::uint64_t>(),
          .content_type = std::string(record::content_type(format)),
          .file_name = download_name(view["session"], view["t_start"], view["t_end"], format),
          .read = [db = db_, id, chunks](std::uint64_t offset, std::uint64_t length) -> std::string {
            const std::lock_guard lock(chunks->mutex);
            const auto index = static_cast<std::int64_t>(offset / kRecordingChunkBytes);
            if (chunks->index != index) {
              try {
                std::optional<std::string> data = db->load_recording_chunk(id, index);
                if (!data) return "";
                chunks->data = std::move(*data);
                chunks->index = index;
              } catch (const StoreError& e) {
                std::fprintf(stderr, "spinfold: %s\n", e.what());
                return "";
              }
            }
            const std::uint64_t within = offset % kRecordingChunkBytes;
            if (within >= chunks->data.size()) return "";
            return chunks->data.substr(within, length);
          }};
}

bool Recordings::cancel_or_delete(const std::string& id) {
  if (db_) {
    std::optional<StoredRecording> row;
    try {
      row = db_->load_recording(id);
      if (!row) throw unknown_recording(id, limits_);
      if (active(row->status) && db_->cancel_recording(id)) {
        // Ours: stopped here at once; another replica's stops at its next row write.
        queue_.cancel(id);
        return true;
      }
      db_->remove_recording(id);
    } catch (const StoreError& e) {
      throw store_away(id, e);
    }
    std::error_code ignored;
    if (const Queue::Ptr entry = queue_.erase_finished(id))
      std::filesystem::remove(entry->extra.path, ignored);
    return false;
  }
  // Cancelled now: a queued job never starts, a running one stops at its next frame and removes
  // its file (whatever it was about to become).
  Queue::Ptr deleted;
  const Queue::Removed removed = queue_.cancel_or_delete(id, &deleted);
  if (removed == Queue::Removed::unknown)
    throw bad(404, "Unknown recording", "id", id, "no recording with this id (it may have expired)");
  if (removed == Queue::Removed::cancelled) return true;
  std::error_code ignored;
  std::filesystem::remove(deleted->extra.path, ignored);
  return false;
}

std::uint64_t Recordings::disk_bytes(const Queue::Entries& entries) {
  std::uint64_t bytes = 0;
  for (const auto& [id, e] : entries)
    if (!e->extra.path.empty()) bytes += e->state.bytes;  // (a file in the store is counted there)
  return bytes;
}

void Recordings::run(Queue::Entry& entry) {
  const RecordingJob& job = entry.state.job;  // not changed while running
  const std::string key = "recording:" + entry.state.id;
  RecordingStatus status = RecordingStatus::done;
  std::string reason;
  try {
    nlohmann::ordered_json provenance = provenance_json(job.frames.scene, "");
    provenance["t_start"] = job.clip.t_start;
    provenance["t_end"] = job.clip.t_end;
    provenance["view"] = std::string(render::view_name(job.frames.view.kind));
    auto recorder = record::open_clip_writer(
        job.format, entry.extra.path,
        {job.frames.view.width, job.frames.view.height, job.clip.fps, provenance.dump()});
    const auto render = [&](render::Snapshot snapshot, const render::ViewOptions& view) {
      try {
        return pool_.render(key, std::move(snapshot), view, RenderPriority::background).get();
      } catch (const std::future_error&) {
        throw record::RecordError("rendering is unavailable (no OpenGL context)");
      }
    };
    auto last_write = std::chrono::steady_clock::now() - kProgressWriteInterval;
    bool store_warned = false;
    const auto progress = [&](long long done, long long total) {
      queue_.progress(entry, static_cast<double>(done), static_cast<double>(total));
      std::optional<RecordingState> snapshot = queue_.locked([&](const Queue::Entries& entries) {
        entry.state.bytes = recorder->bytes();
        if (disk_bytes(entries) > static_cast<std::uint64_t>(limits_.max_recording_disk_bytes))
          throw record::RecordError("the recordings' files passed the disk space allowed to them (" +
                                    std::to_string(limits_.max_recording_disk_bytes) +
                                    " bytes, limits.max_recording_disk_bytes)");
        if (!db_ || std::chrono::steady_clock::now() - last_write < kProgressWriteInterval)
          return std::optional<RecordingState>();
        return std::optional<RecordingState>(entry.state);
      });
      if (!snapshot) return !entry.cancel.load();
      // The row, for every replica (and a cancel or deletion through another one stops the job here).
      last_write = std::chrono::steady_clock::now();
      try {
        if (!save_row(*snapshot)) entry.cancel = true;
      } catch (const StoreError& e) {  // the store away for a moment: the job goes on
        if (!store_warned)
          std::fprintf(stderr, "spinfold: recording %s: %s\n", snapshot->id.c_str(), e.what());
        store_warned = true;
      }
      return !entry.cancel.load();
    };
    if (!record::record_clip(job.clip, job.frames, *recorder, render, progress))
      status = RecordingStatus::cancelled;
  } catch (const std::exception& e) {  // record::RecordError, or out of memory
    status = entry.cancel ? RecordingStatus::cancelled : RecordingStatus::failed;
    reason = e.what();
  }
  if (entry.cancel) status = RecordingStatus::cancelled;  // a cancel is final, even one at the end
  if (queue_.stopping() &&
      status == RecordingStatus::cancelled) {  // not the user's cancel: the server stopped
    status = RecordingStatus::failed;
    reason = "the server recording it stopped: record again";
  }
  std::error_code error;
  const auto size = status == RecordingStatus::done ? std::filesystem::file_size(entry.extra.path, error) : 0;
  if (db_ && status == RecordingStatus::done) {
    // The file into the store (every replica serves it from there), then the row says done.
    try {
      store_file(entry.state.id, entry.extra.path);
    } catch (const StoreError& e) {
      status = RecordingStatus::failed;
      reason = std::string("the store could not take the file: ") + e.what();
    }
  }
  if (status != RecordingStatus::done || db_) std::filesystem::remove(entry.extra.path, error);
  const RecordingState snapshot = queue_.locked([&](const Queue::Entries&) {
    entry.state.status = status;
    entry.state.reason = status == RecordingStatus::failed ? reason : "";
    entry.state.bytes = status == RecordingStatus::done ? size : 0;
    if (db_) entry.extra.path.clear();  // the file is the store's now (not this disk's allowance)
    if (status == RecordingStatus::done) entry.state.progress = 1.0;
    if (status != RecordingStatus::cancelled) entry.finished = std::chrono::steady_clock::now();
    return entry.state;
  });
  if (!db_) return;
  try {
    if (!save_row(snapshot) && status == RecordingStatus::done) {
      // Cancelled through another replica while the file was stored: the row says cancelled, and
      // the next expiry sweep removes the file.
      queue_.locked([&](const Queue::Entries&) { entry.state.status = RecordingStatus::cancelled; });
    }
  } catch (const StoreError& e) {
    // The row stays running until the owner's silence makes it failed (recording_owner_lost).
    std::fprintf(stderr, "spinfold: recording %s: %s\n", snapshot.id.c_str(), e.what());
  }
}

void Recordings::store_file(const std::string& id, const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw StoreError("cannot read the recorded file " + path.string());
  std::string chunk(static_cast<std::size_t>(kRecordingChunkBytes), '\0');
  for (std::int64_t index = 0;; ++index) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    const auto got = in.gcount();
    if (got <= 0) break;
    db_->save_recording_chunk(id, index, std::string_view(chunk.data(), static_cast<std::size_t>(got)));
    if (got < static_cast<std::streamsize>(chunk.size())) break;
  }
}

}  // namespace spinfold::server
