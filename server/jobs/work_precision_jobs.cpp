#include "server/jobs/work_precision_jobs.h"

#include <stdexcept>

#include "codec/provenance.h"
#include "engine/number_text.h"
#include "render/figure_page.h"
#include "server/http/problem.h"
#include "server/sessions/session_id.h"

namespace spinfold::server {

namespace {

namespace wp = work_precision;

// Below the HTTP workers and the render threads, like the recordings: a sweep never slows the live
// view (its timings then measure this thread's share of a core, which a busy server makes noisy).
constexpr int kWorkPrecisionNice = 10;

// "preset NAME", "the scene given", "the scene of a session": never the session's id, which is a
// capability (the plot and the CSV are made to be shared).
std::string describe_source(const WorkPrecisionJob& job) {
  if (job.source == "preset") return "preset " + job.source_name;
  return job.source == "session" ? "the scene of a session" : "the scene given";
}

// The plot as the CLI draws it (cairo, in this process: no temporary files, no program started from
// a server thread), laid out for the UI's side column (about 500 pixels wide, a phone's 370): a
// narrower page, so larger letters, the legend below.
void draw_plot(const WorkPrecisionJob& job, WorkPrecisionResult& result) {
  const wp::PlotLayout layout{.width = 300, .plot_height = 220, .pixels_per_point = 2.0, .key_below = true};
  try {
    const render::FigurePage page =
        wp::plot_page("work-precision: " + describe_source(job),
                      provenance_json(job.scene, "POST /api/v1/work-precision").dump(), result.curves,
                      result.t_end, layout);
    const std::vector<std::uint8_t> svg = render::draw_figure(page, render::FigureFormat::svg);
    const std::vector<std::uint8_t> png = render::raster_figure(page, layout.pixels_per_point);
    result.svg.assign(svg.begin(), svg.end());
    result.png.assign(png.begin(), png.end());
  } catch (const std::invalid_argument& e) {  // nothing to plot
    result.plot_trouble = e.what();
  } catch (const std::exception& e) {
    result.plot_trouble = std::string("the plot was not drawn: ") + e.what();
  }
}

}  // namespace

WorkPrecisionJobs::WorkPrecisionJobs(const Limits& limits)
    : limits_(limits),
      queue_({.threads = 1, .nice = kWorkPrecisionNice, .max_age = limits.work_precision_max_age},
             [this](Queue::Entry& entry) { run(entry); }) {}

std::string WorkPrecisionJobs::start(WorkPrecisionJob job) {
  auto entry = std::make_shared<Queue::Entry>();
  entry->state.id = new_session_id();
  entry->state.job = std::move(job);
  queue_.admit(
      entry, {.per_client_limit = "max_work_precision_jobs_per_client",
              .per_client = limits_.max_work_precision_jobs_per_client,
              .per_client_reason = "this address has a work-precision job queued or running: wait for it "
                                   "to finish or cancel it (DELETE /api/v1/work-precision/{id})",
              .total_limit = "max_work_precision_jobs",
              .total = limits_.max_work_precision_jobs,
              .total_reason = "the server keeps that many work-precision jobs: delete finished ones, or "
                              "wait until they expire (" +
                              std::to_string(limits_.work_precision_max_age.count()) + " s after finishing)",
              .retry_after = "5"});
  queue_.enqueue(entry);
  return entry->state.id;
}

WorkPrecisionState WorkPrecisionJobs::state(const std::string& id) {
  std::optional<WorkPrecisionState> s = queue_.find(id);
  if (!s)
    throw bad(404, "Unknown work-precision job", "id", id,
              "no work-precision job with this id (finished jobs are dropped after " +
                  std::to_string(limits_.work_precision_max_age.count()) + " s)");
  return std::move(*s);
}

std::shared_ptr<const WorkPrecisionResult> WorkPrecisionJobs::result(const std::string& id) {
  const WorkPrecisionState s = state(id);
  if (s.status != JobStatus::done)
    throw bad(409, "Not ready", "status", std::string(job_status_name(s.status)),
              s.status == JobStatus::failed ? "the job failed: " + s.reason
                                            : "the result is there once the status is done");
  return s.result;
}

bool WorkPrecisionJobs::cancel_or_delete(const std::string& id) {
  // Cancelled now: a queued job never starts, a running one stops before its next run.
  const Queue::Removed removed = queue_.cancel_or_delete(id);
  if (removed == Queue::Removed::unknown)
    throw bad(404, "Unknown work-precision job", "id", id,
              "no work-precision job with this id (it may have expired)");
  return removed == Queue::Removed::cancelled;
}

void WorkPrecisionJobs::run(Queue::Entry& entry) {
  const WorkPrecisionJob& job = entry.state.job;  // not changed while running
  auto result = std::make_shared<WorkPrecisionResult>();
  JobStatus status = JobStatus::done;
  std::string reason;
  try {
    // A chaotic scene is measured over its predictable horizon (or, past it, recommends nothing).
    const wp::Horizon horizon = wp::choose_horizon(
        job.scene, job.t_end_given ? std::optional(job.t_end) : std::nullopt, job.target_error,
        static_cast<std::uint64_t>(limits_.work_precision_steps_per_run));
    const double t_end = std::min(horizon.t_end, job.t_end);
    result->t_end = t_end;
    result->horizon_note = horizon.note;
    // Beyond a chaotic horizon nothing is measured (every error would be the chaos's).
    const wp::Reference reference =
        horizon.beyond ? wp::Reference{"none", "not computed: T lies beyond the predictable horizon", {}}
                       : wp::make_reference(job.scene, t_end);
    result->reference_kind = reference.kind;
    result->reference_description = reference.description;
    queue_.locked([&](auto&) { entry.state.reference_ready = true; });
    wp::SweepOptions options;
    options.t_end = t_end;
    options.integrators = job.integrators;
    options.max_seconds_per_run = limits_.work_precision_seconds_per_run;
    options.max_attempts_per_run = static_cast<std::uint64_t>(limits_.work_precision_steps_per_run);
    options.proceed = [&](std::size_t done, std::size_t methods) {
      queue_.locked([&](auto&) {
        entry.state.methods_done = done;
        entry.state.methods = methods;
      });
      return queue_.progress(entry, static_cast<double>(done), static_cast<double>(methods));
    };
    if (!entry.cancel && !horizon.beyond) result->curves = wp::sweep(job.scene, reference, options);
    if (!entry.cancel) {
      result->recommendation =
          wp::recommendation(result->curves, job.target_error, horizon, wp::auto_picks(job.scene));
      result->recommended = wp::recommended_setting(result->curves, job.target_error);
      result->skipped = wp::skipped_integrators(job.scene, options);
      result->csv =
          wp::csv("# spinfold work-precision " + version_line() +
                      "\n# command: POST /api/v1/work-precision\n# provenance: " +
                      provenance_json(job.scene, "POST /api/v1/work-precision").dump() +
                      "\n# scene: " + describe_source(job) + "; T = " + shortest(t_end) + "; target error " +
                      shortest(job.target_error) + "\n# reference: " + reference.kind + ": " +
                      reference.description + "\n# " + wp::kErrorMeaning + "\n# " + wp::kErrorParts + "\n",
                  result->curves);
      draw_plot(job, *result);
    }
  } catch (const std::exception& e) {  // out of memory, or the engine refusing the scene
    status = JobStatus::failed;
    reason = e.what();
  }
  if (entry.cancel) return;  // cancel_or_delete set the status and the time; a cancel is final
  queue_.finish(entry, status, [&](WorkPrecisionState& state, std::monostate&) {
    state.reason = reason;
    if (status == JobStatus::done) state.result = std::move(result);
  });
}

}  // namespace spinfold::server
