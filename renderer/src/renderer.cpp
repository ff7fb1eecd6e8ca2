#include "lgh/renderer.hpp"

#include <spdlog/spdlog.h>

#include "context/gl_context.hpp"
#include "core/stopwatch.hpp"
#include "frame_pipeline.hpp"
#include "frame_report.hpp"
#include "gl/gl_api.hpp"
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
  }

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

RenderResult Renderer::renderFrame(const RenderRequest& request) {
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
    throw;
  }

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
