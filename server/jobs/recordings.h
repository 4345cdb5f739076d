// Recordings of a session's time window (POST /api/v1/sessions/{id}/recordings): jobs that replay a
// copy of the session's timeline (the live session is never paused or changed), draw each frame in
// the render pool at background priority (live frames go first) and encode it on a recording thread
// of lower CPU priority, into a file in the server's temporary directory. Each job is queued →
// running → done | failed (with a reason) | cancelled, its progress 0…1 never going back (a
// JobQueue: server/jobs/job_queue.h, whose sync thread is the heartbeat below). Limits
// (server::Limits): frames, pixels, jobs per client, jobs kept, disk bytes, age.
//
// With a session store (SQLite or PostgreSQL), each job also has a row there, and its finished file
// is stored in chunks beside it, so that every replica answers for every recording: its status,
// its file, its cancellation. The replica that records it (the owner) writes the row as it goes and
// touches it every limits.recording_heartbeat; a job whose owner is silent for
// limits.recording_owner_lost (a host lost) is failed with that reason. Files go into the store
// rather than on a shared path: the store is already shared by every replica and backed up, and a
// shared file system (NFS, a ReadWriteMany volume) would be one more system to run; the price is
// the store's size (limits.max_recording_disk_bytes bounds it) and a copy of each file into it.
#pragma once

#include <filesystem>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

#include "record/clip.h"
#include "record/recorder.h"
#include "server/jobs/job_queue.h"
#include "server/options.h"
#include "server/store/store.h"

namespace spinfold::server {

class RenderPool;

// A recording's status: the job queue's (server/jobs/job_queue.h).
using RecordingStatus = JobStatus;

// What to record: the window and rate, the format, and the frames (the timeline's copy, the view).
struct RecordingJob {
  std::string session{};  // the session's id (for the file's name)
  std::string client{};   // the address that asked (its quota)
  record::Clip clip{};
  record::Format format = record::Format::webm;
  record::ClipFrames frames{};
};

// A recording's state as the API shows it.
struct RecordingState {
  std::string id;
  RecordingJob job;
  RecordingStatus status = RecordingStatus::queued;
  double progress = 0.0;    // 0…1, never decreasing
  long long frames = 0;     // frames in the file
  std::string reason;       // failed: why
  std::uint64_t bytes = 0;  // the file's size (so far)
};

// The API's view of a recording (GET /api/v1/recordings/{id}).
nlohmann::ordered_json recording_json(const RecordingState& r);

// A finished recording's file as the API serves it.
struct RecordingDownload {
  std::uint64_t bytes = 0;
  std::string content_type;
  std::string file_name;  // for Content-Disposition
  // The bytes from `offset` on (at least one, at most `length`); "" past the end or on a read error.
  std::function<std::string(std::uint64_t offset, std::uint64_t length)> read;
};

class Recordings {
 public:
  // Starts limits.recording_threads threads; files are encoded in a new directory under the system's
  // temporary directory, removed with everything in it by the destructor. `db`: the shared store
  // (rows and files there, every replica answering), or nullptr (this process answers alone).
  Recordings(const Limits& limits, RenderPool& pool, Store* db = nullptr);
  ~Recordings();
  Recordings(const Recordings&) = delete;
  Recordings& operator=(const Recordings&) = delete;

  // Queues a job (checked by the caller: clip_errors, the view, the sizes); returns its id.
  // ApiError 422 over max_recording_frames or max_recording_pixels (naming t_end or width), 429
  // over max_recordings_per_client, max_recordings or max_recording_disk_bytes.
  std::string start(RecordingJob job);
  // This process's job, or ApiError 404 (also for one another replica records).
  RecordingState state(const std::string& id);
  // The API's view: from the store when there is one (any replica's job), else this process's;
  // ApiError 404 (unknown), 503 (the store is away).
  nlohmann::ordered_json describe(const std::string& id);
  // The finished file, or ApiError 404 (unknown), 409 (not done), 503 (the store is away).
  RecordingDownload file(const std::string& id);
  // Cancels a queued or running recording (true), or deletes a finished one and its file (false);
  // ApiError 404 when unknown, 503 when the store is away.
  bool cancel_or_delete(const std::string& id);
  // This process's name in the rows it owns (host, process id and a random part).
  const std::string& instance() const { return instance_; }

 private:
  struct File {
    std::filesystem::path path;  // the file being encoded or kept here ("" once it is the store's)
  };
  using Queue = JobQueue<RecordingState, File>;
  void run(Queue::Entry& entry);
  void heartbeat();  // with a store: touches this process's rows, expires everyone's
  // Writes the job's row (the store's copy of its state); false when it was cancelled or deleted
  // through another replica meanwhile. StoreError when the store is away.
  bool save_row(const RecordingState& state);
  // Copies the finished file into the store, in chunks (StoreError when it cannot).
  void store_file(const std::string& id, const std::filesystem::path& path);
  static std::uint64_t disk_bytes(const Queue::Entries& entries);

  const Limits limits_;
  RenderPool& pool_;
  Store* db_;
  std::string instance_;
  // Where the files are made: created at the first recording (a server that never records leaves
  // no directory behind, even when it is killed), removed with the object.
  std::filesystem::path directory();
  std::once_flag dir_made_;
  std::filesystem::path dir_;
  bool heartbeat_warned_ = false;  // (the heartbeat's own)
  Queue queue_;                    // last: its threads use the members above
};

}  // namespace spinfold::server
