// Work-precision jobs (POST /api/v1/work-precision): which integrator for a scene, measured by the
// library the CLI uses (workprecision/work_precision.h) on one background thread of low CPU
// priority, never on an HTTP worker (a JobQueue: server/jobs/job_queue.h). Each job is queued → running →
// done | failed (with a reason) | cancelled; progress is the methods swept / the methods to sweep, never
// going back. A cancel takes effect before the job's next run. Results (the curves, the recommendation, the
// CSV, the SVG and PNG plots) are kept in memory only, and dropped `work_precision_max_age` after finishing.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene.h"
#include "server/jobs/job_queue.h"
#include "server/options.h"
#include "workprecision/work_precision.h"

namespace spinfold::server {

// What to measure (checked by the caller: the scene valid, the integrators known, T and the target
// error within Limits).
struct WorkPrecisionJob {
  std::string client{};                    // the address that asked (its quota)
  Scene scene{};                           // the main body is measured; companions are separate runs
  std::string source{};                    // "scene", "preset" or "session"
  std::string source_name{};               // the preset's name ("" otherwise: a session's id is never shown)
  std::vector<std::string> integrators{};  // catalog names and/or auto; empty: all and auto
  double t_end = 1.0;
  bool t_end_given = false;  // the request named t_end (else the default, which a chaotic scene shortens)
  double target_error = 1e-10;
};

struct WorkPrecisionResult {
  double t_end = 0.0;        // the horizon measured (work_precision::choose_horizon) [time]
  std::string horizon_note;  // why it differs from the job's, or that T is beyond a chaotic horizon
  work_precision::Curves curves;
  std::string reference_kind, reference_description;
  std::string recommendation;                        // work_precision::recommendation's line
  std::optional<work_precision::Point> recommended;  // its first setting, to use as the integrator
  std::map<std::string, std::string> skipped;        // integrators not run, and why
  std::string csv;                                   // the curves with provenance comments
  std::string svg, png;                              // the plot; empty when it could not be drawn
  std::string plot_trouble;                          // why not ("" when drawn)
};

// A job's state as the API shows it.
struct WorkPrecisionState {
  std::string id;
  WorkPrecisionJob job;
  JobStatus status = JobStatus::queued;
  double progress = 0.0;  // methods done / methods, 0…1
  std::size_t methods_done = 0, methods = 0;
  bool reference_ready = false;  // the reference at T is computed (the sweep runs after it)
  std::string reason;            // failed: why
  std::shared_ptr<const WorkPrecisionResult> result;  // done: the result
};

class WorkPrecisionJobs {
 public:
  explicit WorkPrecisionJobs(const Limits& limits);
  ~WorkPrecisionJobs() = default;  // cancels every job, and waits for the one running to reach its next run
  WorkPrecisionJobs(const WorkPrecisionJobs&) = delete;
  WorkPrecisionJobs& operator=(const WorkPrecisionJobs&) = delete;

  // Queues a job; returns its id. ApiError 429 (Retry-After) over max_work_precision_jobs_per_client
  // (queued or running jobs of the client) or max_work_precision_jobs (jobs kept).
  std::string start(WorkPrecisionJob job);
  // The job's state, or ApiError 404.
  WorkPrecisionState state(const std::string& id);
  // The result of a done job: ApiError 404 (unknown), 409 (not done).
  std::shared_ptr<const WorkPrecisionResult> result(const std::string& id);
  // Cancels a queued or running job (true), or deletes a finished one (false); ApiError 404 if unknown.
  bool cancel_or_delete(const std::string& id);

 private:
  using Queue = JobQueue<WorkPrecisionState>;
  void run(Queue::Entry& entry);

  const Limits limits_;
  Queue queue_;  // one thread: the timings are wall-clock times, so jobs never run side by side
};

}  // namespace spinfold::server
