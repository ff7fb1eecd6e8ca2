// The bounded render queue, the one render thread that owns the GL context, and the encoders.
//
// HTTP threads parse and validate, then submit() a job (one render, or a thumbnail batch) and wait
// on its tickets. The render thread constructs lgh::Renderer itself (a GL context belongs to the
// thread that made it), runs a 64x64 self-test of the demo scene before the daemon reports ready,
// then renders jobs in arrival order.
//
// Frames are pipelined (docs/DAEMON.md, "Frames in flight"): the render thread submits a frame
// (its GPU work and asynchronous read-back) and goes on to the next request while the GPU works;
// a finished frame goes to the encoder pool (--encode-threads), which encodes it and settles its
// ticket. The next request's scene is parsed on a thread of its own meanwhile. At most
// --frames-in-flight frames (and --readback-mb of their pixels) are between submission and the
// end of their encoding: the render thread waits beyond that, so memory stays bounded.
//
// Deadlines:
//  - a job still queued when its start deadline passes is answered 504 without rendering;
//  - a render still running at its waiter's deadline is answered 504 by the waiter; its frame
//    finishes on the GPU and the encoder drops it unencoded (its read-back memory goes back), so
//    the context stays healthy for the next job;
//  - a render (or the wait for its frame) still running --watchdog-seconds past its deadline, or
//    a start-up of the renderer running that long past 30 s, counts as hung: every waiting
//    request is answered 503, the daemon turns not ready and exits with kExitRenderHung so that
//    its supervisor starts a fresh process.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "config.hpp"
#include "lgh/task_pool.hpp"
#include "lgh/vulkan_info.hpp"
#include "metrics.hpp"
#include "render_ticket.hpp"
#include "render_watchdog.hpp"

namespace lghd {

// lghd's exit status after its watchdog found the render thread hung (1: no working GL context).
inline constexpr int kExitRenderHung = 3;

struct RenderJob {
  std::string requestId;
  std::vector<std::shared_ptr<RenderTicket>> tickets;
  Clock::time_point enqueued;
  Clock::time_point startDeadline;
  std::atomic<bool> cancelled{false};  // the client went away: skip what has not started
};

class RenderQueue {
 public:
  struct Options {
    lgh::RendererOptions renderer;
    std::size_t capacity = 16;
    std::chrono::milliseconds testRenderDelay{0};
    std::chrono::milliseconds watchdog{0};  // 0: no watchdog
    OutputOptions output;
  };
  // Ends the process with `exitCode` (1: no working GL context, kExitRenderHung).
  using FatalHandler = std::function<void(int exitCode, const std::string& reason)>;

  RenderQueue(Options options, Metrics& metrics);
  ~RenderQueue();
  RenderQueue(const RenderQueue&) = delete;
  RenderQueue& operator=(const RenderQueue&) = delete;

  // Starts the render thread; `onFatal` runs when no working context can be had (on the render
  // thread) or when the render thread hangs (on the watchdog's).
  void start(FatalHandler onFatal);

  // Queues the renders as one job. Throws ApiError: 503 while starting or shutting down, 429 with
  // Retry-After when the queue is full.
  std::shared_ptr<RenderJob> submit(std::vector<lgh::RenderRequest> requests,
                                    const std::string& requestId, Clock::time_point startDeadline);

  bool ready() const;
  // Why the daemon is not ready ("" when it is).
  std::string notReadyReason() const;
  // The device the context runs on, once it is up.
  std::optional<lgh::DeviceInfo> device() const;
  // What Vulkan offers on this machine, probed once after bring-up (empty until the probe is done).
  std::optional<lgh::VulkanInfo> vulkan() const;
  // Queue and scene-cache values for /metrics and /v1/info.
  RuntimeGauges gauges() const;
  // The renderer's shadow side, as of its last render.
  lgh::ShadowInfo shadows() const;
  // Live GL objects and GPU memory, as of the last render.
  lgh::ResourceStats resources() const;

  // Shutdown, in this order: refuse new jobs (503); let queued jobs finish for up to `grace`, then
  // answer what is left 503 (returns whether everything finished); end the render thread, waiting
  // up to `wait` for a render in progress (returns false if it did not end: a hung driver).
  void stopAccepting();
  bool drain(Clock::duration grace);
  bool stop(Clock::duration wait);

 private:
  enum class State { Starting, Ready, Failed };

  void run();
  void releaseVulkanProbe();
  void endVulkanProbe();
  bool bringUpRenderer();
  void recoverRenderer(const std::string& reason);
  void declareHung();
  std::shared_ptr<RenderJob> takeJob();
  void runJob(const std::shared_ptr<RenderJob>& job);
  void finishJob();

  // --- Frames in flight (render thread, except encode()) ---
  // A submitted frame until its encoder settles its ticket.
  struct FrameInFlight {
    std::shared_ptr<RenderJob> job;
    std::shared_ptr<RenderTicket> ticket;
    Clock::time_point started;   // the render thread took the ticket
    Clock::time_point finished;  // its pixels were read back
    std::size_t bytes = 0;       // its read-back memory
  };
  void submitTicket(const std::shared_ptr<RenderJob>& job,
                    const std::shared_ptr<RenderTicket>& ticket, const lgh::RenderRequest* next);
  // Hands the oldest submitted frame to the encoders once it is read back (`wait`: blocks until
  // then). Returns whether one was handed over.
  bool completeFrame(bool wait);
  void waitForFrameCapacity(std::size_t bytes);
  void settleFramesInFlight();
  void failFramesInFlight(const ApiError& error);
  void encode(FrameInFlight& frame, lgh::RenderResult& result);  // an encoder thread
  void frameDone(const FrameInFlight& frame, double seconds);    // any thread
  const lgh::RenderRequest* nextRequest(const RenderJob& job, std::size_t index);
  void publishRendererState();
  void releaseRenderer();
  int retryAfterSeconds() const;  // under mutex_
  void failAll(RenderJob& job, const ApiError& error);

  Options options_;
  Metrics& metrics_;
  FatalHandler onFatal_;
  // Made, used and destroyed on the render thread; assigned under mutex_, where gauges() reads
  // its read-back memory (Renderer::readbackStats is safe on any thread).
  std::unique_ptr<lgh::Renderer> renderer_;

  mutable std::mutex mutex_;
  std::condition_variable workCondition_;
  std::condition_variable idleCondition_;
  std::deque<std::shared_ptr<RenderJob>> jobs_;
  std::shared_ptr<RenderJob> current_;
  State state_ = State::Starting;
  bool accepting_ = true;
  bool stopping_ = false;
  bool threadDone_ = false;
  std::string failure_;
  std::optional<lgh::DeviceInfo> device_;
  struct VulkanSlot {
    std::mutex mutex;
    std::condition_variable changed;  // signals each of the three flags below
    bool mayStart = false;            // the renderer is up (or failed): the probe may start
    bool cancelled = false;           // shutdown: do not start, or give up on the answer
    bool done = false;                // the probe thread has nothing left to do
    std::optional<lgh::VulkanInfo> info;
    std::atomic<pid_t> child = 0;  // the probe process while it runs
  };
  std::shared_ptr<VulkanSlot> vulkan_ = std::make_shared<VulkanSlot>();
  std::thread vulkanProbe_;
  lgh::Renderer::CacheStats cacheStats_;
  lgh::ShadowInfo shadowInfo_;
  lgh::ResourceStats resources_;
  double averageRenderSeconds_ = 0.1;
  std::unique_ptr<RenderWatchdog> watchdog_;

  // Frames in flight: the encoders, the submitted frames in the renderer's order (render thread),
  // and what is outstanding from submission to the end of encoding (under mutex_).
  std::unique_ptr<lgh::TaskPool> encoders_;
  std::deque<FrameInFlight> submitted_;
  std::condition_variable frameDoneCondition_;
  std::size_t framesOutstanding_ = 0;
  std::size_t bytesOutstanding_ = 0;

  std::thread thread_;
};

}  // namespace lghd
