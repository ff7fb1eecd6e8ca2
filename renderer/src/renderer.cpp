#include "lgh/renderer.hpp"

#include <algorithm>
#include <cstdlib>
#include <deque>
#include <limits>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "context/gl_context.hpp"
#include "core/stopwatch.hpp"
#include "frame_pipeline.hpp"
#include "frame_report.hpp"
#include "gl/gl_api.hpp"
#include "gl/gl_objects.hpp"
#include "gl/gpu_timer.hpp"
#include "gl/readback_buffers.hpp"
#include "lgh/error.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/scene_cache.hpp"
#include "shadows/shadow_device.hpp"

namespace lgh {
namespace {

SceneLoadOptions loadOptionsOf(const RenderRequest& request) {
  SceneLoadOptions options;
  options.animation = request.sceneOptions.animation;
  options.materialVariant = request.sceneOptions.materialVariant;
  options.ignoreUnsupportedExtensions = request.settings.ignoreUnsupportedExtensions;
  options.textureCompression = request.settings.textureCompression;
  return options;
}

// A submitted frame until finish() hands it over: its GPU timer, its fence and its pixels, which
// the GPU is still writing until the fence signals.
struct PendingFrame {
  std::uint64_t id = 0;
  OutputSettings output;
  FramePixels pixels;
  gl::GpuTimer timer;
  gl::Fence fence;
  FrameReport report;
  OutputPixels outputPixels = OutputPixels::Display8;
  // Set while the frame's draw stopped after its shadow rays' hand-over: the passes still to
  // issue, after the next frame's first half (FramePipeline::drawUntilShadows). No fence yet.
  std::optional<RemainingPasses> remaining;
  bool sceneCacheHit = false;
  Stopwatch::Clock::time_point submitted;                // when submit() returned
  std::optional<Stopwatch::Clock::time_point> readBack;  // when its fence was seen signalled
};

}  // namespace

struct Renderer::Impl {
  explicit Impl(const RendererOptions& opts)
      : options(opts),
        context(GlContext::create(opts)),
        cache(opts, context.get()),
        pipeline(&shadowDevice) {
    device = context->info();
    if (opts.debugContextLossAfter >= 0) {
      simulatedLossAfter = opts.debugContextLossAfter;
      spdlog::warn("debugContextLossAfter: a context loss is reported after {} frames",
                   simulatedLossAfter);
    } else if (const char* after = std::getenv("LGH_DEBUG_CONTEXT_LOSS_AFTER"); after != nullptr) {
      simulatedLossAfter = std::atoi(after);
      spdlog::warn("LGH_DEBUG_CONTEXT_LOSS_AFTER: a context loss is reported after {} frames",
                   simulatedLossAfter);
    }
  }

  // A reset (or the test hook's simulated one) ends this renderer: its GL objects are gone.
  void checkContext() {
    GLenum status = glGetGraphicsResetStatus();
    if (simulatedLossAfter >= 0 && ++frames > simulatedLossAfter) status = GL_UNKNOWN_CONTEXT_RESET;
    if (status == GL_NO_ERROR) return;
    healthy = false;
    const char* cause = status == GL_GUILTY_CONTEXT_RESET     ? "caused by this context"
                        : status == GL_INNOCENT_CONTEXT_RESET ? "caused elsewhere"
                                                              : "cause unknown";
    spdlog::error("renderer: the GL context was lost ({})", cause);
    throw Error(ErrorCode::Unavailable,
                fmt::format("the GL context was lost in a GPU reset ({}); the renderer is made "
                            "again",
                            cause));
  }

  bool healthy = true;
  int simulatedLossAfter = -1;
  int frames = 0;

  // Destroyed in reverse: the frames in flight and the read-back buffers, then the GL objects of
  // the frame and the cache, then the Vulkan device that the cache's acceleration structures live
  // on, then the GL context.
  RendererOptions options;
  std::unique_ptr<GlContext> context;
  DeviceInfo device;
  ShadowDevice shadowDevice;
  SceneCache cache;
  FramePipeline pipeline;
  gl::ReadbackPool readback;
  std::vector<gl::GpuTimer> spareTimers;  // their queries are reused
  std::deque<PendingFrame> pending;
  std::uint64_t nextFrameId = 1;

  void throwIfLost() const {
    if (!healthy) {
      throw Error(ErrorCode::Unavailable, "this renderer's GL context was lost: make a new one");
    }
  }
  void makeCurrent() {
    // Another Renderer on this thread may have made its own context current since.
    if (gl::currentApi() != &context->api()) context->makeCurrent();
  }
  void waitFor(PendingFrame& frame) {
    if (frame.readBack) return;
    if (frame.remaining) finishDeferred(frame);
    while (!frame.fence.wait(std::numeric_limits<std::uint64_t>::max())) {
    }
    frame.readBack = Stopwatch::Clock::now();
  }
  bool poll(PendingFrame& frame) {
    if (frame.readBack) return true;
    if (frame.remaining) {
      // Issued here once its rays are traced, since nothing else would issue it while no frame
      // follows; not before: the caller's next submit() draws while Vulkan traces (a CPU
      // tracer's wait here held the render thread for the whole trace).
      if (!pipeline.finishReady(*frame.remaining)) return false;
      finishDeferred(frame);
    }
    if (!frame.fence.wait(0)) return false;
    frame.readBack = Stopwatch::Clock::now();
    return true;
  }
  PendingFrame* deferredFrame() {
    const auto found = std::find_if(pending.begin(), pending.end(),
                                    [](const PendingFrame& frame) { return frame.remaining; });
    return found == pending.end() ? nullptr : &*found;
  }
  // Issues the copy of the frame's output into read-back memory and its fence.
  void pack(PendingFrame& frame, int set) {
    gl::ReadbackPool::Lease lease = readback.acquire(FramePipeline::packBufferBytes(frame.pixels));
    pipeline.pack(frame.outputPixels, frame.pixels.layout, lease.buffer, frame.timer, set);
    frame.pixels.bytes = std::move(lease.bytes);
    frame.fence = gl::Fence::insert();
  }
  void finishDeferred(PendingFrame& frame);
  std::uint64_t submit(const RenderRequest& request);
  void drawAndPack(const RenderRequest& request, const CachedScene& scene, PendingFrame& frame);
  RenderResult take(const std::deque<PendingFrame>::iterator& frame);
};

Renderer::Renderer(const RendererOptions& options) : impl_(std::make_unique<Impl>(options)) {}
Renderer::~Renderer() {
  // The frame's and the cache's GL objects are deleted in this context, whichever is current.
  try {
    if (impl_ && gl::currentApi() != &impl_->context->api()) impl_->context->makeCurrent();
  } catch (const Error& error) {
    spdlog::error("renderer: its GL context could not be made current to free it: {}",
                  error.what());
  }
}

const DeviceInfo& Renderer::device() const { return impl_->device; }
const RendererOptions& Renderer::options() const { return impl_->options; }

Renderer::CacheStats Renderer::sceneCacheStats() const { return impl_->cache.stats(); }

ResourceStats Renderer::resourceStats() const {
  ResourceStats stats;
  const auto live = gl::liveObjects();
  for (std::size_t i = 0; i < live.size(); ++i) {
    stats.glObjects[std::string(enumName(static_cast<gl::ObjectKind>(i)))] = live[i];
  }
  stats.sceneCacheBytes = impl_->cache.stats().bytes;
  if (gl::currentApi() != &impl_->context->api()) impl_->context->makeCurrent();
  if (impl_->context->api().NVX_gpu_memory_info != 0) {
    GLint total = 0;
    GLint available = 0;
    glGetIntegerv(GL_GPU_MEMORY_INFO_TOTAL_AVAILABLE_MEMORY_NVX, &total);
    glGetIntegerv(GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, &available);
    stats.gpuMemoryTotalKiB = total;
    stats.gpuMemoryAvailableKiB = available;
  }
  return stats;
}

ShadowInfo Renderer::shadowInfo() const {
  return impl_->shadowDevice.info(impl_->pipeline.shadowTransport());
}

Renderer::ReadbackStats Renderer::readbackStats() const {
  const gl::ReadbackStats stats = impl_->readback.stats();
  return {stats.heldBuffers, stats.heldBytes, stats.pooledBuffers, stats.pooledBytes};
}

std::size_t Renderer::pendingFrames() const { return impl_->pending.size(); }

void Renderer::prefetch(const RenderRequest& request) {
  // A frame that traces rays needs the scene's acceleration structures: built on the prefetch
  // thread too, off the render thread.
  const bool traces =
      request.settings.shadows.mode != ShadowMode::Off || request.settings.gi.enabled;
  impl_->cache.prefetch(
      request.scene, loadOptionsOf(request),
      traces ? impl_->shadowDevice.prefetchBuilder() : SceneCache::TraceBuilder{});
}

std::optional<bool> Renderer::scenePending(const RenderRequest& request) const {
  return impl_->cache.inProgress(request.scene, loadOptionsOf(request));
}

std::uint64_t Renderer::sceneSourceBytes(const RenderRequest& request) const {
  return impl_->cache.sourceBytes(request.scene);
}

std::size_t Renderer::prefetchDepth() const { return impl_->cache.prefetchDepth(); }

std::uint64_t Renderer::Impl::submit(const RenderRequest& request) {
  throwIfLost();
  makeCurrent();
  const Stopwatch submitTimer;
  const auto limit = static_cast<std::size_t>(std::max(options.framesInFlight, 1));
  const auto unfinished = [&] {
    return std::count_if(pending.begin(), pending.end(),
                         [](const PendingFrame& frame) { return !frame.readBack; });
  };
  const Stopwatch slotWait;
  while (static_cast<std::size_t>(unfinished()) >= limit) {
    const auto oldest = std::find_if(pending.begin(), pending.end(),
                                     [](const PendingFrame& frame) { return !frame.readBack; });
    waitFor(*oldest);
  }

  PendingFrame frame;
  frame.output = request.output;
  if (!spareTimers.empty()) {
    frame.timer = std::move(spareTimers.back());
    spareTimers.pop_back();
  }
  const double slotWaitMs = slotWait.elapsedMs();
  const Stopwatch sceneTimer;
  SceneCache::Lookup lookup = cache.get(request.scene, loadOptionsOf(request));
  const double sceneMs = sceneTimer.elapsedMs();
  frame.sceneCacheHit = lookup.hit;
  FrameReport& report = frame.report;
  report.decide("scene_cache", lookup.hit ? "hit" : "miss");
  if (lookup.prefetched) report.decide("scene_parse", "prefetched");
  report.timings.add("scene load", TimingRow::Clock::Cpu, lookup.hit ? 0.0 : lookup.loadMs);
  report.timings.add("upload", TimingRow::Clock::Cpu, lookup.hit ? 0.0 : lookup.uploadMs);
  if (cache.hasGlWorker()) {
    // Not part of "submit": the GL worker's upload of a scene parsed ahead.
    report.timings.add("upload ahead", TimingRow::Clock::Cpu,
                       lookup.hit ? 0.0 : lookup.uploadAheadMs);
  }
  if (cache.hasGlWorker() || cache.stagingBytes() > 0) {
    const char* upload = "render_thread";
    if (lookup.hit) upload = "cached";
    if (lookup.uploadedAhead) upload = "gl_worker";
    if (lookup.staged) upload = "staged";
    report.decide("scene_upload", upload);
  }
  // Parts of "submit" spent waiting: for a frame in flight to finish (--frames-in-flight), and
  // for the scene's parse (a prefetch not done yet, or a parse of its own) besides its upload.
  report.timings.add("slot wait", TimingRow::Clock::Cpu, slotWaitMs);
  report.timings.add(
      "scene wait", TimingRow::Clock::Cpu,
      std::max(0.0, sceneMs - (lookup.hit ? 0.0 : lookup.uploadMs + lookup.releaseMs)));
  if (!lookup.hit) report.timings.add("scene release", TimingRow::Clock::Cpu, lookup.releaseMs);
  report.warnings = lookup.entry->scene.warnings;

  frame.outputPixels = outputPixelsFor(request.output);
  frame.pixels.width = request.output.width;
  frame.pixels.height = request.output.height;
  frame.pixels.layout = pixelLayoutFor(request.output);
  const auto abandon = [&] {
    frame.timer.discard();
    spareTimers.push_back(std::move(frame.timer));
  };
  try {
    drawAndPack(request, *lookup.entry, frame);
  } catch (...) {
    abandon();
    checkContext();  // a lost context explains the failure better than the failure does
    throw;
  }
  try {
    checkContext();
  } catch (...) {
    abandon();
    throw;
  }
  report.timings.add("submit", TimingRow::Clock::Cpu, submitTimer.elapsedMs());
  frame.submitted = Stopwatch::Clock::now();
  frame.id = nextFrameId++;
  pending.push_back(std::move(frame));
  return pending.back().id;
}

// With overlapped frames (RendererOptions::overlapShadowedFrames), GL's queue runs this frame's
// G-buffer and ray set-up while Vulkan traces the frame before it, whose remaining passes follow:
// they wait for their rays without holding up this frame's. Each of the two frame sets is used by
// every other split frame.
void Renderer::Impl::drawAndPack(const RenderRequest& request, const CachedScene& scene,
                                 PendingFrame& frame) {
  PendingFrame* deferred = options.overlapShadowedFrames ? deferredFrame() : nullptr;
  if (!options.overlapShadowedFrames) {
    pipeline.draw(request, scene, frame.timer, frame.report, frame.outputPixels);
    pack(frame, 0);
    return;
  }
  const int set = deferred != nullptr ? 1 - deferred->remaining->set : 0;
  frame.remaining =
      pipeline.drawUntilShadows(request, scene, frame.timer, frame.report, frame.outputPixels, set);
  if (deferred != nullptr) finishDeferred(*deferred);
  if (!frame.remaining) pack(frame, set);
}

void Renderer::Impl::finishDeferred(PendingFrame& frame) {
  const RemainingPasses remaining = *frame.remaining;
  frame.remaining.reset();
  try {
    pipeline.finishDraw(remaining, frame.timer);
    pack(frame, remaining.set);
  } catch (const std::exception& error) {
    // Its rays' semaphore may be left signalled and never waited on: this renderer's shadow
    // lanes cannot be trusted any more, and its frames in flight go with it.
    healthy = false;
    spdlog::error("renderer: a frame's last passes failed after its rays were handed over: {}",
                  error.what());
    throw Error(
        ErrorCode::Internal,
        std::string("a frame's last passes failed (the renderer is made again): ") + error.what());
  }
}

RenderResult Renderer::Impl::take(const std::deque<PendingFrame>::iterator& frame) {
  waitFor(*frame);
  FrameReport& report = frame->report;
  report.timings.add("frame wait", TimingRow::Clock::Cpu,
                     Stopwatch::millisecondsBetween(frame->submitted, *frame->readBack));
  // The GPU rows after the CPU rows of the submit, as a frame's table always listed them.
  TimingTable gpuRows;
  frame->timer.collect(gpuRows);
  RenderResult result;
  result.frameId = frame->id;
  result.output = frame->output;
  result.pixels = std::move(frame->pixels);
  result.device = device;
  result.sceneCacheHit = frame->sceneCacheHit;
  result.timings = std::move(report.timings);
  result.timings.rows.insert(result.timings.rows.end(), gpuRows.rows.begin(), gpuRows.rows.end());
  result.timings.appendMerged(report.writeLateRows());
  result.decisions = std::move(report.decisions);
  result.warnings = std::move(report.warnings);
  spareTimers.push_back(std::move(frame->timer));
  pending.erase(frame);
  return result;
}

std::uint64_t Renderer::submit(const RenderRequest& request) { return impl_->submit(request); }

std::optional<RenderResult> Renderer::finish(bool wait) {
  if (impl_->pending.empty()) return std::nullopt;
  impl_->throwIfLost();
  impl_->makeCurrent();
  if (!wait && !impl_->poll(impl_->pending.front())) return std::nullopt;
  return impl_->take(impl_->pending.begin());
}

RenderResult Renderer::renderFrame(const RenderRequest& request) {
  const std::uint64_t id = impl_->submit(request);
  const auto frame = std::find_if(impl_->pending.begin(), impl_->pending.end(),
                                  [&](const PendingFrame& pending) { return pending.id == id; });
  return impl_->take(frame);
}

RenderResult Renderer::render(const RenderRequest& request) {
  const Stopwatch total;
  RenderResult result = renderFrame(request);
  const Stopwatch encode;
  result.encoded = result.encode();
  result.mimeType = mimeType(request.output.format);
  result.timings.add("encode", TimingRow::Clock::Cpu, encode.elapsedMs());
  result.timings.add("total", TimingRow::Clock::Cpu, total.elapsedMs());
  return result;
}

bool Renderer::healthy() const { return impl_->healthy; }

}  // namespace lgh
