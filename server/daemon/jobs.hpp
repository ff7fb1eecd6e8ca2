// Jobs for long work (POST /v1/jobs): a render, a thumbnail batch or a benchmark that may take
// longer than a synchronous request's deadline. The client gets 202 and the job's address at once,
// polls its status (progress, ETA), fetches the result, or cancels it.
//
// One runner thread takes jobs in arrival order and submits their renders to the render queue one
// at a time, so that synchronous requests take their turns between a job's renders. Each render
// gets --job-deadline-seconds. The store is bounded: at most --max-jobs jobs (queued, running, or
// finished and not yet expired), and results within --jobs-memory-mb (a job reserves an upper
// bound of its result when it is submitted). Finished jobs are kept for --job-ttl-seconds.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "clock.hpp"
#include "config.hpp"
#include "job_work.hpp"
#include "metrics.hpp"
#include "render_queue.hpp"

namespace lghd {

enum class JobStatus { Queued, Running, Succeeded, Failed, Cancelled };
const char* jobStatusName(JobStatus status);

class JobStore {
 public:
  JobStore(JobLimits limits, RenderQueue& queue);
  ~JobStore();
  JobStore(const JobStore&) = delete;
  JobStore& operator=(const JobStore&) = delete;

  void start();
  // Ends the runner: queued jobs fail with 503, a running one ends after its current render.
  void stop();

  // Queues the work; returns the job's status (proto/job-status.schema.json). Throws ApiError 503
  // when the daemon is not ready, 429 (with Retry-After) when the store holds --max-jobs jobs or
  // the memory budget is taken, 413 when the job's result could not fit the budget at all.
  nlohmann::json submit(std::unique_ptr<JobWork> work, const std::string& requestId);
  // The job's status; nullopt for an unknown or expired id.
  std::optional<nlohmann::json> status(const std::string& id);
  // A succeeded job's result. Throws ApiError: 404 unknown id, 409 (with Retry-After) while it is
  // queued or running, 409 when it was cancelled, and the job's own error when it failed.
  std::shared_ptr<const JobResult> result(const std::string& id);
  // DELETE: cancels a queued or running job (kept, as cancelled, for the TTL); forgets a finished
  // one and frees its result. Returns the status it had afterwards; nullopt for an unknown id.
  std::optional<nlohmann::json> remove(const std::string& id);

  // lghd_jobs{status}, lghd_jobs_capacity, lghd_jobs_pending_renders, lghd_jobs_memory_bytes,
  // lghd_jobs_memory_budget_bytes, lghd_jobs_total{kind,outcome}.
  std::string exposition();

 private:
  struct Job {
    std::string id;
    std::string requestId;
    std::string kind;
    std::unique_ptr<JobWork> work;  // released when the job ends
    JobStatus status = JobStatus::Queued;
    std::chrono::system_clock::time_point created;
    std::optional<std::chrono::system_clock::time_point> started;
    std::optional<std::chrono::system_clock::time_point> finished;
    Clock::time_point runStart;
    std::optional<Clock::time_point> expires;  // finished jobs: when they are dropped
    std::size_t total = 0;
    std::size_t done = 0;
    std::size_t failed = 0;
    std::size_t reservedBytes = 0;  // against the memory budget until the job ends
    std::size_t resultBytes = 0;    // held until the job expires or is deleted
    std::shared_ptr<const JobResult> result;
    std::optional<ApiError> error;
    std::atomic<bool> cancelled{false};
    std::shared_ptr<RenderJob> inFlight;  // the render queue's job of the current render
  };
  using JobPtr = std::shared_ptr<Job>;

  void run();
  JobPtr nextJob();
  void runJob(Job& job);
  RenderOutcome renderOne(Job& job, const lgh::RenderRequest& request);
  void finishJob(Job& job);
  void endJob(Job& job, JobStatus status, const char* outcome);  // under mutex_
  bool stopping() const;
  void expireFinished();                                   // under mutex_
  nlohmann::json statusJson(const Job& job) const;         // under mutex_
  std::optional<double> etaSeconds(const Job& job) const;  // under mutex_
  std::size_t memoryInUse() const;                         // under mutex_
  int retryAfterSeconds() const;                           // under mutex_

  JobLimits limits_;
  RenderQueue& queue_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::map<std::string, JobPtr> jobs_;
  std::deque<JobPtr> pending_;
  bool stopping_ = false;
  double secondsPerRender_ = 0.0;  // moving average over job renders; 0 until the first
  std::map<std::string, std::uint64_t> finishedTotals_;  // "kind,outcome" labels
  std::thread runner_;
};

}  // namespace lghd
