#include "render_queue.hpp"

#include <cmath>
#include <csignal>

#include <fmt/format.h>

#include "clock.hpp"
#include "logging.hpp"
#include "vulkan_probe_process.hpp"

namespace lghd {
namespace {

// What a renderer start-up (GL context, Vulkan device, self-test render) may take before the
// watchdog's time starts to count, as a render's deadline does for a render.
constexpr auto kStartUpAllowance = std::chrono::seconds(30);

lgh::RenderRequest selfTestRequest() {
  lgh::RenderRequest request;  // the demo scene
  request.output.width = 64;
  request.output.height = 64;
  return request;
}

}  // namespace

RenderQueue::RenderQueue(Options options, Metrics& metrics)
    : options_(std::move(options)), metrics_(metrics) {}

RenderQueue::~RenderQueue() {
  if (thread_.joinable()) stop(std::chrono::seconds(30));
  endVulkanProbe();
}

void RenderQueue::start(FatalHandler onFatal) {
  onFatal_ = std::move(onFatal);
  if (options_.watchdog.count() > 0) {
    watchdog_ = std::make_unique<RenderWatchdog>([this] { declareHung(); });
  }
  thread_ = std::thread([this] { run(); });
  // In a child process (see vulkan_probe_process.hpp), waited for on a thread of its own so that
  // readiness does not wait for it (a Vulkan instance takes a large part of a second to make). It
  // starts once the renderer is up: run beside the GL bring-up, it slowed the start-up
  // (docs/BENCHMARKS.md, "Start-up").
  vulkanProbe_ = std::thread([slot = vulkan_] {
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
  for (auto& request : requests) {
    job->tickets.push_back(std::make_shared<RenderTicket>(std::move(request)));
  }
  {
    std::lock_guard lock(mutex_);
    if (!accepting_) throw unavailable("the daemon is shutting down");
    if (state_ == State::Starting) {
      throw unavailable("starting: the GL context and its self-test render are not ready yet")
          .withRetryAfter(1);
    }
    if (state_ == State::Failed) throw unavailable(failure_);
    if (jobs_.size() >= options_.capacity) {
      throw queueFull(fmt::format("the render queue is full ({} waiting)", jobs_.size()),
                      retryAfterSeconds());
    }
    jobs_.push_back(job);
  }
  workCondition_.notify_one();
  return job;
}

int RenderQueue::retryAfterSeconds() const {
  const double wait = averageRenderSeconds_ * static_cast<double>(jobs_.size() + 1);
  return std::max(1, static_cast<int>(std::ceil(wait)));
}

bool RenderQueue::ready() const {
  std::lock_guard lock(mutex_);
  return state_ == State::Ready && accepting_;
}

std::string RenderQueue::notReadyReason() const {
  std::lock_guard lock(mutex_);
  if (!accepting_) return "shutting down";
  switch (state_) {
    case State::Starting:
      return "starting: GL context and self-test render not done yet";
    case State::Failed:
      return failure_;
    default:
      return "";
  }
}

std::optional<lgh::VulkanInfo> RenderQueue::vulkan() const {
  std::lock_guard lock(vulkan_->mutex);
  return vulkan_->info;
}

std::optional<lgh::DeviceInfo> RenderQueue::device() const {
  std::lock_guard lock(mutex_);
  return device_;
}

RuntimeGauges RenderQueue::gauges() const {
  std::lock_guard lock(mutex_);
  RuntimeGauges gauges;
  gauges.queueDepth = jobs_.size();
  gauges.queueCapacity = options_.capacity;
  gauges.rendering = current_ != nullptr;
  gauges.ready = state_ == State::Ready && accepting_;
  gauges.sceneCacheHits = cacheStats_.hits;
  gauges.sceneCacheMisses = cacheStats_.misses;
  gauges.sceneCacheEntries = cacheStats_.entries;
  gauges.sceneCacheBytes = cacheStats_.bytes;
  gauges.sceneCacheBudgetBytes = options_.renderer.sceneCacheBytes;
  gauges.resources = resources_;
  gauges.framesInFlight = framesOutstanding_;
  gauges.frameLimit = options_.output.frameLimit();
  gauges.encodeThreads = static_cast<std::size_t>(options_.output.encoderCount());
  // Live: frames give their read-back memory back on encoder threads, after the last publish.
  gauges.readbackBytes = renderer_ ? renderer_->readbackStats().heldBytes : 0;
  gauges.shadowTracer = shadowInfo_.status == "ready"         ? 1
                        : shadowInfo_.status == "unavailable" ? 0
                                                              : -1;
  return gauges;
}

// --- Shutdown -----------------------------------------------------------------------------------

void RenderQueue::stopAccepting() {
  std::lock_guard lock(mutex_);
  accepting_ = false;
}

void RenderQueue::failAll(RenderJob& job, const ApiError& error) {
  job.cancelled = true;
  for (const auto& ticket : job.tickets) ticket->fail(error);
}

bool RenderQueue::drain(Clock::duration grace) {
  std::unique_lock lock(mutex_);
  if (state_ == State::Failed) return jobs_.empty() && !current_;  // nothing left can finish
  const bool idle = idleCondition_.wait_for(
      lock, grace, [this] { return jobs_.empty() && !current_ && framesOutstanding_ == 0; });
  if (idle) return true;
  const ApiError cancelled = unavailable("the daemon is shutting down: render cancelled");
  logging::event(spdlog::level::warn, "drain_timeout",
                 {{"cancelled_jobs", jobs_.size() + (current_ ? 1 : 0)},
                  {"frames_in_flight", framesOutstanding_}});
  for (const auto& job : jobs_) failAll(*job, cancelled);
  jobs_.clear();
  if (current_) failAll(*current_, cancelled);
  return false;
}

bool RenderQueue::stop(Clock::duration wait) {
  std::unique_lock lock(mutex_);
  accepting_ = false;
  stopping_ = true;
  workCondition_.notify_all();
  const bool done = idleCondition_.wait_for(lock, wait, [this] { return threadDone_; });
  lock.unlock();
  endVulkanProbe();
  if (!thread_.joinable()) return true;
  if (!done) {
    thread_.detach();  // stuck in a driver call; the process is about to exit
    return false;
  }
  thread_.join();
  return true;
}

// --- The render thread --------------------------------------------------------------------------

void RenderQueue::run() {
  const bool up = bringUpRenderer();
  releaseVulkanProbe();
  if (up) {
    while (std::shared_ptr<RenderJob> job = takeJob()) {
      runJob(job);
      finishJob();
    }
    settleFramesInFlight();
  }
  releaseRenderer();  // the context is destroyed on the thread that made it
  std::lock_guard lock(mutex_);
  threadDone_ = true;
  idleCondition_.notify_all();
}

bool RenderQueue::bringUpRenderer() {
  const auto start = Clock::now();
  if (!encoders_) encoders_ = std::make_unique<lgh::TaskPool>(options_.output.encoderCount());
  try {
    const WatchdogScope watched(watchdog_.get(), start + kStartUpAllowance + options_.watchdog);
    auto renderer = std::make_unique<lgh::Renderer>(options_.renderer);
    const lgh::RenderResult selfTest = renderer->render(selfTestRequest());
    if (selfTest.encoded.empty()) throw internalError("the self-test render produced no image");
    std::lock_guard lock(mutex_);
    renderer_ = std::move(renderer);
  } catch (const std::exception& error) {
    {
      std::lock_guard lock(mutex_);
      state_ = State::Failed;
      failure_ = std::string("no working GL context: ") + error.what();
      const ApiError noContext = unavailable(failure_);
      for (const auto& job : jobs_) failAll(*job, noContext);
      jobs_.clear();
    }
    logging::event(spdlog::level::critical, "renderer_failed", {{"error", error.what()}});
    if (onFatal_) onFatal_(1, error.what());
    return false;
  }
  publishRendererState();
  std::lock_guard lock(mutex_);
  device_ = renderer_->device();
  state_ = State::Ready;
  logging::event(spdlog::level::info, "ready",
                 {{"device", device_->toJson()}, {"startup_ms", millisecondsSince(start)}});
  return true;
}

// After a GL failure the context may be broken: replace it rather than serve from it. The frames
// in flight on it fail, and the encoders finish reading pixels from its read-back memory first.
void RenderQueue::recoverRenderer(const std::string& reason) {
  logging::event(spdlog::level::err, "renderer_reset", {{"reason", reason}});
  failFramesInFlight(
      internalError("the GL context failed while this frame was in flight: " + reason));
  encoders_->waitIdle();
  releaseRenderer();
  {
    std::lock_guard lock(mutex_);
    state_ = State::Starting;
  }
  bringUpRenderer();
}

// The next job; while none waits and frames are in flight, those are finished and handed to the
// encoders instead of sleeping.
std::shared_ptr<RenderJob> RenderQueue::takeJob() {
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      if (submitted_.empty()) {
        workCondition_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
      }
      if (stopping_ || state_ == State::Failed) return nullptr;
      if (!jobs_.empty()) {
        current_ = std::move(jobs_.front());
        jobs_.pop_front();
        return current_;
      }
    }
    completeFrame(true);
    if (!renderer_) return nullptr;  // recovery failed: the daemon is going down
  }
}

void RenderQueue::finishJob() {
  std::lock_guard lock(mutex_);
  current_.reset();
  idleCondition_.notify_all();
}

const lgh::RenderRequest* RenderQueue::nextRequest(const RenderJob& job, std::size_t index) {
  if (index + 1 < job.tickets.size()) return &job.tickets[index + 1]->request();
  std::lock_guard lock(mutex_);
  // Tickets never change once queued, and the job stays alive in the queue while it is read.
  if (!jobs_.empty() && !jobs_.front()->tickets.empty()) {
    return &jobs_.front()->tickets.front()->request();
  }
  return nullptr;
}

void RenderQueue::runJob(const std::shared_ptr<RenderJob>& job) {
  if (Clock::now() > job->startDeadline) {
    failAll(*job, timedOut("the render waited in the queue past its deadline"));
    for (std::size_t i = 0; i < job->tickets.size(); ++i) metrics_.recordRender("skipped");
    logging::event(spdlog::level::warn, "job_expired_in_queue", {{"request_id", job->requestId}});
    return;
  }
  for (std::size_t i = 0; i < job->tickets.size(); ++i) {
    const std::shared_ptr<RenderTicket>& ticket = job->tickets[i];
    if (job->cancelled) ticket->fail(unavailable("the batch was cancelled"));
    if (ticket->settled()) {  // its waiter gave up (deadline) or the job was cancelled
      metrics_.recordRender("skipped");
      continue;
    }
    submitTicket(job, ticket, nextRequest(*job, i));
    if (!renderer_) {  // recovery failed: the daemon is going down
      failAll(*job, unavailable("no working GL context"));
      return;
    }
    while (completeFrame(false)) {
    }
  }
}

// --- Frames in flight ---------------------------------------------------------------------------

namespace {

std::size_t frameBytes(const lgh::RenderRequest& request) {
  const lgh::FramePixels shape{request.output.width, request.output.height,
                               lgh::pixelLayoutFor(request.output), nullptr};
  return shape.size();
}

}  // namespace

void RenderQueue::submitTicket(const std::shared_ptr<RenderJob>& job,
                               const std::shared_ptr<RenderTicket>& ticket,
                               const lgh::RenderRequest* next) {
  const std::size_t bytes = frameBytes(ticket->request());
  waitForFrameCapacity(bytes);
  if (!renderer_) return;
  ticket->markStarted();
  const auto start = Clock::now();
  try {
    const WatchdogScope watched(watchdog_.get(), job->startDeadline + options_.watchdog);
    if (options_.testRenderDelay.count() > 0) std::this_thread::sleep_for(options_.testRenderDelay);
    // The next scene is parsed while this one uploads and renders.
    if (next != nullptr) renderer_->prefetch(*next);
    renderer_->submit(ticket->request());
    submitted_.push_back({job, ticket, start, start, bytes});
    std::lock_guard lock(mutex_);
    ++framesOutstanding_;
    bytesOutstanding_ += bytes;
  } catch (const lgh::Error& error) {
    ticket->fail(fromLghError(error));
    metrics_.recordRender("error");
    // A GL failure may have broken the context, and a lost one (GPU reset) certainly has.
    if (error.code() == lgh::ErrorCode::Internal || !renderer_->healthy()) {
      recoverRenderer(error.what());
    }
  } catch (const std::exception& error) {
    ticket->fail(internalError(error.what()));
    metrics_.recordRender("error");
    recoverRenderer(error.what());
  }
}

void RenderQueue::waitForFrameCapacity(std::size_t bytes) {
  const std::size_t frameLimit = options_.output.frameLimit();
  const std::size_t byteLimit = options_.output.readbackBytes;
  const auto fits = [&] {
    return framesOutstanding_ == 0 ||
           (framesOutstanding_ < frameLimit && bytesOutstanding_ + bytes <= byteLimit);
  };
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      if (fits()) return;
      if (submitted_.empty()) {  // only the encoders can make room
        frameDoneCondition_.wait(lock, fits);
        return;
      }
    }
    completeFrame(true);
    if (!renderer_) return;
  }
}

bool RenderQueue::completeFrame(bool wait) {
  if (submitted_.empty() || !renderer_) return false;
  std::optional<lgh::RenderResult> result;
  try {
    const WatchdogScope watched(watchdog_.get(),
                                submitted_.front().job->startDeadline + options_.watchdog);
    result = renderer_->finish(wait);
  } catch (const std::exception& error) {
    recoverRenderer(error.what());
    return false;
  }
  if (!result) return false;
  FrameInFlight frame = std::move(submitted_.front());
  submitted_.pop_front();
  frame.finished = Clock::now();
  publishRendererState();
  encoders_->submit([this, frame = std::move(frame), result = std::move(*result)]() mutable {
    encode(frame, result);
  });
  return true;
}

void RenderQueue::encode(FrameInFlight& frame, lgh::RenderResult& result) {
  RenderTicket& ticket = *frame.ticket;
  const auto encodeStart = Clock::now();
  const double queueMs = millisecondsBetween(frame.job->enqueued, frame.started);
  const double waitMs = millisecondsBetween(frame.finished, encodeStart);
  auto& rows = result.timings.rows;
  rows.insert(rows.begin(), lgh::TimingRow{"queue", lgh::TimingRow::Clock::Cpu, queueMs, 0});
  result.timings.add("encode wait", lgh::TimingRow::Clock::Cpu, waitMs);
  bool failed = false;
  bool encoded = false;
  // A ticket settled already (its waiter's deadline, a cancel, the shutdown) is not encoded.
  if (!ticket.settled()) {
    try {
      result.encoded = result.encode(encoders_.get());
      result.mimeType = lgh::mimeType(result.output.format);
      encoded = true;
    } catch (const std::exception& error) {
      failed = true;
      ticket.fail(internalError(std::string("encoding failed: ") + error.what()));
    }
  }
  result.pixels.release();  // back to the renderer's read-back memory
  const double encodeSeconds = secondsSince(encodeStart);
  result.timings.add("encode", lgh::TimingRow::Clock::Cpu, encodeSeconds * 1000.0);
  result.timings.add("total", lgh::TimingRow::Clock::Cpu, millisecondsSince(frame.started));
  if (encoded) {
    metrics_.recordEncode(lgh::enumName(result.output.format), waitMs / 1000.0, encodeSeconds);
  }
  metrics_.recordRenderTimes(result.timings, queueMs / 1000.0, result.sceneCacheHit);
  if (const auto shadows = result.decisions.find("shadows"); shadows != result.decisions.end()) {
    metrics_.recordShadows(shadows->second);
  }
  if (failed) {
    metrics_.recordRender("error");
  } else if (ticket.complete(std::move(result))) {
    metrics_.recordRender("ok");
  } else {
    metrics_.recordRender("timeout");
    logging::event(
        spdlog::level::warn, "render_discarded",
        {{"request_id", frame.job->requestId}, {"render_ms", millisecondsSince(frame.started)}});
  }
  frameDone(frame, secondsSince(frame.started));
}

void RenderQueue::frameDone(const FrameInFlight& frame, double seconds) {
  {
    std::lock_guard lock(mutex_);
    --framesOutstanding_;
    bytesOutstanding_ -= frame.bytes;
    if (seconds > 0.0) averageRenderSeconds_ = 0.8 * averageRenderSeconds_ + 0.2 * seconds;
  }
  frameDoneCondition_.notify_all();
  idleCondition_.notify_all();
}

void RenderQueue::failFramesInFlight(const ApiError& error) {
  while (!submitted_.empty()) {
    FrameInFlight frame = std::move(submitted_.front());
    submitted_.pop_front();
    frame.ticket->fail(error);
    metrics_.recordRender("error");
    frameDone(frame, 0.0);
  }
}

// At the end: the frames in flight finish and are encoded (or dropped, when their tickets were
// settled by the shutdown), before the renderer and its read-back memory go.
void RenderQueue::settleFramesInFlight() {
  while (completeFrame(true)) {
  }
  if (!submitted_.empty()) failFramesInFlight(unavailable("the daemon is shutting down"));
  if (encoders_) encoders_->waitIdle();
}

// --- The watchdog -------------------------------------------------------------------------------

// On the watchdog's thread, while the render thread is stuck: answer everyone, turn not ready and
// have the process end (a context stuck in a driver call cannot be replaced in this process).
void RenderQueue::declareHung() {
  const auto seconds = std::chrono::duration<double>(options_.watchdog).count();
  const std::string reason = fmt::format(
      "the render thread has been stuck in one render (or renderer start-up) for {:g} s past "
      "its deadline (--watchdog-seconds): the GPU or its driver hangs; lghd exits so that its "
      "supervisor starts it again",
      seconds);
  std::string requestId;
  {
    std::lock_guard lock(mutex_);
    state_ = State::Failed;
    failure_ = reason;
    const ApiError hung = unavailable(reason).withRetryAfter(5);
    for (const auto& job : jobs_) failAll(*job, hung);
    jobs_.clear();
    if (current_) {
      requestId = current_->requestId;
      failAll(*current_, hung);
    }
  }
  metrics_.recordRender("hung");
  logging::event(spdlog::level::critical, "render_hung",
                 {{"request_id", requestId}, {"watchdog_s", seconds}, {"reason", reason}});
  if (onFatal_) onFatal_(kExitRenderHung, reason);
}

void RenderQueue::publishRendererState() {
  const lgh::Renderer::CacheStats stats = renderer_->sceneCacheStats();
  lgh::ShadowInfo shadows = renderer_->shadowInfo();
  lgh::ResourceStats resources = renderer_->resourceStats();
  std::lock_guard lock(mutex_);
  cacheStats_ = stats;
  shadowInfo_ = std::move(shadows);
  resources_ = std::move(resources);
}

lgh::ResourceStats RenderQueue::resources() const {
  std::lock_guard lock(mutex_);
  return resources_;
}

// Under mutex_, so that gauges() may read the renderer's read-back memory from HTTP threads.
void RenderQueue::releaseRenderer() {
  std::lock_guard lock(mutex_);
  renderer_.reset();
}

lgh::ShadowInfo RenderQueue::shadows() const {
  std::lock_guard lock(mutex_);
  return shadowInfo_;
}

}  // namespace lghd
