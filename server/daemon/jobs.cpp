#include "jobs.hpp"

#include <cmath>
#include <ctime>
#include <random>

#include <fmt/format.h>

#include "lgh/thread_name.hpp"
#include "logging.hpp"

namespace lghd {
namespace {

using json = nlohmann::json;
using SystemClock = std::chrono::system_clock;

// How often a job whose render found the render queue full tries again.
constexpr auto kQueueFullRetry = std::chrono::milliseconds(50);

// 128 random bits: a job id is its capability to read the result (with no --auth-token).
std::string newJobId() {
  static std::mutex mutex;
  static std::mt19937_64 generator{std::random_device{}()};
  std::lock_guard lock(mutex);
  return fmt::format("{:016x}{:016x}", generator(), generator());
}

std::string rfc3339(SystemClock::time_point time) {
  const std::time_t seconds = SystemClock::to_time_t(time);
  const auto milliseconds =
      std::chrono::duration_cast<std::chrono::milliseconds>(time.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}.{:03}Z", utc.tm_year + 1900,
                     utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec,
                     milliseconds);
}

json timeOrNull(const std::optional<SystemClock::time_point>& time) {
  return time ? json(rfc3339(*time)) : json();
}

bool ended(JobStatus status) {
  return status == JobStatus::Succeeded || status == JobStatus::Failed ||
         status == JobStatus::Cancelled;
}

std::size_t mebibytes(std::size_t bytes) { return (bytes + (1U << 20) - 1) >> 20; }

ApiError conflict(std::string message) {
  return ApiError(409, "conflict", std::move(message), "id");
}

ApiError unknownJob(const std::string& id) {
  return ApiError(
      404, "not_found",
      fmt::format("no job {} (unknown, deleted, or expired after its time to live)", id), "id");
}

}  // namespace

const char* jobStatusName(JobStatus status) {
  switch (status) {
    case JobStatus::Queued:
      return "queued";
    case JobStatus::Running:
      return "running";
    case JobStatus::Succeeded:
      return "succeeded";
    case JobStatus::Failed:
      return "failed";
    case JobStatus::Cancelled:
      return "cancelled";
  }
  return "failed";
}

JobStore::JobStore(JobLimits limits, RenderQueue& queue) : limits_(limits), queue_(queue) {}

JobStore::~JobStore() {
  try {
    stop();
  } catch (const std::exception& error) {  // a destructor must not throw: say so and go on
    logging::event(spdlog::level::err, "job_store_stop_failed", {{"error", error.what()}});
  }
}

void JobStore::start() {
  runner_ = std::thread([this] { run(); });
}

void JobStore::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    for (const JobPtr& job : pending_) {
      job->error = unavailable("the daemon shut down before the job started");
      endJob(*job, JobStatus::Failed, "failed");
    }
    pending_.clear();
    // A render in progress is not waited for: a hung driver must not hold up the exit.
    const ApiError stopped = unavailable("the daemon shut down before the job finished");
    for (const auto& [id, job] : jobs_) {
      if (!job->inFlight) continue;
      job->inFlight->cancelled = true;
      for (const auto& ticket : job->inFlight->tickets) ticket->fail(stopped);
    }
  }
  changed_.notify_all();
  if (runner_.joinable()) runner_.join();
}

bool JobStore::stopping() const {
  std::lock_guard lock(mutex_);
  return stopping_;
}

// --- HTTP threads -------------------------------------------------------------------------------

json JobStore::submit(std::unique_ptr<JobWork> work, const std::string& requestId) {
  if (const std::string reason = queue_.notReadyReason(); !reason.empty()) {
    throw unavailable(reason).withRetryAfter(1);
  }
  const std::size_t bound = work->resultBytesBound();
  if (bound > limits_.memoryBytes) {
    throw ApiError(413, "too_large",
                   fmt::format("the job's result may take up to {} MiB, over this server's job "
                               "memory of {} MiB",
                               mebibytes(bound), mebibytes(limits_.memoryBytes)),
                   "/request");
  }
  auto job = std::make_shared<Job>();
  job->id = newJobId();
  job->requestId = requestId;
  job->kind = work->kind();
  job->total = work->size();
  job->reservedBytes = bound;
  job->created = SystemClock::now();
  job->work = std::move(work);
  json status;
  {
    std::lock_guard lock(mutex_);
    if (stopping_) throw unavailable("the daemon is shutting down");
    expireFinished();
    if (jobs_.size() >= static_cast<std::size_t>(limits_.maxJobs)) {
      throw queueFull(fmt::format("this server holds {} jobs, its limit: fetch the results of "
                                  "finished jobs and DELETE them, or retry later",
                                  jobs_.size()),
                      retryAfterSeconds());
    }
    if (memoryInUse() + bound > limits_.memoryBytes) {
      throw queueFull(fmt::format("the job memory ({} MiB) is taken by other jobs' results: fetch "
                                  "and DELETE finished jobs, or retry later",
                                  mebibytes(limits_.memoryBytes)),
                      retryAfterSeconds());
    }
    jobs_.emplace(job->id, job);
    pending_.push_back(job);
    status = statusJson(*job);
  }
  changed_.notify_all();
  logging::event(
      spdlog::level::info, "job_queued",
      {{"request_id", requestId}, {"job", job->id}, {"kind", job->kind}, {"renders", job->total}});
  return status;
}

std::optional<json> JobStore::status(const std::string& id) {
  std::lock_guard lock(mutex_);
  expireFinished();
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) return std::nullopt;
  return statusJson(*it->second);
}

std::shared_ptr<const JobResult> JobStore::result(const std::string& id) {
  std::lock_guard lock(mutex_);
  expireFinished();
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) throw unknownJob(id);
  const Job& job = *it->second;
  switch (job.status) {
    case JobStatus::Queued:
    case JobStatus::Running: {
      const int eta = static_cast<int>(std::ceil(etaSeconds(job).value_or(1.0)));
      throw conflict(
          fmt::format("the job is {}: its result is not ready", jobStatusName(job.status)))
          .withRetryAfter(std::max(1, eta));
    }
    case JobStatus::Cancelled:
      throw conflict("the job was cancelled: it has no result");
    case JobStatus::Failed:
      throw *job.error;
    case JobStatus::Succeeded:
      break;
  }
  return job.result;
}

std::optional<json> JobStore::remove(const std::string& id) {
  std::lock_guard lock(mutex_);
  expireFinished();
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) return std::nullopt;
  const JobPtr job = it->second;
  switch (job->status) {
    case JobStatus::Queued:
      std::erase(pending_, job);
      job->cancelled = true;
      endJob(*job, JobStatus::Cancelled, "cancelled");
      break;
    case JobStatus::Running:
      // The runner ends it after the render in progress (or skips that render if it has not
      // started); until then its reserved memory stays taken.
      job->cancelled = true;
      job->status = JobStatus::Cancelled;
      job->finished = SystemClock::now();
      job->expires = Clock::now() + limits_.ttl;
      if (job->inFlight) job->inFlight->cancelled = true;
      break;
    default: {
      json last = statusJson(*job);
      jobs_.erase(it);
      return last;
    }
  }
  changed_.notify_all();
  logging::event(spdlog::level::info, "job_cancelled",
                 {{"request_id", job->requestId}, {"job", job->id}});
  return statusJson(*job);
}

// --- The runner ---------------------------------------------------------------------------------

void JobStore::run() {
  lgh::nameThisThread("lgh-jobs");
  while (const JobPtr job = nextJob()) runJob(*job);
}

JobStore::JobPtr JobStore::nextJob() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return stopping_ || !pending_.empty(); });
  if (stopping_) return nullptr;
  JobPtr job = std::move(pending_.front());
  pending_.pop_front();
  job->status = JobStatus::Running;
  job->started = SystemClock::now();
  job->runStart = Clock::now();
  return job;
}

void JobStore::runJob(Job& job) {
  JobWork& work = *job.work;  // only this thread resets it while the job runs
  for (std::size_t i = 0; i < job.total; ++i) {
    if (job.cancelled || stopping()) break;
    auto [request, itemError] = work.item(i);
    RenderOutcome outcome;
    if (itemError) {
      outcome.error = std::move(itemError);
    } else {
      outcome = renderOne(job, *request);
    }
    if (job.cancelled) break;
    const bool goOn = work.record(i, std::move(outcome));
    {
      std::lock_guard lock(mutex_);
      job.done = i + 1;
      job.failed = work.failedItems();
    }
    if (!goOn) break;
  }
  finishJob(job);
}

RenderOutcome JobStore::renderOne(Job& job, const lgh::RenderRequest& request) {
  const Clock::time_point deadline = Clock::now() + limits_.renderDeadline;
  std::shared_ptr<RenderJob> renderJob;
  // A full render queue (429), or a context being replaced (503 with Retry-After), is a reason
  // to wait, not to fail: synchronous clients get their turn first.
  while (!renderJob) {
    try {
      renderJob = queue_.submit({request}, job.requestId, deadline);
    } catch (const ApiError& error) {
      const bool transient = error.status() == 429 || error.retryAfterSeconds() > 0;
      if (!transient) return {std::nullopt, error, 0.0};
      std::unique_lock lock(mutex_);
      changed_.wait_for(lock, kQueueFullRetry, [&] { return stopping_ || job.cancelled.load(); });
      if (stopping_ || job.cancelled) return {std::nullopt, error, 0.0};
      if (Clock::now() > deadline) {
        return {std::nullopt,
                timedOut("the render could not enter the render queue before its deadline"), 0.0};
      }
    }
  }
  {
    std::lock_guard lock(mutex_);
    job.inFlight = renderJob;
    if (job.cancelled) renderJob->cancelled = true;
  }
  RenderTicket& ticket = *renderJob->tickets.front();
  RenderOutcome outcome;
  try {
    outcome.result = ticket.wait(deadline);
  } catch (const ApiError& error) {
    outcome.error = error;
  }
  const Clock::time_point enqueued = renderJob->enqueued;
  const std::optional<Clock::time_point> started = ticket.started();
  outcome.queueMs = millisecondsBetween(enqueued, started.value_or(enqueued));
  outcome.gpu = ticket.gpu();
  std::lock_guard lock(mutex_);
  job.inFlight.reset();
  if (outcome.result && started) {
    const double seconds = secondsSince(*started);
    secondsPerRender_ =
        secondsPerRender_ == 0.0 ? seconds : 0.8 * secondsPerRender_ + 0.2 * seconds;
  }
  return outcome;
}

void JobStore::finishJob(Job& job) {
  std::shared_ptr<const JobResult> result;
  std::optional<ApiError> error;
  if (!job.cancelled) {
    if (stopping() && job.done < job.total) {
      error = unavailable("the daemon shut down before the job finished");
    } else {
      try {
        result = std::make_shared<const JobResult>(job.work->finish());
      } catch (const ApiError& failure) {
        error = failure;
      } catch (const lgh::Error& failure) {
        error = fromLghError(failure);
      } catch (const std::exception& failure) {
        logging::event(spdlog::level::err, "unhandled_exception",
                       {{"request_id", job.requestId}, {"job", job.id}, {"error", failure.what()}});
        error = internalError("internal error; the log has the details under this request id");
      }
    }
  }
  std::lock_guard lock(mutex_);
  if (job.cancelled) {
    endJob(job, JobStatus::Cancelled, "cancelled");
  } else if (error) {
    job.error = std::move(error);
    endJob(job, JobStatus::Failed, "failed");
  } else {
    job.result = std::move(result);
    job.resultBytes = job.result->bytes();
    endJob(job, JobStatus::Succeeded, "succeeded");
  }
}

void JobStore::endJob(Job& job, JobStatus status, const char* outcome) {
  job.work.reset();
  job.reservedBytes = 0;
  job.inFlight.reset();
  job.status = status;
  if (!job.finished) job.finished = SystemClock::now();
  if (!job.expires) job.expires = Clock::now() + limits_.ttl;
  ++finishedTotals_[fmt::format("kind=\"{}\",outcome=\"{}\"", job.kind, outcome)];
  json fields = {{"request_id", job.requestId},     {"job", job.id},    {"kind", job.kind},
                 {"status", jobStatusName(status)}, {"done", job.done}, {"total", job.total}};
  if (job.error) fields["error"] = job.error->body("")["error"];
  logging::event(status == JobStatus::Failed ? spdlog::level::warn : spdlog::level::info,
                 "job_finished", fields);
}

// --- Bookkeeping (under mutex_) -----------------------------------------------------------------

void JobStore::expireFinished() {
  const Clock::time_point now = Clock::now();
  std::erase_if(jobs_, [&](const auto& entry) {
    const Job& job = *entry.second;
    // A cancelled job the runner still holds stays until the runner lets go of it.
    return ended(job.status) && job.expires && *job.expires <= now && !job.work;
  });
}

std::size_t JobStore::memoryInUse() const {
  std::size_t bytes = 0;
  for (const auto& [id, job] : jobs_) bytes += job->reservedBytes + job->resultBytes;
  return bytes;
}

int JobStore::retryAfterSeconds() const {
  std::optional<Clock::time_point> firstExpiry;
  for (const auto& [id, job] : jobs_) {
    if (job->expires && (!firstExpiry || *job->expires < *firstExpiry)) firstExpiry = job->expires;
  }
  if (firstExpiry) {
    return std::max(1, static_cast<int>(std::ceil(secondsBetween(Clock::now(), *firstExpiry))));
  }
  std::size_t pendingRenders = 0;
  for (const auto& [id, job] : jobs_) {
    if (!ended(job->status)) pendingRenders += job->total - job->done;
  }
  return std::max(
      1, static_cast<int>(std::ceil(secondsPerRender_ * static_cast<double>(pendingRenders))));
}

// Renders left, times the seconds a render of this job took so far (or of recent jobs while it
// has none done); a queued job adds the renders of the jobs ahead of it. Synchronous requests
// between them are not foreseen.
std::optional<double> JobStore::etaSeconds(const Job& job) const {
  if (ended(job.status)) return std::nullopt;
  const bool ownPace = job.status == JobStatus::Running && job.done > 0;
  const double perRender =
      ownPace ? secondsSince(job.runStart) / static_cast<double>(job.done) : secondsPerRender_;
  if (perRender <= 0.0) return std::nullopt;
  std::size_t renders = job.total - job.done;
  if (job.status == JobStatus::Queued) {
    for (const auto& [id, other] : jobs_) {
      if (other->status == JobStatus::Running) renders += other->total - other->done;
    }
    for (const JobPtr& ahead : pending_) {
      if (ahead.get() == &job) break;
      renders += ahead->total;
    }
  }
  return perRender * static_cast<double>(renders);
}

json JobStore::statusJson(const Job& job) const {
  const std::string href = "/v1/jobs/" + job.id;
  json result;
  if (job.status == JobStatus::Succeeded && job.result) {
    result = {{"href", href + "/result"}, {"mime", job.result->mime}, {"bytes", job.resultBytes}};
  }
  std::optional<SystemClock::time_point> expiresAt;
  if (job.finished) {
    expiresAt = *job.finished + std::chrono::duration_cast<SystemClock::duration>(limits_.ttl);
  }
  const std::optional<double> eta = etaSeconds(job);
  return {
      {"id", job.id},
      {"href", href},
      {"kind", job.kind},
      {"status", jobStatusName(job.status)},
      {"request_id", job.requestId},
      {"created_at", rfc3339(job.created)},
      {"started_at", timeOrNull(job.started)},
      {"finished_at", timeOrNull(job.finished)},
      {"expires_at", timeOrNull(expiresAt)},
      {"progress",
       {{"done", job.done},
        {"total", job.total},
        {"failed", job.failed},
        {"fraction",
         job.total == 0 ? 1.0 : static_cast<double>(job.done) / static_cast<double>(job.total)}}},
      {"eta_seconds", eta ? json(std::round(*eta * 1000.0) / 1000.0) : json()},
      {"result", result},
      {"error", job.error ? job.error->body("")["error"] : json()}};
}

std::string JobStore::exposition() {
  std::lock_guard lock(mutex_);
  expireFinished();
  std::map<JobStatus, std::size_t> counts;
  std::size_t pendingRenders = 0;
  for (const auto& [id, job] : jobs_) {
    ++counts[job->status];
    if (!ended(job->status)) pendingRenders += job->total - job->done;
  }
  std::string out =
      "# HELP lghd_jobs Jobs held by the job store, by status.\n# TYPE lghd_jobs gauge\n";
  for (JobStatus status : {JobStatus::Queued, JobStatus::Running, JobStatus::Succeeded,
                           JobStatus::Failed, JobStatus::Cancelled}) {
    out += fmt::format("lghd_jobs{{status=\"{}\"}} {}\n", jobStatusName(status), counts[status]);
  }
  auto gauge = [&out](const char* name, const char* help, std::size_t value) {
    out += fmt::format("# HELP {} {}\n# TYPE {} gauge\n{} {}\n", name, help, name, name, value);
  };
  gauge("lghd_jobs_capacity", "Jobs the store may hold (--max-jobs).",
        static_cast<std::size_t>(limits_.maxJobs));
  gauge("lghd_jobs_pending_renders",
        "Renders not yet done of queued and running jobs: the work ahead.", pendingRenders);
  gauge("lghd_jobs_memory_bytes",
        "Job memory in use: results held plus the reservations of unfinished jobs.", memoryInUse());
  gauge("lghd_jobs_memory_budget_bytes", "Job memory budget (--jobs-memory-mb).",
        limits_.memoryBytes);
  out +=
      "# HELP lghd_jobs_total Jobs finished, by kind and outcome (succeeded, failed, "
      "cancelled).\n# TYPE lghd_jobs_total counter\n";
  for (const auto& [labels, value] : finishedTotals_) {
    out += fmt::format("lghd_jobs_total{{{}}} {}\n", labels, value);
  }
  return out;
}

}  // namespace lghd
