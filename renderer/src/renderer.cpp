#include "lgh/renderer.hpp"

#include <cstdlib>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "context/gl_context.hpp"
#include "core/stopwatch.hpp"
#include "frame_pipeline.hpp"
#include "frame_report.hpp"
#include "gl/gl_api.hpp"
#include "gl/gl_objects.hpp"
#include "gl/gpu_timer.hpp"
#include "lgh/error.hpp"
#include "scene/gltf/gltf_loader.hpp"
#include "scene/scene_cache.hpp"
#include "shadows/shadow_device.hpp"

namespace lgh {

struct Renderer::Impl {
  explicit Impl(const RendererOptions& opts)
      : options(opts), context(GlContext::create(opts)), cache(opts), pipeline(&shadowDevice) {
    device = context->info();
    if (const char* after = std::getenv("LGH_DEBUG_CONTEXT_LOSS_AFTER"); after != nullptr) {
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

  // Destroyed in reverse: the GL objects of the frame and the cache go first, then the Vulkan
  // device that the cache's acceleration structures live on, then the GL context.
  RendererOptions options;
  std::unique_ptr<GlContext> context;
  DeviceInfo device;
  ShadowDevice shadowDevice;
  SceneCache cache;
  FramePipeline pipeline;
  gl::GpuTimer timer;
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

RenderResult Renderer::render(const RenderRequest& request) {
  const Stopwatch total;
  RenderResult result = renderFrame(request);
  const Stopwatch encode;
  result.encoded = result.encode(request.output);
  result.mimeType = mimeType(request.output.format);
  result.timings.add("encode", TimingRow::Clock::Cpu, encode.elapsedMs());
  result.timings.add("total", TimingRow::Clock::Cpu, total.elapsedMs());
  return result;
}

bool Renderer::healthy() const { return impl_->healthy; }

RenderResult Renderer::renderFrame(const RenderRequest& request) {
  if (!impl_->healthy) {
    throw Error(ErrorCode::Unavailable, "this renderer's GL context was lost: make a new one");
  }
  // Another Renderer on this thread may have made its own context current since.
  if (gl::currentApi() != &impl_->context->api()) impl_->context->makeCurrent();
  FrameReport report;
  SceneLoadOptions loadOptions;
  loadOptions.animation = request.sceneOptions.animation;
  loadOptions.materialVariant = request.sceneOptions.materialVariant;
  loadOptions.ignoreUnsupportedExtensions = request.settings.ignoreUnsupportedExtensions;
  loadOptions.textureCompression = request.settings.textureCompression;
  SceneCache::Lookup lookup = impl_->cache.get(request.scene, loadOptions);
  report.decide("scene_cache", lookup.hit ? "hit" : "miss");
  report.timings.add("scene load", TimingRow::Clock::Cpu, lookup.hit ? 0.0 : lookup.loadMs);
  report.timings.add("upload", TimingRow::Clock::Cpu, lookup.hit ? 0.0 : lookup.uploadMs);
  report.warnings = lookup.entry->scene.warnings;

  try {
    impl_->pipeline.render(request, *lookup.entry, impl_->timer, report);
  } catch (...) {
    impl_->timer.discard();
    impl_->checkContext();  // a lost context explains the failure better than the failure does
    throw;
  }
  impl_->checkContext();

  RenderResult result;
  result.device = impl_->device;
  result.sceneCacheHit = lookup.hit;
  result.image = std::move(report.image);
  result.timings = std::move(report.timings);
  result.decisions = std::move(report.decisions);
  result.warnings = std::move(report.warnings);
  return result;
}

}  // namespace lgh
