// The one background-job queue of the server: recordings (recordings.h) and work-precision studies
// (work_precision_jobs.h) are each a JobQueue of their own state. The queue owns what every kind
// of job shares: the jobs kept by id, the FIFO of queued ones, worker threads of low CPU priority,
// the status (queued → running → done | failed | cancelled), progress that never goes back, the
// cancel flag a running job polls, admission against a per-client and a total count (429 naming
// the limit), expiry of finished jobs after an age, and, with a store, a thread of its own that
// keeps the store in step (the recordings' heartbeat). What a job does, what its state holds
// besides, and how it answers the API are the kind's.
#pragma once

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <variant>
#include <vector>

#include "server/http/problem.h"

namespace spinfold::server {

enum class JobStatus { queued, running, done, failed, cancelled };
// "queued", "running", "done", "failed", "cancelled" (the API's names).
std::string_view job_status_name(JobStatus status);
inline bool job_active(JobStatus status) {
  return status == JobStatus::queued || status == JobStatus::running;
}

struct JobQueueOptions {
  int threads = 1;  // jobs run at once (the rest wait, queued)
  int nice = 10;    // the workers' CPU priority: below the HTTP workers and the render threads
  std::chrono::seconds max_age{3600};  // a finished job is dropped this long after finishing
  // With a store: `sync` runs every `sync_every` on a thread of its own until the queue stops.
  std::chrono::milliseconds sync_every{0};
  std::function<void()> sync{};
};

// The counts a new job is admitted against (a refusal: 429 naming the limit, with Retry-After).
struct JobQuota {
  std::string per_client_limit;  // "max_recordings_per_client": queued or running jobs of one client
  int per_client = 1;
  std::string per_client_reason;
  std::string total_limit;  // "max_recordings": jobs kept, any status
  int total = 1;
  std::string total_reason;
  std::string retry_after = "5";
};

// 429 naming a limit of Limits ("limits.<name>") and its value.
inline ApiError job_over_limit(const std::string& limit, long long value, const std::string& reason,
                               const std::string& retry_after) {
  return {429, "Too many requests", {{"limits." + limit, std::to_string(value), reason}}, retry_after};
}

// State: the kind's state as the API shows it, with at least `id`, `status`, `progress` (0…1) and
// `job.client`. Extra: what the queue keeps beside it, not shown (a recording's file).
template <class State, class Extra = std::monostate>
class JobQueue {
 public:
  struct Entry {
    State state;                                     // guarded by the queue's lock (locked())
    Extra extra;                                     // guarded too
    std::atomic<bool> cancel{false};                 // set by a cancel and at stop: polled by the job
    std::chrono::steady_clock::time_point finished;  // done, failed or cancelled at (guarded)
    bool active() const { return job_active(state.status); }
  };
  using Ptr = std::shared_ptr<Entry>;
  using Entries = std::map<std::string, Ptr>;
  using Run = std::function<void(Entry&)>;   // runs a job on a worker (status running; not locked)
  using Drop = std::function<void(Entry&)>;  // a finished job expired (locked): remove its files

  // Starts the workers and, with options.sync, the sync thread. Declare the queue after whatever
  // `run` and `sync` use, and stop() it first in the owner's destructor.
  JobQueue(JobQueueOptions options, Run run, Drop drop = {})
      : options_(std::move(options)), run_(std::move(run)), drop_(std::move(drop)) {
    for (int i = 0; i < std::max(1, options_.threads); ++i) threads_.emplace_back([this] { work(); });
    if (options_.sync) sync_thread_ = std::thread([this] { sync(); });
  }
  ~JobQueue() { stop(); }
  JobQueue(const JobQueue&) = delete;
  JobQueue& operator=(const JobQueue&) = delete;

  // Cancels every job and waits for the running ones to reach their next poll of `cancel`.
  void stop() {
    {
      const std::lock_guard lock(mutex_);
      if (stopping_ && threads_.empty()) return;
      stopping_ = true;
      for (auto& [id, entry] : entries_) entry->cancel = true;
    }
    wake_.notify_all();
    sync_wake_.notify_all();
    for (auto& thread : threads_) thread.join();
    threads_.clear();
    if (sync_thread_.joinable()) sync_thread_.join();
  }
  bool stopping() {
    const std::lock_guard lock(mutex_);
    return stopping_;
  }

  // Keeps a new job (not yet queued: enqueue() it, or forget() it) after expiring old ones and
  // checking the quota, then `check` (more refusals, the lock held; it may read entries).
  void admit(const Ptr& entry, const JobQuota& quota, const std::function<void(const Entries&)>& check = {}) {
    const std::lock_guard lock(mutex_);
    prune_locked();
    int of_client = 0;
    for (const auto& [id, e] : entries_)
      of_client += e->active() && e->state.job.client == entry->state.job.client;
    if (of_client >= quota.per_client)
      throw job_over_limit(quota.per_client_limit, quota.per_client, quota.per_client_reason,
                           quota.retry_after);
    if (static_cast<int>(entries_.size()) >= quota.total)
      throw job_over_limit(quota.total_limit, quota.total, quota.total_reason, quota.retry_after);
    if (check) check(entries_);
    entries_[entry->state.id] = entry;
  }
  void enqueue(const Ptr& entry) {
    {
      const std::lock_guard lock(mutex_);
      queue_.push_back(entry);
    }
    wake_.notify_one();
  }
  void forget(const std::string& id) {
    const std::lock_guard lock(mutex_);
    entries_.erase(id);
  }

  // A copy of the job's state (finished jobs past their age dropped first), or nullopt.
  std::optional<State> find(const std::string& id) {
    const std::lock_guard lock(mutex_);
    prune_locked();
    const auto it = entries_.find(id);
    if (it == entries_.end()) return std::nullopt;
    return it->second->state;
  }

  // Cancels a queued or running job: a queued one never starts, a running one stops at its next
  // poll. False when unknown or finished.
  bool cancel(const std::string& id) {
    const std::lock_guard lock(mutex_);
    const auto it = entries_.find(id);
    if (it == entries_.end() || !it->second->active()) return false;
    cancel_locked(it->second);
    return true;
  }
  // Drops a finished job; returns it (null when unknown or still active).
  Ptr erase_finished(const std::string& id) {
    const std::lock_guard lock(mutex_);
    const auto it = entries_.find(id);
    if (it == entries_.end() || it->second->active()) return nullptr;
    Ptr entry = it->second;
    entries_.erase(it);
    return entry;
  }
  enum class Removed { unknown, cancelled, deleted };
  // Cancels an active job, or drops a finished one (`deleted` gets it).
  Removed cancel_or_delete(const std::string& id, Ptr* deleted = nullptr) {
    const std::lock_guard lock(mutex_);
    const auto it = entries_.find(id);
    if (it == entries_.end()) return Removed::unknown;
    if (it->second->active()) {
      cancel_locked(it->second);
      return Removed::cancelled;
    }
    if (deleted) *deleted = it->second;
    entries_.erase(it);
    return Removed::deleted;
  }

  // Raises the job's progress to done / total (never lowers it); false once the job is cancelled.
  bool progress(Entry& entry, double done, double total) {
    const std::lock_guard lock(mutex_);
    if (total > 0) entry.state.progress = std::max(entry.state.progress, done / total);
    return !entry.cancel.load();
  }
  // Ends a running job with `status` (a cancel is final: the status and time it set stay); done
  // sets progress to 1. `also` changes more of the state, the lock held.
  void finish(Entry& entry, JobStatus status, const std::function<void(State&, Extra&)>& also = {}) {
    const std::lock_guard lock(mutex_);
    if (entry.state.status == JobStatus::cancelled) return;
    entry.state.status = status;
    if (status == JobStatus::done) entry.state.progress = 1.0;
    if (also) also(entry.state, entry.extra);
    entry.finished = std::chrono::steady_clock::now();
  }

  // Runs f(entries) with the lock held: reading or changing states beside the queue's own calls.
  template <class F>
  decltype(auto) locked(F&& f) {
    const std::lock_guard lock(mutex_);
    return f(entries_);
  }

 private:
  void cancel_locked(const Ptr& entry) {
    entry->cancel = true;
    std::erase(queue_, entry);
    entry->state.status = JobStatus::cancelled;
    entry->finished = std::chrono::steady_clock::now();
  }
  void prune_locked() {
    const auto now = std::chrono::steady_clock::now();
    for (auto it = entries_.begin(); it != entries_.end();) {
      Entry& e = *it->second;
      if (!e.active() && now - e.finished >= options_.max_age) {
        if (drop_) drop_(e);
        it = entries_.erase(it);
      } else {
        ++it;
      }
    }
  }
  void work() {
    // Linux: nice applies to this thread only (its own task id).
    setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), options_.nice);
    for (;;) {
      Ptr entry;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
        if (stopping_) return;
        entry = queue_.front();
        queue_.pop_front();
        entry->state.status = JobStatus::running;
      }
      run_(*entry);
    }
  }
  void sync() {
    std::unique_lock lock(mutex_);
    while (!sync_wake_.wait_for(lock, options_.sync_every, [this] { return stopping_; })) {
      lock.unlock();
      options_.sync();
      lock.lock();
    }
  }

  const JobQueueOptions options_;
  const Run run_;
  const Drop drop_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable sync_wake_;  // its own: a notify_one for a job must reach a worker
  Entries entries_;
  std::deque<Ptr> queue_;
  bool stopping_ = false;
  std::vector<std::thread> threads_;
  std::thread sync_thread_;
};

}  // namespace spinfold::server
