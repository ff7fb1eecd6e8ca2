#include "render_queue.hpp"

#include <algorithm>
#include <cmath>
#include <csignal>
#include <set>

#include <fmt/format.h>

#include "clock.hpp"
#include "lgh/thread_name.hpp"
#include "logging.hpp"
#include "vulkan_probe_process.hpp"

namespace lghd {
namespace {

bool anyIn(const std::vector<RenderWorker::Status>& workers, RenderWorker::State state) {
  return std::any_of(workers.begin(), workers.end(),
                     [state](const RenderWorker::Status& worker) { return worker.state == state; });
}

std::string describeWorkers(const std::vector<RenderWorker::Status>& workers) {
  std::string text;
  for (const RenderWorker::Status& worker : workers) {
    if (!text.empty()) text += "; ";
    text += fmt::format("gpu {}: {}", worker.index, workerStateName(worker.state));
    if (!worker.failure.empty()) text += " (" + worker.failure + ")";
  }
  return text;
}

}  // namespace

RenderQueue::RenderQueue(Options options, Metrics& metrics)
    : options_(std::move(options)), metrics_(metrics) {
  if (options_.gpus.empty()) options_.gpus.push_back(options_.renderer.gpuIndex);
}

RenderQueue::~RenderQueue() {
  if (!workers_.empty()) stop(std::chrono::seconds(30));
  endVulkanProbe();
}

void RenderQueue::start(FatalHandler onFatal) {
  onFatal_ = std::move(onFatal);
  encoders_ = std::make_unique<lgh::TaskPool>(options_.output.encoderCount(), "lgh-encode");
  RenderWorker::Hooks hooks;
  hooks.stateChanged = [this](RenderWorker& worker) { workerStateChanged(worker); };
  hooks.piecesReturned = [this](RenderWorker& worker, std::vector<JobPiece> pieces) {
    piecesReturned(worker, std::move(pieces));
  };
  hooks.pieceLeft = [this](RenderJob& job) { pieceLeft(job); };
  hooks.hung = [this](RenderWorker& worker) { declareHung(worker); };
  for (std::size_t i = 0; i < options_.gpus.size(); ++i) {
    RenderWorker::Options worker{static_cast<int>(i), options_.renderer, options_.testRenderDelay,
                                 options_.watchdog, options_.output};
    worker.renderer.gpuIndex = options_.gpus[i];
    if (static_cast<int>(i) == options_.testContextLossGpu) {
      worker.renderer.debugContextLossAfter = options_.testContextLossAfter;
    }
    workers_.push_back(
        std::make_unique<RenderWorker>(std::move(worker), metrics_, *encoders_, hooks));
  }
  for (const auto& worker : workers_) worker->start();
  // In a child process (see vulkan_probe_process.hpp), waited for on a thread of its own so that
  // readiness does not wait for it (a Vulkan instance takes a large part of a second to make). It
  // starts once a renderer is up: run beside the GL bring-up, it slowed the start-up
  // (docs/BENCHMARKS.md, "Start-up").
  vulkanProbe_ = std::thread([slot = vulkan_] {
    lgh::nameThisThread("lgh-vk-probe");
    {
      std::unique_lock lock(slot->mutex);
      slot->changed.wait(lock, [&] { return slot->mayStart || slot->cancelled; });
      if (slot->cancelled) {
        slot->done = true;
        return;
      }
    }
    lgh::VulkanInfo vulkan = probeVulkanInChildProcess(slot->child);
    {
      std::lock_guard lock(slot->mutex);
      if (slot->cancelled && !vulkan.available) {
        logging::event(spdlog::level::info, "vulkan", {{"error", "probe cancelled at shutdown"}});
      } else {
        logging::event(spdlog::level::info, "vulkan", vulkan.toJson());
        slot->info = std::move(vulkan);
      }
      slot->done = true;
    }
    slot->changed.notify_all();
  });
}

void RenderQueue::releaseVulkanProbe() {
  {
    std::lock_guard lock(vulkan_->mutex);
    vulkan_->mayStart = true;
  }
  vulkan_->changed.notify_all();
}

// Cancels a probe that has not started and kills one that has not finished (a hung driver). The
// child can be spawned just after a look at `child`, so it is looked at again until the probe
// thread is done.
void RenderQueue::endVulkanProbe() {
  if (!vulkanProbe_.joinable()) return;
  {
    std::unique_lock lock(vulkan_->mutex);
    vulkan_->cancelled = true;
    vulkan_->changed.notify_all();
    while (!vulkan_->done) {
      if (const pid_t child = vulkan_->child; child > 0) kill(child, SIGKILL);
      vulkan_->changed.wait_for(lock, std::chrono::milliseconds(10));
    }
  }
  vulkanProbe_.join();
}

// --- HTTP threads -------------------------------------------------------------------------------

std::shared_ptr<RenderJob> RenderQueue::submit(std::vector<lgh::RenderRequest> requests,
                                               const std::string& requestId,
                                               Clock::time_point startDeadline) {
  auto job = std::make_shared<RenderJob>();
  job->requestId = requestId;
  job->enqueued = Clock::now();
  job->startDeadline = startDeadline;
  std::vector<std::size_t> tickets;
  for (auto& request : requests) {
    tickets.push_back(job->tickets.size());
    job->tickets.push_back(std::make_shared<RenderTicket>(std::move(request)));
  }
  std::lock_guard lock(mutex_);
  if (!accepting_) throw unavailable("the daemon is shutting down");
  if (hung_) throw unavailable(hungReason_);
  if (workers_.empty()) {
    throw unavailable("starting: the GL context and its self-test render are not ready yet")
        .withRetryAfter(1);
  }
  if (waitingJobs_ >= options_.capacity) {
    throw queueFull(fmt::format("the render queue is full ({} waiting)", waitingJobs_),
                    retryAfterSeconds());
  }
  if (tickets.empty()) return job;
  std::vector<JobPiece> pieces = assign(job, tickets);
  if (pieces.empty()) {
    const std::vector<RenderWorker::Status> states = workers();
    if (anyIn(states, RenderWorker::State::Starting)) {
      throw unavailable("starting: the GL context and its self-test render are not ready yet")
          .withRetryAfter(1);
    }
    if (anyIn(states, RenderWorker::State::Rebuilding)) {
      throw unavailable("every GPU's render worker is rebuilding its GL context").withRetryAfter(1);
    }
    throw unavailable(states.size() == 1 ? states.front().failure : describeWorkers(states));
  }
  job->piecesWaiting = pieces.size();
  ++waitingJobs_;
  dispatch(std::move(pieces));
  return job;
}

// Each ticket in order goes to the worker that finishes it soonest, counting what this job has
// given each worker already (its work, and its scenes as resident there).
std::vector<JobPiece> RenderQueue::assign(const std::shared_ptr<RenderJob>& job,
                                          const std::vector<std::size_t>& tickets) const {
  const std::size_t count = workers_.size();
  std::vector<JobPiece> pieces(count);
  std::vector<double> added(count, 0.0);
  std::vector<std::set<std::string>> planned(count);
  for (std::size_t ticket : tickets) {
    const std::string scene = sceneKey(job->tickets[ticket]->request().scene);
    std::vector<WorkerEstimate> estimates;
    estimates.reserve(count);
    for (std::size_t w = 0; w < count; ++w) {
      WorkerEstimate estimate = workers_[w]->estimate(scene);
      estimate.pendingSeconds += added[w];
      estimate.resident = estimate.resident || planned[w].count(scene) > 0;
      estimates.push_back(estimate);
    }
    const std::optional<std::size_t> chosen = chooseWorker(estimates);
    if (!chosen) return {};
    const double seconds = estimates[*chosen].renderSeconds();
    JobPiece& piece = pieces[*chosen];
    piece.job = job;
    piece.worker = *chosen;
    piece.tickets.push_back(ticket);
    piece.scenes.push_back(scene);
    piece.estimates.push_back(seconds);
    added[*chosen] += seconds;
    planned[*chosen].insert(scene);
  }
  std::erase_if(pieces, [](const JobPiece& piece) { return piece.tickets.empty(); });
  return pieces;
}

void RenderQueue::dispatch(std::vector<JobPiece> pieces) {
  for (JobPiece& piece : pieces) {
    const std::size_t worker = piece.worker;
    workers_[worker]->enqueue(std::move(piece));
  }
}

int RenderQueue::retryAfterSeconds() const {
  double seconds = 0.0;
  std::size_t ready = 0;
  for (const auto& worker : workers_) {
    const RenderWorker::Status status = worker->status();
    if (status.state != RenderWorker::State::Ready) continue;
    seconds += status.averageRenderSeconds;
    ++ready;
  }
  const double average = ready > 0 ? seconds / static_cast<double>(ready) : 0.1;
  const double wait = average * static_cast<double>(waitingJobs_ + 1) /
                      static_cast<double>(std::max<std::size_t>(ready, 1));
  return std::max(1, static_cast<int>(std::ceil(wait)));
}

bool RenderQueue::ready() const { return notReadyReason().empty(); }

std::string RenderQueue::notReadyReason() const {
  {
    std::lock_guard lock(mutex_);
    if (!accepting_) return "shutting down";
    if (hung_) return hungReason_;
  }
  const std::vector<RenderWorker::Status> states = workers();
  if (states.empty() || std::all_of(states.begin(), states.end(), [](const auto& worker) {
        return worker.state == RenderWorker::State::Starting;
      })) {
    return "starting: GL context and self-test render not done yet";
  }
  if (anyIn(states, RenderWorker::State::Ready)) return "";
  if (states.size() == 1) {
    const RenderWorker::Status& only = states.front();
    return only.state == RenderWorker::State::Failed
               ? only.failure
               : "starting: GL context and self-test render not done yet";
  }
  return "no GPU's render worker is ready: " + describeWorkers(states);
}

std::optional<lgh::VulkanInfo> RenderQueue::vulkan() const {
  std::lock_guard lock(vulkan_->mutex);
  return vulkan_->info;
}

std::vector<RenderWorker::Status> RenderQueue::workers() const {
  std::vector<RenderWorker::Status> states;
  states.reserve(workers_.size());
  for (const auto& worker : workers_) states.push_back(worker->status());
  return states;
}

std::optional<lgh::DeviceInfo> RenderQueue::device() const {
  const std::vector<RenderWorker::Status> states = workers();
  for (const RenderWorker::Status& worker : states) {
    if (worker.state == RenderWorker::State::Ready && worker.device) return worker.device;
  }
  for (const RenderWorker::Status& worker : states) {
    if (worker.device) return worker.device;
  }
  return std::nullopt;
}

RuntimeGauges RenderQueue::gauges() const {
  RuntimeGauges gauges;
  const std::vector<RenderWorker::Status> states = workers();
  gauges.ready = ready();
  {
    std::lock_guard lock(mutex_);
    gauges.queueDepth = waitingJobs_;
  }
  gauges.queueCapacity = options_.capacity;
  gauges.frameLimit = options_.output.frameLimit() * std::max<std::size_t>(states.size(), 1);
  gauges.encodeThreads = static_cast<std::size_t>(options_.output.encoderCount());
  for (const RenderWorker::Status& worker : states) {
    gauges.rendering = gauges.rendering || worker.rendering;
    gauges.sceneCacheHits += worker.cache.hits;
    gauges.sceneCacheMisses += worker.cache.misses;
    gauges.sceneCacheEntries += worker.cache.entries;
    gauges.sceneCacheBytes += worker.cache.bytes;
    gauges.sceneCacheBudgetBytes += options_.renderer.sceneCacheBytes;
    gauges.sceneStorageKeptBytes += worker.cache.keptStorageBytes;
    gauges.framesInFlight += worker.framesInFlight;
    gauges.readbackBytes += worker.readbackBytes;
    GpuGauges gpu;
    gpu.index = worker.index;
    gpu.ready = worker.state == RenderWorker::State::Ready;
    gpu.queuedRenders = worker.queuedRenders;
    gpu.rendering = worker.rendering;
    gpu.sceneCacheHits = worker.cache.hits;
    gpu.sceneCacheMisses = worker.cache.misses;
    gpu.sceneCacheEntries = worker.cache.entries;
    gpu.sceneCacheBytes = worker.cache.bytes;
    gpu.framesInFlight = worker.framesInFlight;
    gauges.gpus.push_back(gpu);
  }
  if (!states.empty()) {
    const RenderWorker::Status& first = states.front();
    gauges.resources = first.resources;
    gauges.shadowTracer = first.shadows.status == "ready"         ? 1
                          : first.shadows.status == "unavailable" ? 0
                                                                  : -1;
  }
  return gauges;
}

lgh::ShadowInfo RenderQueue::shadows() const {
  return workers_.empty() ? lgh::ShadowInfo{} : workers_.front()->status().shadows;
}

lgh::ResourceStats RenderQueue::resources() const {
  return workers_.empty() ? lgh::ResourceStats{} : workers_.front()->status().resources;
}

// --- Worker threads -----------------------------------------------------------------------------

void RenderQueue::pieceLeft(RenderJob& job) {
  if (job.piecesWaiting.fetch_sub(1) != 1) return;
  std::lock_guard lock(mutex_);
  --waitingJobs_;
}

// A worker going out of scheduling gives its queued pieces back: they go to the other workers,
// or wait for it when there are none.
void RenderQueue::piecesReturned(RenderWorker& from, std::vector<JobPiece> pieces) {
  std::lock_guard lock(mutex_);
  for (JobPiece& piece : pieces) {
    std::vector<JobPiece> spread = assign(piece.job, piece.tickets);
    if (spread.empty()) {
      from.enqueue(std::move(piece));
      continue;
    }
    piece.job->piecesWaiting += spread.size() - 1;
    logging::event(spdlog::level::info, "renders_moved",
                   {{"request_id", piece.job->requestId},
                    {"from_gpu", from.index()},
                    {"renders", piece.tickets.size()}});
    dispatch(std::move(spread));
  }
}

void RenderQueue::workerStateChanged(RenderWorker& worker) {
  const RenderWorker::Status status = worker.status();
  logging::event(spdlog::level::info, "gpu_state",
                 {{"gpu", status.index}, {"state", workerStateName(status.state)}});
  if (status.state == RenderWorker::State::Ready || status.state == RenderWorker::State::Failed) {
    releaseVulkanProbe();
  }
  if (status.state != RenderWorker::State::Failed) return;
  const std::vector<RenderWorker::Status> states = workers();
  const bool noneLeft = std::all_of(states.begin(), states.end(), [](const auto& other) {
    return other.state == RenderWorker::State::Failed;
  });
  {
    std::lock_guard lock(mutex_);
    if (hung_) return;
  }
  if (!noneLeft || !onFatal_) return;
  if (states.size() > 1) {
    onFatal_(1, describeWorkers(states));
    return;
  }
  // One worker: the renderer's own words, as the exit reason has always been.
  constexpr std::string_view kPrefix = "no working GL context: ";
  const std::string& failure = status.failure;
  onFatal_(1, failure.starts_with(kPrefix) ? failure.substr(kPrefix.size()) : failure);
}

// On the hung worker's watchdog thread, while its render thread is stuck: answer everyone on every
// worker, turn not ready and have the process end (a context stuck in a driver call cannot be
// replaced in this process, and the process is what the supervisor restarts).
void RenderQueue::declareHung(RenderWorker& worker) {
  const auto seconds = std::chrono::duration<double>(options_.watchdog).count();
  const std::string reason = fmt::format(
      "the render thread of GPU {} has been stuck in one render (or renderer start-up) for {:g} s "
      "past its deadline (--watchdog-seconds): the GPU or its driver hangs; lghd exits so that "
      "its supervisor starts it again",
      worker.index(), seconds);
  {
    std::lock_guard lock(mutex_);
    hung_ = true;
    hungReason_ = reason;
  }
  worker.markHung(reason);
  const ApiError hung = unavailable(reason).withRetryAfter(5);
  for (const auto& each : workers_) each->failAll(hung);
  logging::event(spdlog::level::critical, "render_hung",
                 {{"gpu", worker.index()}, {"watchdog_s", seconds}, {"reason", reason}});
  if (onFatal_) onFatal_(kExitRenderHung, reason);
}

// --- Shutdown -----------------------------------------------------------------------------------

void RenderQueue::stopAccepting() {
  std::lock_guard lock(mutex_);
  accepting_ = false;
}

bool RenderQueue::drain(Clock::duration grace) {
  const Clock::time_point deadline = Clock::now() + grace;
  bool idle = true;
  for (const auto& worker : workers_) idle = worker->waitIdle(deadline) && idle;
  if (idle) return true;
  const ApiError cancelled = unavailable("the daemon is shutting down: render cancelled");
  std::size_t frames = 0;
  for (const RenderWorker::Status& status : workers()) frames += status.framesInFlight;
  std::size_t jobs = 0;
  for (const auto& worker : workers_) jobs += worker->failAll(cancelled);
  logging::event(spdlog::level::warn, "drain_timeout",
                 {{"cancelled_jobs", jobs}, {"frames_in_flight", frames}});
  return false;
}

bool RenderQueue::stop(Clock::duration wait) {
  {
    std::lock_guard lock(mutex_);
    accepting_ = false;
  }
  for (const auto& worker : workers_) worker->requestStop();
  const Clock::time_point deadline = Clock::now() + wait;
  bool stopped = true;
  for (const auto& worker : workers_) {
    stopped = worker->join(std::max<Clock::duration>(deadline - Clock::now(), Clock::duration{})) &&
              stopped;
  }
  endVulkanProbe();
  return stopped;
}

}  // namespace lghd
