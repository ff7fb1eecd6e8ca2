// The front of rendering: one bounded queue in front of the render workers, one per GPU
// (render_worker.hpp), and the encoder pool they share.
//
// HTTP threads parse and validate, then submit() a job (one render, or a thumbnail batch) and wait
// on its tickets. submit() gives each render to the worker that will finish it soonest
// (render_scheduler.hpp: its queued work, its render times, and whether the scene is resident in
// its scene cache); a batch's renders may so go to several workers, and its waiter merges them
// back by waiting on its tickets in order. A job holds one slot of --queue-depth until its last
// piece has been taken by a worker.
//
// Deadlines:
//  - a job still queued when its start deadline passes is answered 504 without rendering;
//  - a render still running at its waiter's deadline is answered 504 by the waiter; its frame
//    finishes on the GPU and the encoder drops it unencoded (its read-back memory goes back), so
//    the context stays healthy for the next job;
//  - a render (or the wait for its frame) still running --watchdog-seconds past its deadline, or
//    a start-up of a renderer running that long past 30 s, counts as hung: every waiting request
//    (on every worker) is answered 503, the daemon turns not ready and exits with kExitRenderHung
//    so that its supervisor starts a fresh process (a thread stuck in a driver call cannot be
//    interrupted, nor its context torn down).
// The daemon is ready while at least one worker is. A worker that fails its start-up or its
// rebuild stays out; lghd exits 1 once no worker is left.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
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
#include "render_job.hpp"
#include "render_ticket.hpp"
#include "render_worker.hpp"

namespace lghd {

// lghd's exit status after its watchdog found a render thread hung (1: no working GL context).
inline constexpr int kExitRenderHung = 3;

class RenderQueue {
 public:
  struct Options {
    lgh::RendererOptions renderer;
    std::size_t capacity = 16;
    std::chrono::milliseconds testRenderDelay{0};
    std::chrono::milliseconds watchdog{0};  // 0: no watchdog
    OutputOptions output;
    // The EGL device of each worker (--gpus; a device may repeat). Empty: one worker on
    // renderer.gpuIndex.
    std::vector<int> gpus;
    // FOR TESTS ONLY: worker `testContextLossGpu`'s first renderer reports a lost context after
    // `testContextLossAfter` frames (-1: none).
    int testContextLossGpu = -1;
    int testContextLossAfter = -1;
  };
  // Ends the process with `exitCode` (1: no working GL context, kExitRenderHung).
  using FatalHandler = std::function<void(int exitCode, const std::string& reason)>;

  RenderQueue(Options options, Metrics& metrics);
  ~RenderQueue();
  RenderQueue(const RenderQueue&) = delete;
  RenderQueue& operator=(const RenderQueue&) = delete;

  // Starts the workers; `onFatal` runs when no worker has a working context (on a render thread)
  // or when a render thread hangs (on its watchdog's thread).
  void start(FatalHandler onFatal);

  // Queues the renders as one job. Throws ApiError: 503 while starting or shutting down, 429 with
  // Retry-After when the queue is full.
  std::shared_ptr<RenderJob> submit(std::vector<lgh::RenderRequest> requests,
                                    const std::string& requestId, Clock::time_point startDeadline);

  bool ready() const;
  // Why the daemon is not ready ("" when it is).
  std::string notReadyReason() const;
  // The device of the first ready worker (else of the first that is up).
  std::optional<lgh::DeviceInfo> device() const;
  // What Vulkan offers on this machine, probed once after bring-up (empty until the probe is done).
  std::optional<lgh::VulkanInfo> vulkan() const;
  // Queue and scene-cache values for /metrics and /v1/info (totals, and each worker's).
  RuntimeGauges gauges() const;
  std::vector<RenderWorker::Status> workers() const;
  // The first worker's shadow side and resources, as of its last render.
  lgh::ShadowInfo shadows() const;
  lgh::ResourceStats resources() const;

  // Shutdown, in this order: refuse new jobs (503); let queued jobs finish for up to `grace`, then
  // answer what is left 503 (returns whether everything finished); end the render threads,
  // waiting up to `wait` for renders in progress (returns false if one did not end: a hung
  // driver).
  void stopAccepting();
  bool drain(Clock::duration grace);
  bool stop(Clock::duration wait);

 private:
  struct Assignment {
    std::size_t worker = 0;
    double estimate = 0.0;
  };
  // Splits the job's tickets over the schedulable workers (none: empty).
  std::vector<JobPiece> assign(const std::shared_ptr<RenderJob>& job,
                               const std::vector<std::size_t>& tickets) const;
  void dispatch(std::vector<JobPiece> pieces);
  void workerStateChanged(RenderWorker& worker);
  void piecesReturned(RenderWorker& from, std::vector<JobPiece> pieces);
  void pieceLeft(RenderJob& job);
  void declareHung(RenderWorker& worker);
  int retryAfterSeconds() const;
  void releaseVulkanProbe();
  void endVulkanProbe();

  Options options_;
  Metrics& metrics_;
  FatalHandler onFatal_;
  std::unique_ptr<lgh::TaskPool> encoders_;
  std::vector<std::unique_ptr<RenderWorker>> workers_;

  mutable std::mutex mutex_;
  bool accepting_ = true;
  bool hung_ = false;
  std::string hungReason_;
  std::size_t waitingJobs_ = 0;  // jobs with a piece still queued (the --queue-depth slots)

  struct VulkanSlot {
    std::mutex mutex;
    std::condition_variable changed;  // signals each of the three flags below
    bool mayStart = false;            // a renderer is up (or failed): the probe may start
    bool cancelled = false;           // shutdown: do not start, or give up on the answer
    bool done = false;                // the probe thread has nothing left to do
    std::optional<lgh::VulkanInfo> info;
    std::atomic<pid_t> child = 0;  // the probe process while it runs
  };
  std::shared_ptr<VulkanSlot> vulkan_ = std::make_shared<VulkanSlot>();
  std::thread vulkanProbe_;
};

}  // namespace lghd
