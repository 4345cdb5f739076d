// The one background-job queue (server/jobs/job_queue.h) on a job kind of its own: admission,
// FIFO order, progress, cancel, expiry and the sync thread. Recordings and work-precision jobs are
// tested through HTTP (tests/server/jobs/recordings_test.cpp, tests/server/work_precision_test.cpp).
#include "server/jobs/job_queue.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

namespace {

using spinfold::server::ApiError;
using spinfold::server::job_status_name;
using spinfold::server::JobQueue;
using spinfold::server::JobQuota;
using spinfold::server::JobStatus;
using namespace std::chrono_literals;

struct TestJob {
  std::string client;
  int polls = 0;  // how many times the job polls its cancel flag (1 ms apart)
};

struct TestState {
  std::string id;
  TestJob job;
  JobStatus status = JobStatus::queued;
  double progress = 0.0;
  std::vector<double> seen;  // the progress after each poll
};

using Queue = JobQueue<TestState>;

JobQuota quota(int per_client, int total) {
  return {.per_client_limit = "max_tests_per_client",
          .per_client = per_client,
          .per_client_reason = "one each",
          .total_limit = "max_tests",
          .total = total,
          .total_reason = "that many",
          .retry_after = "7"};
}

// Runs a job: `polls` steps of 1 ms, each raising the progress; done unless cancelled.
struct Harness {
  std::atomic<int> started{0};
  std::vector<std::string> order;  // ids in the order they started (one worker)
  std::mutex mutex;
  Queue queue;
  explicit Harness(std::chrono::seconds max_age = 3600s, int threads = 1)
      : queue({.threads = threads, .nice = 0, .max_age = max_age}, [this](Queue::Entry& e) { run(e); }) {}
  void run(Queue::Entry& e) {
    {
      const std::lock_guard lock(mutex);
      order.push_back(e.state.id);
    }
    ++started;
    for (int i = 1; i <= e.state.job.polls; ++i) {
      std::this_thread::sleep_for(1ms);
      if (!queue.progress(e, i, e.state.job.polls)) return;  // cancelled: the queue set the status
      queue.locked([&](auto&) { e.state.seen.push_back(e.state.progress); });
    }
    queue.finish(e, JobStatus::done);
  }
  std::string add(const std::string& id, const std::string& client, int polls, JobQuota q = quota(10, 10)) {
    auto entry = std::make_shared<Queue::Entry>();
    entry->state.id = id;
    entry->state.job = {client, polls};
    queue.admit(entry, q);
    queue.enqueue(entry);
    return id;
  }
  TestState wait_finished(const std::string& id) {
    for (int i = 0; i < 5000; ++i) {
      const auto s = queue.find(id);
      if (s && !spinfold::server::job_active(s->status)) return *s;
      std::this_thread::sleep_for(1ms);
    }
    ADD_FAILURE() << id << " did not finish";
    return *queue.find(id);
  }
};

TEST(JobQueue, StatusNamesAreTheApis) {
  EXPECT_EQ(job_status_name(JobStatus::queued), "queued");
  EXPECT_EQ(job_status_name(JobStatus::running), "running");
  EXPECT_EQ(job_status_name(JobStatus::done), "done");
  EXPECT_EQ(job_status_name(JobStatus::failed), "failed");
  EXPECT_EQ(job_status_name(JobStatus::cancelled), "cancelled");
}

TEST(JobQueue, JobsRunInOrderAndFinishDoneWithProgressNeverGoingBack) {
  Harness h;
  h.add("a", "x", 20);
  h.add("b", "y", 5);
  h.add("c", "z", 5);
  for (const char* id : {"a", "b", "c"}) {
    const TestState s = h.wait_finished(id);
    EXPECT_EQ(s.status, JobStatus::done);
    EXPECT_EQ(s.progress, 1.0);
    for (std::size_t i = 1; i < s.seen.size(); ++i) EXPECT_GE(s.seen[i], s.seen[i - 1]);
  }
  EXPECT_EQ(h.order, (std::vector<std::string>{"a", "b", "c"}));
}

TEST(JobQueue, AdmissionCountsActiveJobsPerClientAndAllJobsKept) {
  Harness h;
  h.add("a", "x", 200, quota(1, 2));
  try {
    h.add("b", "x", 1, quota(1, 2));
    FAIL() << "a second active job of one client was admitted";
  } catch (const ApiError& e) {
    EXPECT_EQ(e.status, 429);
    EXPECT_EQ(e.retry_after, "7");
    ASSERT_EQ(e.errors.size(), 1u);
    EXPECT_EQ(e.errors[0].field, "limits.max_tests_per_client");
  }
  h.add("c", "y", 1, quota(1, 2));
  try {
    h.add("d", "z", 1, quota(1, 2));
    FAIL() << "a job over the total was admitted";
  } catch (const ApiError& e) {
    EXPECT_EQ(e.errors[0].field, "limits.max_tests");
  }
  EXPECT_FALSE(h.queue.find("b"));
  EXPECT_FALSE(h.queue.find("d"));
}

TEST(JobQueue, ACancelIsFinalAndAQueuedJobNeverStarts) {
  Harness h;
  h.add("long", "x", 5000);
  h.add("queued", "y", 1);
  while (h.started == 0) std::this_thread::sleep_for(1ms);
  EXPECT_TRUE(h.queue.cancel("queued"));
  EXPECT_EQ(h.queue.cancel_or_delete("long"), Queue::Removed::cancelled);
  EXPECT_EQ(h.wait_finished("long").status, JobStatus::cancelled);
  EXPECT_EQ(h.queue.find("queued")->status, JobStatus::cancelled);
  std::this_thread::sleep_for(20ms);
  EXPECT_EQ(h.started, 1) << "a cancelled queued job started";
  // A finished job is deleted, then unknown.
  EXPECT_EQ(h.queue.cancel_or_delete("long"), Queue::Removed::deleted);
  EXPECT_EQ(h.queue.cancel_or_delete("long"), Queue::Removed::unknown);
  EXPECT_FALSE(h.queue.cancel("queued")) << "a finished job is not cancelled again";
}

TEST(JobQueue, FinishedJobsExpireAfterTheirAge) {
  Harness h(0s);
  h.add("a", "x", 1);
  for (int i = 0; i < 5000 && h.queue.find("a"); ++i) std::this_thread::sleep_for(1ms);
  EXPECT_FALSE(h.queue.find("a")) << "a finished job outlived its age";
}

TEST(JobQueue, TheSyncThreadRunsUntilStop) {
  std::atomic<int> syncs{0};
  Queue queue({.threads = 1, .nice = 0, .max_age = 60s, .sync_every = 2ms, .sync = [&] { ++syncs; }},
              [](Queue::Entry&) {});
  for (int i = 0; i < 5000 && syncs < 3; ++i) std::this_thread::sleep_for(1ms);
  EXPECT_GE(syncs, 3);
  queue.stop();
  const int after = syncs;
  std::this_thread::sleep_for(10ms);
  EXPECT_EQ(syncs, after);
}

}  // namespace
