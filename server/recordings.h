// Recordings of a session's time window (POST /api/v1/sessions/{id}/recordings): jobs that replay a
// copy of the session's timeline (the live session is never paused or changed), draw each frame in
// the render pool at background priority (live frames go first) and encode it on a recording thread
// of lower CPU priority, into a file in the server's temporary directory. Each job is queued →
// running → done | failed (with a reason) | cancelled, its progress 0…1 never going back. Limits
// (server::Limits): frames, pixels, jobs per client, jobs kept, disk bytes, age.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "record/clip.h"
#include "record/recorder.h"
#include "server/api.h"

namespace spinfold::server {

class RenderPool;

enum class RecordingStatus { queued, running, done, failed, cancelled };
std::string_view status_name(RecordingStatus status);

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

class Recordings {
 public:
  // Starts limits.recording_threads threads; files go to a new directory under the system's
  // temporary directory, removed with everything in it by the destructor.
  Recordings(const Limits& limits, RenderPool& pool);
  ~Recordings();
  Recordings(const Recordings&) = delete;
  Recordings& operator=(const Recordings&) = delete;

  // Queues a job (checked by the caller: clip_errors, the view, the sizes); returns its id.
  // ApiError 422 over max_recording_frames or max_recording_pixels (naming t_end or width), 429
  // over max_recordings_per_client, max_recordings or max_recording_disk_bytes.
  std::string start(RecordingJob job);
  // The recording's state, or ApiError 404.
  RecordingState state(const std::string& id);
  // The finished file's path, or ApiError 404 (unknown), 409 (not done).
  std::filesystem::path file(const std::string& id);
  // Cancels a queued or running recording (true), or deletes a finished one and its file (false);
  // ApiError 404 when unknown.
  bool cancel_or_delete(const std::string& id);

 private:
  struct Entry;
  void work();
  void run(Entry& entry);
  void prune_locked();
  std::uint64_t disk_bytes_locked() const;

  const Limits limits_;
  RenderPool& pool_;
  std::filesystem::path dir_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::map<std::string, std::shared_ptr<Entry>> entries_;
  std::deque<std::shared_ptr<Entry>> queue_;
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace spinfold::server
