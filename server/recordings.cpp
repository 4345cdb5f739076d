#include "server/recordings.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstdlib>

#include "codec/provenance.h"
#include "engine/number_text.h"
#include "render/view.h"
#include "server/problem.h"
#include "server/render_pool.h"
#include "server/session_id.h"

namespace spinfold::server {

namespace {

// The recording threads' CPU priority (nice): encoding yields the cores to the HTTP workers and
// the render threads that serve live viewers.
constexpr int kRecordingNice = 10;

ApiError over_limit(const std::string& limit, long long value, const std::string& reason) {
  return {429, "Too many requests", {{"limits." + limit, std::to_string(value), reason}}, "10"};
}

}  // namespace

std::string_view status_name(RecordingStatus status) {
  switch (status) {
    case RecordingStatus::queued: return "queued";
    case RecordingStatus::running: return "running";
    case RecordingStatus::done: return "done";
    case RecordingStatus::failed: return "failed";
    case RecordingStatus::cancelled: return "cancelled";
  }
  return "failed";
}

struct Recordings::Entry {
  RecordingState state;  // guarded by Recordings::mutex_
  std::filesystem::path path;
  std::atomic<bool> cancel{false};
  std::chrono::steady_clock::time_point finished;  // done, failed or cancelled at (guarded)
  bool active() const {
    return state.status == RecordingStatus::queued || state.status == RecordingStatus::running;
  }
};

Recordings::Recordings(const Limits& limits, RenderPool& pool) : limits_(limits), pool_(pool) {
  std::string pattern = (std::filesystem::temp_directory_path() / "spinfold-recordings-XXXXXX").string();
  if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a directory for recordings");
  dir_ = pattern;
  for (int i = 0; i < std::max(1, limits_.recording_threads); ++i) threads_.emplace_back([this] { work(); });
}

Recordings::~Recordings() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
    for (auto& [id, entry] : entries_) entry->cancel = true;
  }
  wake_.notify_all();
  for (auto& thread : threads_) thread.join();
  std::error_code ignored;
  std::filesystem::remove_all(dir_, ignored);
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
  auto entry = std::make_shared<Entry>();
  // The session's id (22 characters) first: the front's consistent hashing sends the recording's
  // requests to the replica that records it, the one its session's go to (deploy/nginx/spinfold.conf).
  entry->state.id = job.session + new_session_id();
  entry->state.frames = frames;
  entry->path = dir_ / (entry->state.id + "." + std::string(record::file_extension(job.format)));
  entry->state.job = std::move(job);
  {
    const std::lock_guard lock(mutex_);
    prune_locked();
    int of_client = 0;
    for (const auto& [id, e] : entries_)
      of_client += e->active() && e->state.job.client == entry->state.job.client;
    if (of_client >= limits_.max_recordings_per_client)
      throw over_limit("max_recordings_per_client", limits_.max_recordings_per_client,
                       "this address has that many recordings queued or running: wait for one to finish "
                       "or cancel it (DELETE /api/v1/recordings/{id})");
    if (static_cast<int>(entries_.size()) >= limits_.max_recordings)
      throw over_limit("max_recordings", limits_.max_recordings,
                       "the server keeps that many recordings: delete finished ones, or wait until they "
                       "expire (" +
                           std::to_string(limits_.recording_max_age.count()) + " s after finishing)");
    if (disk_bytes_locked() >= static_cast<std::uint64_t>(limits_.max_recording_disk_bytes))
      throw over_limit("max_recording_disk_bytes", limits_.max_recording_disk_bytes,
                       "the recordings kept fill the disk space allowed to them: delete finished ones, or "
                       "wait until they expire");
    entries_[entry->state.id] = entry;
    queue_.push_back(entry);
  }
  wake_.notify_one();
  return entry->state.id;
}

RecordingState Recordings::state(const std::string& id) {
  const std::lock_guard lock(mutex_);
  prune_locked();
  const auto it = entries_.find(id);
  if (it == entries_.end())
    throw bad(404, "Unknown recording", "id", id,
              "no recording with this id (finished recordings are deleted after " +
                  std::to_string(limits_.recording_max_age.count()) + " s)");
  return it->second->state;
}

std::filesystem::path Recordings::file(const std::string& id) {
  const RecordingState s = state(id);
  if (s.status != RecordingStatus::done)
    throw bad(409, "Not ready", "status", std::string(status_name(s.status)),
              s.status == RecordingStatus::failed ? "the recording failed: " + s.reason
                                                  : "the file is there once the status is done");
  const std::lock_guard lock(mutex_);
  return entries_.at(id)->path;
}

bool Recordings::cancel_or_delete(const std::string& id) {
  std::shared_ptr<Entry> entry;
  {
    const std::lock_guard lock(mutex_);
    const auto it = entries_.find(id);
    if (it == entries_.end())
      throw bad(404, "Unknown recording", "id", id, "no recording with this id (it may have expired)");
    entry = it->second;
    if (entry->active()) {
      // Cancelled now: a queued job never starts, a running one stops at its next frame and
      // removes its file (whatever it was about to become).
      entry->cancel = true;
      std::erase(queue_, entry);
      entry->state.status = RecordingStatus::cancelled;
      entry->finished = std::chrono::steady_clock::now();
      return true;
    }
    entries_.erase(it);
  }
  std::error_code ignored;
  std::filesystem::remove(entry->path, ignored);
  return false;
}

void Recordings::prune_locked() {
  const auto now = std::chrono::steady_clock::now();
  for (auto it = entries_.begin(); it != entries_.end();) {
    const Entry& e = *it->second;
    if (!e.active() && now - e.finished >= limits_.recording_max_age) {
      std::error_code ignored;
      std::filesystem::remove(e.path, ignored);
      it = entries_.erase(it);
    } else {
      ++it;
    }
  }
}

std::uint64_t Recordings::disk_bytes_locked() const {
  std::uint64_t bytes = 0;
  for (const auto& [id, e] : entries_) bytes += e->state.bytes;
  return bytes;
}

void Recordings::work() {
  // Linux: nice applies to this thread only (its own task id).
  setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), kRecordingNice);
  for (;;) {
    std::shared_ptr<Entry> entry;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      entry = queue_.front();
      queue_.pop_front();
      entry->state.status = RecordingStatus::running;
    }
    run(*entry);
  }
}

void Recordings::run(Entry& entry) {
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
        job.format, entry.path,
        {job.frames.view.width, job.frames.view.height, job.clip.fps, provenance.dump()});
    const auto render = [&](render::Snapshot snapshot, const render::ViewOptions& view) {
      try {
        return pool_.render(key, std::move(snapshot), view, RenderPriority::background).get();
      } catch (const std::future_error&) {
        throw record::RecordError("rendering is unavailable (no OpenGL context)");
      }
    };
    const auto progress = [&](long long done, long long total) {
      const std::lock_guard lock(mutex_);
      entry.state.progress =
          std::max(entry.state.progress, static_cast<double>(done) / static_cast<double>(total));
      entry.state.bytes = recorder->bytes();
      if (disk_bytes_locked() > static_cast<std::uint64_t>(limits_.max_recording_disk_bytes))
        throw record::RecordError("the recordings' files passed the disk space allowed to them (" +
                                  std::to_string(limits_.max_recording_disk_bytes) +
                                  " bytes, limits.max_recording_disk_bytes)");
      return !entry.cancel.load();
    };
    if (!record::record_clip(job.clip, job.frames, *recorder, render, progress))
      status = RecordingStatus::cancelled;
  } catch (const std::exception& e) {  // record::RecordError, or out of memory
    status = entry.cancel ? RecordingStatus::cancelled : RecordingStatus::failed;
    reason = e.what();
  }
  if (entry.cancel) status = RecordingStatus::cancelled;  // a cancel is final, even one at the end
  std::error_code error;
  const auto size = status == RecordingStatus::done ? std::filesystem::file_size(entry.path, error) : 0;
  if (status != RecordingStatus::done) std::filesystem::remove(entry.path, error);
  const std::lock_guard lock(mutex_);
  entry.state.status = status;
  entry.state.reason = status == RecordingStatus::failed ? reason : "";
  entry.state.bytes = status == RecordingStatus::done ? size : 0;
  if (status == RecordingStatus::done) entry.state.progress = 1.0;
  if (status != RecordingStatus::cancelled) entry.finished = std::chrono::steady_clock::now();
}

}  // namespace spinfold::server
