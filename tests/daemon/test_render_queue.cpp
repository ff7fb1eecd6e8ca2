// render_queue.hpp: the bounded queue and its render thread, on a real Renderer (Mesa llvmpipe),
// driven directly as the HTTP handlers drive it. Arrival order, 429 when full, the two deadlines
// (expired in the queue; past the waiter's deadline while rendering), cancelled batches, renderer
// errors, shutdown (refuse, drain within the grace, cancel the rest, stop) and a context that
// cannot be had. --test-render-delay-ms (Options::testRenderDelay) keeps the render thread busy
// for a known time so that queue states are reached on purpose, not by luck.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "api_error.hpp"
#include "clock.hpp"
#include "lgh/renderer.hpp"
#include "metrics.hpp"
#include "render_queue.hpp"

namespace lghd {
namespace {

using namespace std::chrono_literals;

// Long enough for llvmpipe on a loaded 2-core machine; a passing test never waits this long.
constexpr auto kPatience = 60s;

bool waitUntil(const std::function<bool()>& done) {
  const Clock::time_point end = Clock::now() + kPatience;
  while (!done()) {
    if (Clock::now() > end) return false;
    std::this_thread::sleep_for(2ms);
  }
  return true;
}

Clock::time_point farDeadline() { return Clock::now() + kPatience; }

// A small render of the demo scene.
lgh::RenderRequest smallRender(int width = 32, int height = 24) {
  lgh::RenderRequest request;
  request.output.width = width;
  request.output.height = height;
  return request;
}

std::vector<lgh::RenderRequest> renders(std::size_t count) {
  return std::vector<lgh::RenderRequest>(count, smallRender());
}

RenderQueue::Options queueOptions(std::size_t capacity, std::chrono::milliseconds delay) {
  RenderQueue::Options options;
  // The suite's context path, as for lghd (scripts/run-tests runs it on each).
  if (const char* backend = std::getenv("LGH_BACKEND"); backend != nullptr && *backend != 0) {
    options.renderer.backend = lgh::parseContextBackend(backend);
  }
  options.capacity = capacity;
  options.testRenderDelay = delay;
  return options;
}

// The ApiError `wait` throws (fails the test if it returns a result instead).
ApiError errorOf(RenderTicket& ticket, Clock::time_point deadline) {
  try {
    ticket.wait(deadline);
  } catch (const ApiError& error) {
    return error;
  }
  ADD_FAILURE() << "the ticket was answered with an image";
  return internalError("no error");
}

ApiError submitError(RenderQueue& queue, std::vector<lgh::RenderRequest> requests) {
  try {
    queue.submit(std::move(requests), "refused", farDeadline());
  } catch (const ApiError& error) {
    return error;
  }
  ADD_FAILURE() << "the job was queued";
  return internalError("no error");
}

std::optional<double> rendersTotal(const Metrics& metrics, const std::string& outcome) {
  const std::string text = metrics.exposition({});
  const std::string series = "lghd_renders_total{outcome=\"" + outcome + "\"} ";
  const std::size_t at = text.find(series);
  if (at == std::string::npos) return std::nullopt;
  return std::stod(text.substr(at + series.size()));
}

class RenderQueueTest : public testing::Test {
 protected:
  void TearDown() override {
    if (queue_) {
      EXPECT_TRUE(queue_->stop(30s)) << "the render thread did not end";
    }
  }

  // A started queue whose renderer is up (self-test passed).
  RenderQueue& readyQueue(RenderQueue::Options options) {
    RenderQueue& queue = startedQueue(std::move(options));
    EXPECT_TRUE(waitUntil([&] { return queue.ready() || !fatal().empty(); }));
    EXPECT_TRUE(queue.ready()) << queue.notReadyReason();
    return queue;
  }

  RenderQueue& startedQueue(RenderQueue::Options options) {
    queue_ = std::make_unique<RenderQueue>(std::move(options), metrics_);
    queue_->start([this](int exitCode, const std::string& reason) {
      std::lock_guard lock(fatalMutex_);
      fatal_ = reason;
      fatalExitCode_ = exitCode;
    });
    return *queue_;
  }

  std::string fatal() {
    std::lock_guard lock(fatalMutex_);
    return fatal_;
  }

  int fatalExitCode() {
    std::lock_guard lock(fatalMutex_);
    return fatalExitCode_;
  }

  // Nothing queued, rendering or in flight: the encoders have settled every ticket and counted
  // its outcome (a waiter wakes before its encoder has counted it).
  bool idle() const {
    const RuntimeGauges gauges = queue_->gauges();
    return gauges.queueDepth == 0 && !gauges.rendering && gauges.framesInFlight == 0;
  }

  Metrics metrics_;  // outlives the queue
  std::unique_ptr<RenderQueue> queue_;

 private:
  std::mutex fatalMutex_;
  std::string fatal_;
  int fatalExitCode_ = 0;
};

TEST_F(RenderQueueTest, RefusesJobsWhileStarting) {
  RenderQueue queue(queueOptions(4, 0ms), metrics_);  // not started: no render thread
  EXPECT_FALSE(queue.ready());
  EXPECT_TRUE(queue.notReadyReason().starts_with("starting")) << queue.notReadyReason();
  EXPECT_FALSE(queue.device());
  const ApiError error = submitError(queue, renders(1));
  EXPECT_EQ(error.status(), 503);
  EXPECT_EQ(error.code(), "unavailable");
  EXPECT_EQ(error.retryAfterSeconds(), 1);
  const RuntimeGauges gauges = queue.gauges();
  EXPECT_FALSE(gauges.ready);
  EXPECT_EQ(gauges.queueDepth, 0U);
  EXPECT_EQ(gauges.queueCapacity, 4U);
}

TEST_F(RenderQueueTest, RendersOnceReady) {
  RenderQueue::Options options = queueOptions(4, 0ms);
  options.renderer.sceneCacheBytes = 32ULL << 20;
  RenderQueue& queue = readyQueue(options);
  EXPECT_EQ(queue.notReadyReason(), "");
  ASSERT_TRUE(queue.device());
  EXPECT_FALSE(queue.device()->glRenderer.empty());

  const auto job = queue.submit({smallRender(48, 32)}, "req-1", farDeadline());
  EXPECT_EQ(job->requestId, "req-1");
  ASSERT_EQ(job->tickets.size(), 1U);
  const lgh::RenderResult result = job->tickets[0]->wait(farDeadline());
  EXPECT_EQ(result.output.width, 48);
  EXPECT_EQ(result.output.height, 32);
  ASSERT_GE(result.encoded.size(), 8U);
  EXPECT_EQ(result.encoded[1], 'P');
  EXPECT_EQ(result.encoded[2], 'N');
  EXPECT_EQ(result.encoded[3], 'G');
  ASSERT_TRUE(job->tickets[0]->started());
  EXPECT_GE(*job->tickets[0]->started(), job->enqueued);

  ASSERT_TRUE(waitUntil([&] { return idle(); })) << "metrics are recorded once the job is done";
  const RuntimeGauges gauges = queue.gauges();
  EXPECT_TRUE(gauges.ready);
  EXPECT_EQ(gauges.sceneCacheBudgetBytes, 32ULL << 20);
  EXPECT_GE(gauges.sceneCacheHits + gauges.sceneCacheMisses, 1U);
  EXPECT_EQ(rendersTotal(metrics_, "ok"), 1.0) << "the self-test render is not counted";
}

// One render thread, first come first served: jobs in submission order, a job's renders in order.
TEST_F(RenderQueueTest, RendersJobsInArrivalOrder) {
  RenderQueue& queue = readyQueue(queueOptions(8, 0ms));
  const std::vector<std::shared_ptr<RenderJob>> jobs{
      queue.submit(renders(1), "first", farDeadline()),
      queue.submit(renders(1), "second", farDeadline()),
      queue.submit(renders(1), "third", farDeadline()),
      queue.submit(renders(3), "batch", farDeadline()),
      queue.submit(renders(1), "last", farDeadline()),
  };

  std::vector<Clock::time_point> starts;
  for (const auto& job : jobs) {
    for (const auto& ticket : job->tickets) {
      EXPECT_FALSE(ticket->wait(farDeadline()).encoded.empty());
      ASSERT_TRUE(ticket->started());
      starts.push_back(*ticket->started());
    }
  }
  ASSERT_TRUE(waitUntil([&] { return idle(); }));
  ASSERT_EQ(starts.size(), 7U);
  for (std::size_t i = 1; i < starts.size(); ++i) {
    EXPECT_LT(starts[i - 1], starts[i]) << "render " << i << " started before render " << i - 1;
  }
  EXPECT_EQ(rendersTotal(metrics_, "ok"), 7.0);
}

// Capacity counts waiting jobs (a batch is one); the one rendering does not count.
TEST_F(RenderQueueTest, FullQueueIs429WithRetryAfter) {
  RenderQueue& queue = readyQueue(queueOptions(2, 300ms));
  const auto rendering = queue.submit(renders(1), "a", farDeadline());
  ASSERT_TRUE(waitUntil([&] { return rendering->tickets[0]->started().has_value(); }));
  const auto second = queue.submit(renders(1), "b", farDeadline());
  const auto third = queue.submit(renders(2), "c", farDeadline());
  EXPECT_EQ(queue.gauges().queueDepth, 2U);

  const ApiError full = submitError(queue, renders(1));
  EXPECT_EQ(full.status(), 429);
  EXPECT_EQ(full.code(), "queue_full");
  EXPECT_EQ(full.message(), "the render queue is full (2 waiting)");
  EXPECT_GE(full.retryAfterSeconds(), 1);

  for (const auto& job : {rendering, second, third}) {
    for (const auto& ticket : job->tickets) {
      EXPECT_FALSE(ticket->wait(farDeadline()).encoded.empty());
    }
  }
  ASSERT_TRUE(waitUntil([&] { return idle(); }));
  const auto later = queue.submit(renders(1), "d", farDeadline());
  EXPECT_FALSE(later->tickets[0]->wait(farDeadline()).encoded.empty()) << "room again";
}

// A job whose start deadline passes while it waits is answered 504 and never rendered.
TEST_F(RenderQueueTest, JobExpiredInTheQueueIsSkipped) {
  RenderQueue& queue = readyQueue(queueOptions(4, 200ms));
  const auto first = queue.submit(renders(1), "first", farDeadline());
  const auto expiring = queue.submit(renders(2), "expiring", Clock::now() + 20ms);
  EXPECT_FALSE(first->tickets[0]->wait(farDeadline()).encoded.empty());
  for (const auto& ticket : expiring->tickets) {
    const ApiError error = errorOf(*ticket, farDeadline());  // the queue answers, not the waiter
    EXPECT_EQ(error.status(), 504);
    EXPECT_EQ(error.code(), "timeout");
    EXPECT_EQ(error.message(), "the render waited in the queue past its deadline");
    EXPECT_FALSE(ticket->started());
  }
  ASSERT_TRUE(waitUntil([&] { return idle(); }));
  EXPECT_EQ(rendersTotal(metrics_, "skipped"), 2.0);
  EXPECT_EQ(rendersTotal(metrics_, "ok"), 1.0);
}

// A render still running at its waiter's deadline: the waiter answers 504 at once; the render
// thread finishes, discards the result (outcome "timeout") and renders the next job.
TEST_F(RenderQueueTest, RenderPastTheWaitersDeadlineIs504AndDiscarded) {
  RenderQueue& queue = readyQueue(queueOptions(4, 300ms));
  const auto job = queue.submit(renders(1), "slow", farDeadline());
  RenderTicket& ticket = *job->tickets[0];
  ASSERT_TRUE(waitUntil([&] { return ticket.started().has_value(); }));
  const Clock::time_point waited = Clock::now();
  const ApiError error = errorOf(ticket, Clock::now() + 20ms);
  EXPECT_LT(millisecondsSince(waited), 250.0) << "the waiter must not wait for the render";
  EXPECT_EQ(error.status(), 504);
  EXPECT_EQ(error.message(), "the render ran past its deadline");

  ASSERT_TRUE(waitUntil([&] { return rendersTotal(metrics_, "timeout").has_value(); }));
  EXPECT_EQ(rendersTotal(metrics_, "timeout"), 1.0);
  const auto next = queue.submit(renders(1), "next", farDeadline());
  EXPECT_FALSE(next->tickets[0]->wait(farDeadline()).encoded.empty());
}

// A render still running --watchdog-seconds past its deadline counts as hung (a GL call that
// never returns; the test render delay stands in for it): every waiting request is answered 503,
// the queue turns not ready and the process is asked to exit with kExitRenderHung.
TEST_F(RenderQueueTest, RenderHungPastTheWatchdogIsFatal) {
  RenderQueue::Options options = queueOptions(4, 1500ms);
  options.watchdog = 200ms;
  RenderQueue& queue = readyQueue(options);
  const auto hung = queue.submit(renders(1), "hung", Clock::now() + 100ms);
  const auto waiting = queue.submit(renders(1), "waiting", farDeadline());
  const Clock::time_point submitted = Clock::now();
  const ApiError error = errorOf(*waiting->tickets[0], farDeadline());
  EXPECT_LT(millisecondsSince(submitted), 1200.0) << "answered by the watchdog, not the render";
  EXPECT_EQ(error.status(), 503);
  EXPECT_EQ(error.retryAfterSeconds(), 5);
  EXPECT_NE(error.message().find("--watchdog-seconds"), std::string::npos) << error.message();
  EXPECT_EQ(errorOf(*hung->tickets[0], farDeadline()).status(), 503);
  ASSERT_TRUE(waitUntil([&] { return !fatal().empty(); }));
  EXPECT_EQ(fatalExitCode(), kExitRenderHung);
  EXPECT_FALSE(queue.ready());
  EXPECT_NE(queue.notReadyReason().find("stuck"), std::string::npos) << queue.notReadyReason();
  EXPECT_EQ(submitError(queue, renders(1)).status(), 503);
  EXPECT_EQ(rendersTotal(metrics_, "hung"), 1.0);
}

// A render that ends within the watchdog's time does not fire it.
TEST_F(RenderQueueTest, WatchdogStaysQuietForRendersThatEnd) {
  RenderQueue::Options options = queueOptions(4, 50ms);
  options.watchdog = 2000ms;
  RenderQueue& queue = readyQueue(options);
  const auto job = queue.submit(renders(3), "fine", farDeadline());
  for (const auto& ticket : job->tickets) EXPECT_FALSE(ticket->wait(farDeadline()).encoded.empty());
  EXPECT_TRUE(fatal().empty()) << fatal();
  EXPECT_TRUE(queue.ready());
}

// The client of a batch went away: renders not started yet are skipped.
TEST_F(RenderQueueTest, CancelledJobSkipsItsRenders) {
  RenderQueue& queue = readyQueue(queueOptions(4, 200ms));
  const auto first = queue.submit(renders(1), "first", farDeadline());
  const auto cancelled = queue.submit(renders(2), "gone", farDeadline());
  cancelled->cancelled = true;
  EXPECT_FALSE(first->tickets[0]->wait(farDeadline()).encoded.empty());
  for (const auto& ticket : cancelled->tickets) {
    const ApiError error = errorOf(*ticket, farDeadline());
    EXPECT_EQ(error.status(), 503);
    EXPECT_EQ(error.message(), "the batch was cancelled");
  }
  ASSERT_TRUE(waitUntil([&] { return idle(); }));
  EXPECT_EQ(rendersTotal(metrics_, "skipped"), 2.0);
}

// A renderer error answers its ticket with the error's status; the queue goes on.
TEST_F(RenderQueueTest, RendererErrorAnswersTheTicket) {
  RenderQueue& queue = readyQueue(queueOptions(4, 0ms));
  lgh::RenderRequest missing = smallRender();
  missing.scene.kind = lgh::SceneSource::Kind::AssetPath;
  missing.scene.assetPath = "no/such/asset.glb";
  const auto job = queue.submit({missing, smallRender()}, "mixed", farDeadline());
  const ApiError error = errorOf(*job->tickets[0], farDeadline());
  EXPECT_EQ(error.status(), 404);
  EXPECT_EQ(error.code(), "not_found");
  EXPECT_NE(error.message().find("no/such/asset.glb"), std::string::npos) << error.message();
  EXPECT_FALSE(job->tickets[1]->wait(farDeadline()).encoded.empty()) << "the next render runs";
  ASSERT_TRUE(waitUntil([&] { return idle(); }));
  EXPECT_EQ(rendersTotal(metrics_, "error"), 1.0);
  EXPECT_EQ(rendersTotal(metrics_, "ok"), 1.0);
  EXPECT_TRUE(queue.ready());
}

TEST_F(RenderQueueTest, StopAcceptingRefusesNewJobs) {
  RenderQueue& queue = readyQueue(queueOptions(4, 0ms));
  queue.stopAccepting();
  EXPECT_FALSE(queue.ready());
  EXPECT_EQ(queue.notReadyReason(), "shutting down");
  EXPECT_FALSE(queue.gauges().ready);
  const ApiError error = submitError(queue, renders(1));
  EXPECT_EQ(error.status(), 503);
  EXPECT_EQ(error.message(), "the daemon is shutting down");
  EXPECT_EQ(error.retryAfterSeconds(), 0);
  EXPECT_TRUE(queue.drain(1s)) << "nothing queued: drained at once";
  EXPECT_TRUE(queue.stop(30s));
}

// Within the grace period, queued renders finish normally.
TEST_F(RenderQueueTest, DrainLetsQueuedRendersFinish) {
  RenderQueue& queue = readyQueue(queueOptions(4, 100ms));
  const std::vector<std::shared_ptr<RenderJob>> jobs{
      queue.submit(renders(1), "queued-1", farDeadline()),
      queue.submit(renders(1), "queued-2", farDeadline()),
      queue.submit(renders(1), "queued-3", farDeadline()),
  };
  queue.stopAccepting();
  EXPECT_TRUE(queue.drain(kPatience));
  EXPECT_TRUE(idle());
  for (const auto& job : jobs) EXPECT_FALSE(job->tickets[0]->wait(farDeadline()).encoded.empty());
  EXPECT_TRUE(queue.stop(30s));
}

// Past the grace period, what is left (queued, and the render in progress) is answered 503; the
// render thread still ends cleanly.
TEST_F(RenderQueueTest, DrainPastTheGraceCancelsTheRest) {
  RenderQueue& queue = readyQueue(queueOptions(4, 300ms));
  const auto rendering = queue.submit(renders(1), "rendering", farDeadline());
  ASSERT_TRUE(waitUntil([&] { return rendering->tickets[0]->started().has_value(); }));
  const auto queued = queue.submit(renders(2), "queued", farDeadline());
  queue.stopAccepting();
  const Clock::time_point drainStart = Clock::now();
  EXPECT_FALSE(queue.drain(30ms));
  EXPECT_LT(millisecondsSince(drainStart), 250.0) << "the grace period bounds the drain";
  for (const auto& job : {rendering, queued}) {
    EXPECT_TRUE(job->cancelled);
    for (const auto& ticket : job->tickets) {
      const ApiError error = errorOf(*ticket, farDeadline());
      EXPECT_EQ(error.status(), 503);
      EXPECT_EQ(error.message(), "the daemon is shutting down: render cancelled");
    }
  }
  EXPECT_FALSE(queued->tickets[0]->started()) << "cancelled jobs are never rendered";
  EXPECT_EQ(queue.gauges().queueDepth, 0U);
  EXPECT_TRUE(queue.stop(30s));
}

// The render in progress looks ahead at the next queued ticket (to parse its scene early). When the
// drain cancels that ticket and its waiter lets go of the job, the look-ahead must not read freed
// memory (AddressSanitizer, scripts/run-tests --asan, reports it if it does).
TEST_F(RenderQueueTest, ALookAheadOutlivesTheJobThatADrainCancelled) {
  RenderQueue& queue = readyQueue(queueOptions(4, 300ms));
  // While the first job renders, two more queue up: the second renders looking ahead at the third.
  const auto first = queue.submit(renders(1), "first", farDeadline());
  ASSERT_TRUE(waitUntil([&] { return first->tickets[0]->started().has_value(); }));
  const auto rendering = queue.submit(renders(1), "rendering", farDeadline());
  std::shared_ptr<RenderJob> queued = queue.submit({smallRender(40, 30)}, "queued", farDeadline());
  ASSERT_TRUE(waitUntil([&] { return rendering->tickets[0]->started().has_value(); }));
  queue.stopAccepting();
  EXPECT_FALSE(queue.drain(30ms));
  EXPECT_EQ(errorOf(*queued->tickets[0], farDeadline()).status(), 503);
  queued.reset();  // the waiter answered its client and is gone
  EXPECT_EQ(errorOf(*rendering->tickets[0], farDeadline()).status(), 503);
  EXPECT_TRUE(queue.stop(30s));
}

// No working context (an EGL device index no machine here has): the fatal handler runs, and the
// queue answers 503 with the reason.
TEST_F(RenderQueueTest, NoContextIsFatalAnd503) {
  RenderQueue::Options options = queueOptions(4, 0ms);
  options.renderer.backend = lgh::ContextBackend::EglDevice;
  options.renderer.gpuIndex = 999;
  RenderQueue& queue = startedQueue(options);
  ASSERT_TRUE(waitUntil([&] { return !fatal().empty(); }));
  EXPECT_NE(fatal().find("GPU index 999"), std::string::npos) << fatal();
  EXPECT_EQ(fatalExitCode(), 1);
  EXPECT_FALSE(queue.ready());
  EXPECT_EQ(queue.notReadyReason(), "no working GL context: " + fatal());
  EXPECT_FALSE(queue.device());
  const ApiError error = submitError(queue, renders(1));
  EXPECT_EQ(error.status(), 503);
  EXPECT_EQ(error.message(), "no working GL context: " + fatal());
}

// /v1/info's Vulkan report: probed once the renderer is up, in a child process (this executable
// run with --probe-vulkan; see daemon_test_main.cpp). Whether Vulkan is there depends on the
// machine; the report must come either way, with devices or with the reason.
TEST_F(RenderQueueTest, VulkanIsProbedOnceReady) {
  RenderQueue& queue = readyQueue(queueOptions(4, 0ms));
  ASSERT_TRUE(waitUntil([&] { return queue.vulkan().has_value(); }));
  const lgh::VulkanInfo vulkan = *queue.vulkan();
  if (vulkan.available) {
    EXPECT_FALSE(vulkan.devices.empty());
  } else {
    EXPECT_FALSE(vulkan.error.empty());
  }
}

}  // namespace
}  // namespace lghd
