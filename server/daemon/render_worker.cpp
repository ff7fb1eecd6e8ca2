#include "render_worker.hpp"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

#include "lgh/thread_name.hpp"
#include "logging.hpp"

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

std::size_t frameBytes(const lgh::RenderRequest& request) {
  const lgh::FramePixels shape{request.output.width, request.output.height,
                               lgh::pixelLayoutFor(request.output), nullptr};
  return shape.size();
}

double pieceSeconds(const JobPiece& piece) {
  return std::accumulate(piece.estimates.begin(), piece.estimates.end(), 0.0);
}

void failJob(RenderJob& job, const ApiError& error) {
  job.cancelled = true;
  for (const auto& ticket : job.tickets) ticket->fail(error);
}

// Workers make and destroy their renderers one at a time. On the H200, two workers starting at
// once on one GPU both hung in their start-up (the watchdog ended lghd after 90 s); the driver's
// context and device set-up is not to be raced (docs/BENCHMARKS.md, "Several render workers").
std::mutex& rendererSetupMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

const char* workerStateName(RenderWorker::State state) {
  switch (state) {
    case RenderWorker::State::Starting:
      return "starting";
    case RenderWorker::State::Ready:
      return "ready";
    case RenderWorker::State::Rebuilding:
      return "rebuilding";
    case RenderWorker::State::Failed:
      return "failed";
  }
  return "unknown";
}

RenderWorker::RenderWorker(Options options, Metrics& metrics, lgh::TaskPool& encoders, Hooks hooks)
    : options_(std::move(options)),
      metrics_(metrics),
      encoders_(encoders),
      hooks_(std::move(hooks)) {}

RenderWorker::~RenderWorker() {
  if (thread_.joinable()) {
    requestStop();
    join(std::chrono::seconds(30));
  }
}

void RenderWorker::start() {
  if (options_.watchdog.count() > 0) {
    watchdog_ = std::make_unique<RenderWatchdog>([this] {
      if (hooks_.hung) hooks_.hung(*this);
    });
  }
  thread_ = std::thread([this] { run(); });
}

// --- Other threads ------------------------------------------------------------------------------

void RenderWorker::enqueue(JobPiece piece) {
  {
    std::lock_guard lock(mutex_);
    pendingSeconds_ += pieceSeconds(piece);
    pieces_.push_back(std::move(piece));
  }
  workCondition_.notify_one();
}

WorkerEstimate RenderWorker::estimate(const std::string& scene) const {
  std::lock_guard lock(mutex_);
  WorkerEstimate estimate;
  estimate.schedulable = state_ == State::Ready && !stopping_;
  estimate.pendingSeconds = pendingSeconds_;
  estimate.hitSeconds = hitSeconds_;
  estimate.missSeconds = missSeconds_;
  estimate.resident = resident_.contains(scene);
  return estimate;
}

RenderWorker::Status RenderWorker::status() const {
  std::lock_guard lock(mutex_);
  Status status;
  status.index = options_.index;
  status.deviceIndex = options_.renderer.gpuIndex;
  status.state = state_;
  status.failure = failure_;
  status.device = device_;
  for (const JobPiece& piece : pieces_) status.queuedRenders += piece.tickets.size();
  status.rendering = current_.has_value();
  status.pendingSeconds = pendingSeconds_;
  status.cache = cacheStats_;
  status.framesInFlight = framesOutstanding_;
  // Live: frames give their read-back memory back on encoder threads, after the last publish.
  status.readbackBytes = renderer_ ? renderer_->readbackStats().heldBytes : 0;
  status.shadows = shadowInfo_;
  status.resources = resources_;
  status.averageRenderSeconds = averageRenderSeconds_;
  return status;
}

bool RenderWorker::waitIdle(Clock::time_point deadline) {
  std::unique_lock lock(mutex_);
  if (state_ == State::Failed) return pieces_.empty() && !current_;  // nothing left can finish
  return idleCondition_.wait_until(
      lock, deadline, [this] { return pieces_.empty() && !current_ && framesOutstanding_ == 0; });
}

std::size_t RenderWorker::failAll(const ApiError& error) {
  std::deque<JobPiece> queued;
  std::shared_ptr<RenderJob> current;
  {
    std::lock_guard lock(mutex_);
    queued.swap(pieces_);
    for (const JobPiece& piece : queued) pendingSeconds_ -= pieceSeconds(piece);
    if (current_) current = current_->job;
  }
  for (JobPiece& piece : queued) {
    failJob(*piece.job, error);
    if (hooks_.pieceLeft) hooks_.pieceLeft(*piece.job);
  }
  if (current) failJob(*current, error);
  idleCondition_.notify_all();
  return queued.size() + (current ? 1 : 0);
}

void RenderWorker::markHung(const std::string& reason) {
  {
    std::lock_guard lock(mutex_);
    hung_ = true;
    state_ = State::Failed;
    failure_ = reason;
  }
  metrics_.recordRender("hung", options_.index);
}

void RenderWorker::requestStop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  workCondition_.notify_all();
}

bool RenderWorker::join(Clock::duration wait) {
  if (!thread_.joinable()) return true;
  bool done = false;
  {
    std::unique_lock lock(mutex_);
    done = idleCondition_.wait_for(lock, wait, [this] { return threadDone_; });
  }
  if (!done) {
    thread_.detach();  // stuck in a driver call; the process is about to exit
    return false;
  }
  thread_.join();
  return true;
}

// --- The render thread --------------------------------------------------------------------------

void RenderWorker::run() {
  // Named once the renderer is up: the threads the drivers start while it comes up take the name
  // of the thread that starts them, and should not pass for the render thread.
  if (bringUpRenderer()) {
    lgh::nameThisThread(fmt::format("lgh-render-{}", options_.index));
    while (std::optional<JobPiece> piece = takePiece()) {
      runPiece(*piece);
      finishPiece();
    }
    settleFramesInFlight();
  }
  releaseRenderer();  // the context is destroyed on the thread that made it
  std::lock_guard lock(mutex_);
  threadDone_ = true;
  idleCondition_.notify_all();
}

void RenderWorker::setState(State state, const std::string& failure) {
  {
    std::lock_guard lock(mutex_);
    if (hung_) return;
    state_ = state;
    failure_ = failure;
  }
  if (hooks_.stateChanged) hooks_.stateChanged(*this);
}

bool RenderWorker::bringUpRenderer() {
  const auto start = Clock::now();
  try {
    const WatchdogScope watched(watchdog_.get(), start + kStartUpAllowance + options_.watchdog);
    std::unique_ptr<lgh::Renderer> renderer;
    {
      const std::lock_guard setup(rendererSetupMutex());
      renderer = std::make_unique<lgh::Renderer>(options_.renderer);
      const lgh::RenderResult selfTest = renderer->render(selfTestRequest());
      if (selfTest.encoded.empty()) throw internalError("the self-test render produced no image");
    }
    std::lock_guard lock(mutex_);
    std::swap(renderer_, renderer);  // an older one (none after releaseRenderer) goes unlocked
  } catch (const std::exception& error) {
    const std::string failure = std::string("no working GL context: ") + error.what();
    logging::event(spdlog::level::critical, "renderer_failed",
                   {{"gpu", options_.index}, {"error", error.what()}});
    setState(State::Failed, failure);
    failAll(unavailable(failure));
    return false;
  }
  // A test hook's simulated loss is for the first renderer only: the rebuilt one stays healthy.
  options_.renderer.debugContextLossAfter = -1;
  publishRendererState();
  lgh::DeviceInfo device = renderer_->device();
  {
    std::lock_guard lock(mutex_);
    device_ = device;
    resident_.clear();
    resident_.touch(sceneKey(selfTestRequest().scene));  // the self-test left it in the cache
  }
  logging::event(spdlog::level::info, "ready",
                 {{"gpu", options_.index},
                  {"device", device.toJson()},
                  {"startup_ms", millisecondsSince(start)}});
  setState(State::Ready);
  return true;
}

// After a GL failure the context may be broken: replace it rather than serve from it. The worker
// leaves scheduling first and gives its queued pieces back; the frames in flight on it fail, and
// the encoders finish reading pixels from its read-back memory before it goes.
void RenderWorker::recoverRenderer(const std::string& reason) {
  markRebuilding(reason);
  rebuildRenderer(reason);
}

void RenderWorker::markRebuilding(const std::string& reason) {
  logging::event(spdlog::level::err, "renderer_reset",
                 {{"gpu", options_.index}, {"reason", reason}});
  setState(State::Rebuilding, "rebuilding its GL context after: " + reason);
}

void RenderWorker::rebuildRenderer(const std::string& reason) {
  std::deque<JobPiece> queued;
  {
    std::lock_guard lock(mutex_);
    queued.swap(pieces_);
    for (const JobPiece& piece : queued) pendingSeconds_ -= pieceSeconds(piece);
  }
  if (!queued.empty() && hooks_.piecesReturned) {
    hooks_.piecesReturned(
        *this, {std::make_move_iterator(queued.begin()), std::make_move_iterator(queued.end())});
  }
  failFramesInFlight(
      internalError("the GL context failed while this frame was in flight: " + reason));
  encoders_.waitIdle();
  releaseRenderer();
  bringUpRenderer();
}

// The next piece; while none waits and frames are in flight, those are finished and handed to the
// encoders instead of sleeping.
std::optional<JobPiece> RenderWorker::takePiece() {
  for (;;) {
    std::shared_ptr<RenderJob> taken;
    {
      std::unique_lock lock(mutex_);
      if (submitted_.empty()) {
        workCondition_.wait(lock, [this] { return stopping_ || !pieces_.empty(); });
      }
      if (stopping_ || state_ == State::Failed) return std::nullopt;
      if (!pieces_.empty()) {
        current_ = std::move(pieces_.front());
        pieces_.pop_front();
        taken = current_->job;
      }
    }
    if (taken) {
      if (hooks_.pieceLeft) hooks_.pieceLeft(*taken);
      std::lock_guard lock(mutex_);
      return current_;
    }
    completeFrame(true);
    if (!renderer_) return std::nullopt;  // recovery failed
  }
}

void RenderWorker::finishPiece() {
  std::lock_guard lock(mutex_);
  current_.reset();
  idleCondition_.notify_all();
}

void RenderWorker::forget(double estimateSeconds) {
  std::lock_guard lock(mutex_);
  pendingSeconds_ -= estimateSeconds;
}

RenderWorker::LookAhead RenderWorker::nextTickets(const JobPiece& piece,
                                                  const std::vector<bool>& taken,
                                                  std::size_t position, std::size_t count) {
  LookAhead next;
  for (std::size_t i = 0; i < piece.tickets.size() && next.size() < count; ++i) {
    if (!taken[i] && i != position) next.push_back(piece.job->tickets[piece.tickets[i]]);
  }
  std::lock_guard lock(mutex_);
  for (const JobPiece& queued : pieces_) {
    for (const std::size_t index : queued.tickets) {
      if (next.size() >= count) return next;
      next.push_back(queued.job->tickets[index]);
    }
  }
  return next;
}

std::optional<std::size_t> RenderWorker::firstAtHand(const JobPiece& piece,
                                                     const std::vector<bool>& taken,
                                                     std::size_t head) const {
  // The window is the look-ahead the scenes were hinted for: a ticket past it has no parse on
  // its way and would be parsed when drawn.
  const std::size_t window = renderer_->prefetchDepth();
  std::size_t looked = 0;
  for (std::size_t i = head; i < piece.tickets.size() && looked < window; ++i) {
    if (taken[i]) continue;
    ++looked;
    const RenderTicket& ticket = *piece.job->tickets[piece.tickets[i]];
    // A ticket to skip (cancelled, or its waiter gave up) costs nothing: take it at once.
    if (piece.job->cancelled || ticket.settled()) return i;
    // A scene whose state is not looked up (an upload: Renderer::scenePending) is drawn in its
    // turn, never ahead.
    const std::optional<bool> pending = renderer_->scenePending(ticket.request());
    if (pending ? !*pending : i == head) return i;
  }
  return std::nullopt;
}

std::size_t RenderWorker::choosePosition(const JobPiece& piece, const std::vector<bool>& taken,
                                         std::size_t head) {
  const bool alone = std::find(taken.begin() + static_cast<std::ptrdiff_t>(head) + 1, taken.end(),
                               false) == taken.end();
  if (alone || !renderer_) return head;
  // The scenes must be on their way before they are looked at: the first of a batch are not
  // (after that, the last submit's window holds the head and hinted what follows it).
  const std::shared_ptr<RenderTicket>& headTicket = piece.job->tickets[piece.tickets[head]];
  if (std::find(hinted_.begin(), hinted_.end(), headTicket.get()) == hinted_.end()) {
    prefetch(headTicket, nextTickets(piece, taken, head, renderer_->prefetchDepth()));
  }
  const auto giveUp = Clock::now() + kDrawAheadWait;
  for (;;) {
    if (const std::optional<std::size_t> atHand = firstAtHand(piece, taken, head)) {
      if (*atHand != head) metrics_.recordDrawnAhead();
      return *atHand;
    }
    // Nothing at hand: hand finished frames to the encoders meanwhile, or wait a little.
    if (Clock::now() >= giveUp) return head;  // its submit waits for its scene
    if (!completeFrame(false)) std::this_thread::sleep_for(kDrawAheadPoll);
    if (!renderer_) return head;
  }
}

namespace {

bool distinctAssetFiles(const std::vector<const RenderTicket*>& tickets) {
  std::vector<const std::string*> paths;
  for (const RenderTicket* ticket : tickets) {
    const lgh::SceneSource& scene = ticket->request().scene;
    if (scene.kind != lgh::SceneSource::Kind::AssetPath) return false;
    paths.push_back(&scene.assetPath);
  }
  std::sort(paths.begin(), paths.end(), [](auto* a, auto* b) { return *a < *b; });
  return std::adjacent_find(paths.begin(), paths.end(),
                            [](auto* a, auto* b) { return *a == *b; }) == paths.end();
}

}  // namespace

// Each ticket is hinted once, when it enters the look-ahead window: the window moves on by about
// one ticket per render, and a hint costs a cache key (an upload's is a hash of its bytes). The
// ticket about to be drawn is in the window too, first: the first of a batch was never hinted, so
// its parse queued behind the whole window's (20-70 ms per batch on the H200 machine).
// A window hinted whole (a batch's start, nothing of it parsed yet) of distinct asset files is
// hinted smallest file first, which is the order the parser takes them in: the render thread
// draws ahead whatever is ready (choosePosition), so a large first asset no longer holds up the
// whole start while the small ones wait behind it (docs/DAEMON.md, "Batches"). A window that
// names a scene twice keeps its order: the scene cache takes a hint right after the same
// scene's for views of one asset drawn back to back.
void RenderWorker::prefetch(const std::shared_ptr<const RenderTicket>& current,
                            const LookAhead& next) {
  std::vector<const RenderTicket*> window;
  window.reserve(next.size() + 1);
  window.push_back(current.get());
  for (const std::shared_ptr<const RenderTicket>& ticket : next) window.push_back(ticket.get());
  const auto unhinted = [&](const RenderTicket* ticket) {
    return std::find(hinted_.begin(), hinted_.end(), ticket) == hinted_.end();
  };
  std::vector<const RenderTicket*> order;
  std::copy_if(window.begin(), window.end(), std::back_inserter(order), unhinted);
  if (order.size() == window.size() && distinctAssetFiles(order)) sortSmallestSourceFirst(order);
  for (const RenderTicket* ticket : order) renderer_->prefetch(ticket->request());
  hinted_ = std::move(window);
}

void RenderWorker::sortSmallestSourceFirst(std::vector<const RenderTicket*>& tickets) const {
  std::vector<std::pair<std::uint64_t, const RenderTicket*>> sized;
  sized.reserve(tickets.size());
  for (const RenderTicket* ticket : tickets) {
    sized.emplace_back(renderer_->sceneSourceBytes(ticket->request()), ticket);
  }
  std::stable_sort(sized.begin(), sized.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < sized.size(); ++i) tickets[i] = sized[i].second;
}

void RenderWorker::runPiece(const JobPiece& piece) {
  RenderJob& job = *piece.job;
  if (Clock::now() > job.startDeadline) {
    failJob(job, timedOut("the render waited in the queue past its deadline"));
    for (double estimate : piece.estimates) {
      forget(estimate);
      metrics_.recordRender("skipped", options_.index);
    }
    logging::event(spdlog::level::warn, "job_expired_in_queue",
                   {{"request_id", job.requestId}, {"gpu", options_.index}});
    return;
  }
  // Tickets are drawn in order, except that one whose scene is still being parsed ahead lets a
  // later one whose scene is at hand go first (choosePosition). Answers keep their order: a
  // batch's NDJSON lines and ZIP entries wait for each ticket in turn.
  std::vector<bool> taken(piece.tickets.size(), false);
  std::size_t head = 0;
  for (;;) {
    while (head < taken.size() && taken[head]) ++head;
    if (head == taken.size()) return;
    const std::size_t position = choosePosition(piece, taken, head);
    if (!renderer_) break;
    taken[position] = true;
    const std::shared_ptr<RenderTicket>& ticket = job.tickets[piece.tickets[position]];
    if (job.cancelled) ticket->fail(unavailable("the batch was cancelled"));
    if (ticket->settled()) {  // its waiter gave up (deadline) or the job was cancelled
      forget(piece.estimates[position]);
      metrics_.recordRender("skipped", options_.index);
      continue;
    }
    submitTicket(piece, position, nextTickets(piece, taken, position, renderer_->prefetchDepth()));
    if (!renderer_) break;
    while (completeFrame(false)) {
    }
  }
  // Recovery failed: this worker is out.
  failJob(job, unavailable("no working GL context on GPU " + std::to_string(options_.index)));
  for (std::size_t rest = 0; rest < taken.size(); ++rest) {
    if (!taken[rest]) forget(piece.estimates[rest]);
  }
}

// --- Frames in flight ---------------------------------------------------------------------------

void RenderWorker::submitTicket(const JobPiece& piece, std::size_t position,
                                const LookAhead& next) {
  const std::shared_ptr<RenderTicket>& ticket = piece.job->tickets[piece.tickets[position]];
  const double estimate = piece.estimates[position];
  const std::size_t bytes = frameBytes(ticket->request());
  waitForFrameCapacity(bytes);
  if (!renderer_) {
    forget(estimate);
    return;
  }
  ticket->markStarted(options_.index);
  {
    std::lock_guard lock(mutex_);
    resident_.touch(piece.scenes[position]);
  }
  const auto start = Clock::now();
  try {
    const WatchdogScope watched(watchdog_.get(), piece.job->startDeadline + options_.watchdog);
    if (options_.testRenderDelay.count() > 0) std::this_thread::sleep_for(options_.testRenderDelay);
    // The next scenes are parsed while this one uploads and renders.
    prefetch(ticket, next);
    renderer_->submit(ticket->request());
    submitted_.push_back({piece.job, ticket, start, start, bytes, estimate});
    std::lock_guard lock(mutex_);
    ++framesOutstanding_;
    bytesOutstanding_ += bytes;
    return;
  } catch (const lgh::Error& error) {
    // A GL failure may have broken the context, and a lost one (GPU reset) certainly has. The
    // worker leaves readiness before the failed request is answered, so that a client that then
    // sees /readyz answer 200 is not sent to a worker about to rebuild.
    const bool recover = error.code() == lgh::ErrorCode::Internal || !renderer_->healthy();
    if (recover) markRebuilding(error.what());
    ticket->fail(fromLghError(error));
    forget(estimate);
    metrics_.recordRender("error", options_.index);
    if (recover) rebuildRenderer(error.what());
  } catch (const std::exception& error) {
    markRebuilding(error.what());
    ticket->fail(internalError(error.what()));
    forget(estimate);
    metrics_.recordRender("error", options_.index);
    rebuildRenderer(error.what());
  }
}

void RenderWorker::waitForFrameCapacity(std::size_t bytes) {
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

bool RenderWorker::completeFrame(bool wait) {
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
  // The renderer's state for status(): after the last frame in flight, and at most every
  // kPublishInterval in between (its GL queries cost the render thread per thumbnail).
  if (submitted_.empty() || frame.finished - lastPublished_ >= kPublishInterval) {
    publishRendererState();
  }
  encoders_.submit([this, frame = std::move(frame), result = std::move(*result)]() mutable {
    encode(frame, result);
  });
  return true;
}

void RenderWorker::encode(FrameInFlight& frame, lgh::RenderResult& result) {
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
      result.encoded = result.encode(&encoders_);
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
  metrics_.recordRenderTimes(result.timings, queueMs / 1000.0, result.sceneCacheHit,
                             options_.index);
  if (const auto shadows = result.decisions.find("shadows"); shadows != result.decisions.end()) {
    metrics_.recordShadows(shadows->second);
  }
  const bool cacheHit = result.sceneCacheHit;
  if (failed) {
    metrics_.recordRender("error", options_.index);
  } else if (ticket.complete(std::move(result))) {
    metrics_.recordRender("ok", options_.index);
  } else {
    metrics_.recordRender("timeout", options_.index);
    logging::event(spdlog::level::warn, "render_discarded",
                   {{"request_id", frame.job->requestId},
                    {"gpu", options_.index},
                    {"render_ms", millisecondsSince(frame.started)}});
  }
  frameDone(frame, secondsSince(frame.started), cacheHit);
}

// Learns the worker's render times: the whole time (for Retry-After) and the time to its
// read-back by scene-cache result (for the scheduler).
void RenderWorker::frameDone(const FrameInFlight& frame, double seconds,
                             std::optional<bool> cacheHit) {
  {
    std::lock_guard lock(mutex_);
    --framesOutstanding_;
    bytesOutstanding_ -= frame.bytes;
    pendingSeconds_ -= frame.estimate;
    if (seconds > 0.0) averageRenderSeconds_ = 0.8 * averageRenderSeconds_ + 0.2 * seconds;
    if (cacheHit) {
      const double rendered = secondsBetween(frame.started, frame.finished);
      double& average = *cacheHit ? hitSeconds_ : missSeconds_;
      average = 0.8 * average + 0.2 * rendered;
    }
  }
  frameDoneCondition_.notify_all();
  idleCondition_.notify_all();
}

void RenderWorker::failFramesInFlight(const ApiError& error) {
  while (!submitted_.empty()) {
    FrameInFlight frame = std::move(submitted_.front());
    submitted_.pop_front();
    frame.ticket->fail(error);
    metrics_.recordRender("error", options_.index);
    frameDone(frame, 0.0, std::nullopt);
  }
}

// At the end: the frames in flight finish and are encoded (or dropped, when their tickets were
// settled by the shutdown), before the renderer and its read-back memory go.
void RenderWorker::settleFramesInFlight() {
  while (completeFrame(true)) {
  }
  if (!submitted_.empty()) failFramesInFlight(unavailable("the daemon is shutting down"));
  encoders_.waitIdle();
}

void RenderWorker::publishRendererState() {
  lastPublished_ = Clock::now();
  const lgh::Renderer::CacheStats stats = renderer_->sceneCacheStats();
  lgh::ShadowInfo shadows = renderer_->shadowInfo();
  lgh::ResourceStats resources = renderer_->resourceStats();
  std::lock_guard lock(mutex_);
  cacheStats_ = stats;
  resident_.limit(stats.entries);
  shadowInfo_ = std::move(shadows);
  resources_ = std::move(resources);
}

// Under mutex_, so that status() may read the renderer's read-back memory from HTTP threads.
// Destroyed outside the lock: tearing down a context can block in the driver (seen on the H200
// with two contexts on one GPU), and join() must still be able to take the lock and time out.
void RenderWorker::releaseRenderer() {
  std::unique_ptr<lgh::Renderer> renderer;
  {
    std::lock_guard lock(mutex_);
    renderer = std::move(renderer_);
  }
  const std::lock_guard setup(rendererSetupMutex());
  renderer.reset();
}

}  // namespace lghd
