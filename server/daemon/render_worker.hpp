// One render worker: the render thread of one GPU (an EGL device), the lgh::Renderer it owns (a
// GL context belongs to the thread that made it) with its scene cache, its frames in flight and
// its watchdog. The front queue (render_queue.hpp) hands it pieces of jobs; it renders them in
// the order they came.
//
// The thread constructs the renderer, runs a 64x64 self-test of the demo scene before the worker
// reports ready, then renders. Frames are pipelined (docs/DAEMON.md, "Frames in flight"): the
// thread submits a frame and goes on to the next while the GPU works; a finished frame goes to the
// encoder pool shared by all workers, which encodes it and settles its ticket. At most
// --frames-in-flight frames (and --readback-mb of their pixels) of this worker are between
// submission and the end of their encoding.
//
// After a GL failure the worker takes itself out of scheduling (its queued pieces go back to the
// front queue for the other workers), replaces its renderer and comes back once the new one has
// passed its self-test; the other workers serve meanwhile. A render that hangs past its deadline
// plus --watchdog-seconds cannot be interrupted (a thread stuck in a driver call): the watchdog
// calls the hung hook, and the front ends the process.
#pragma once

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
#include "lgh/renderer.hpp"
#include "lgh/task_pool.hpp"
#include "metrics.hpp"
#include "render_job.hpp"
#include "render_scheduler.hpp"
#include "render_watchdog.hpp"

namespace lghd {

class RenderWorker {
 public:
  struct Options {
    int index = 0;  // its place in --gpus: the "gpu" that results, metrics and /v1/info name
    lgh::RendererOptions renderer;  // renderer.gpuIndex: its EGL device
    std::chrono::milliseconds testRenderDelay{0};
    std::chrono::milliseconds watchdog{0};  // 0: no watchdog
    OutputOptions output;
  };
  enum class State { Starting, Ready, Rebuilding, Failed };
  // Called on the worker's thread (stateChanged, piecesReturned, pieceLeft) or on its watchdog's
  // (hung); never under the worker's lock.
  struct Hooks {
    std::function<void(RenderWorker&)> stateChanged;
    // Pieces that were queued here when the worker went out of scheduling (a rebuild).
    std::function<void(RenderWorker&, std::vector<JobPiece>)> piecesReturned;
    // A queued piece left the queue (taken, failed or cancelled): the job's slot accounting.
    std::function<void(RenderJob&)> pieceLeft;
    std::function<void(RenderWorker&)> hung;
  };
  struct Status {
    int index = 0;
    int deviceIndex = 0;  // the EGL device asked for
    State state = State::Starting;
    std::string failure;
    std::optional<lgh::DeviceInfo> device;
    std::size_t queuedRenders = 0;
    bool rendering = false;
    double pendingSeconds = 0.0;
    lgh::Renderer::CacheStats cache;
    std::size_t framesInFlight = 0;
    std::size_t readbackBytes = 0;
    lgh::ShadowInfo shadows;
    lgh::ResourceStats resources;
    double averageRenderSeconds = 0.1;
  };

  RenderWorker(Options options, Metrics& metrics, lgh::TaskPool& encoders, Hooks hooks);
  ~RenderWorker();
  RenderWorker(const RenderWorker&) = delete;
  RenderWorker& operator=(const RenderWorker&) = delete;

  void start();
  int index() const { return options_.index; }
  const Options& options() const { return options_; }

  // Queues a piece (the front checked capacity and state).
  void enqueue(JobPiece piece);
  // How this worker would do a render of `scene`, for the scheduler.
  WorkerEstimate estimate(const std::string& scene) const;
  Status status() const;

  // Shutdown and failures. waitIdle: nothing queued, rendering or in flight by `deadline`.
  bool waitIdle(Clock::time_point deadline);
  // Answers every queued job and the one in progress with `error` (returns the jobs answered).
  std::size_t failAll(const ApiError& error);
  // Marks the worker failed after its watchdog fired (the thread is stuck).
  void markHung(const std::string& reason);
  void requestStop();
  // Waits up to `wait` for the thread to end; false: it is stuck (detached).
  bool join(Clock::duration wait);

 private:
  void run();
  bool bringUpRenderer();
  void recoverRenderer(const std::string& reason);
  // recoverRenderer in two steps: leave readiness (and log why), then replace the renderer.
  void markRebuilding(const std::string& reason);
  void rebuildRenderer(const std::string& reason);
  void setState(State state, const std::string& failure = "");
  std::optional<JobPiece> takePiece();
  void runPiece(const JobPiece& piece);
  void finishPiece();
  void forget(double estimateSeconds);
  // Up to `count` tickets to draw after the one at `position`: this piece's not yet taken, in
  // order, then the queued pieces'. Owned: a shutdown or a hang may drop a queued piece, and its
  // job with it, while the current frame renders.
  using LookAhead = std::vector<std::shared_ptr<const RenderTicket>>;
  LookAhead nextTickets(const JobPiece& piece, const std::vector<bool>& taken, std::size_t position,
                        std::size_t count);
  // The position to draw next: `head` (the first not taken) when its scene is at hand, else the
  // first of the next Renderer::prefetchDepth() not taken whose scene is (polling up to
  // kDrawAheadWait, finishing frames meanwhile), else `head`.
  std::size_t choosePosition(const JobPiece& piece, const std::vector<bool>& taken,
                             std::size_t head);
  std::optional<std::size_t> firstAtHand(const JobPiece& piece, const std::vector<bool>& taken,
                                         std::size_t head) const;
  static constexpr auto kDrawAheadWait = std::chrono::seconds(1);
  static constexpr auto kDrawAheadPoll = std::chrono::microseconds(200);
  void prefetch(const std::shared_ptr<const RenderTicket>& current, const LookAhead& next);
  // `tickets` (distinct asset files) in ascending size of their scenes' sources, ties in order.
  void sortSmallestSourceFirst(std::vector<const RenderTicket*>& tickets) const;

  // --- Frames in flight (render thread, except encode()) ---
  struct FrameInFlight {
    std::shared_ptr<RenderJob> job;
    std::shared_ptr<RenderTicket> ticket;
    Clock::time_point started;   // the render thread took the ticket
    Clock::time_point finished;  // its pixels were read back
    std::size_t bytes = 0;       // its read-back memory
    double estimate = 0.0;       // its share of pendingSeconds_
  };
  void submitTicket(const JobPiece& piece, std::size_t position, const LookAhead& next);
  bool completeFrame(bool wait);
  void waitForFrameCapacity(std::size_t bytes);
  void settleFramesInFlight();
  void failFramesInFlight(const ApiError& error);
  void encode(FrameInFlight& frame, lgh::RenderResult& result);  // an encoder thread
  void frameDone(const FrameInFlight& frame, double seconds, std::optional<bool> cacheHit);
  void publishRendererState();
  void releaseRenderer();
  static constexpr auto kPublishInterval = std::chrono::milliseconds(100);

  Options options_;
  Metrics& metrics_;
  lgh::TaskPool& encoders_;
  Hooks hooks_;
  std::unique_ptr<lgh::Renderer> renderer_;  // made, used and destroyed on the render thread
  std::vector<const RenderTicket*> hinted_;  // the last look-ahead window (render thread)
  Clock::time_point lastPublished_;          // of publishRendererState (render thread)

  mutable std::mutex mutex_;
  std::condition_variable workCondition_;
  std::condition_variable idleCondition_;
  std::deque<JobPiece> pieces_;
  std::optional<JobPiece> current_;
  State state_ = State::Starting;
  bool stopping_ = false;
  bool threadDone_ = false;
  bool hung_ = false;
  std::string failure_;
  std::optional<lgh::DeviceInfo> device_;
  lgh::Renderer::CacheStats cacheStats_;
  lgh::ShadowInfo shadowInfo_;
  lgh::ResourceStats resources_;
  ResidentScenes resident_;
  double pendingSeconds_ = 0.0;
  double hitSeconds_ = 0.05;
  double missSeconds_ = 0.1;
  double averageRenderSeconds_ = 0.1;
  std::unique_ptr<RenderWatchdog> watchdog_;

  std::deque<FrameInFlight> submitted_;
  std::condition_variable frameDoneCondition_;
  std::size_t framesOutstanding_ = 0;
  std::size_t bytesOutstanding_ = 0;

  std::thread thread_;
};

const char* workerStateName(RenderWorker::State state);

}  // namespace lghd
