#include "lgh/renderer.hpp"

#include <chrono>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "context/gl_context.hpp"
#include "frame_pipeline.hpp"
#include "gl/gpu_timer.hpp"
#include "scene/scene_cache.hpp"

namespace lgh {

using Clock = std::chrono::steady_clock;

static double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

struct Renderer::Impl {
  explicit Impl(const RendererOptions& opts)
      : options(opts), context(GlContext::create(opts)), cache(opts), pipeline() {
    device = context->info();
  }

  RendererOptions options;
  std::unique_ptr<GlContext> context;
  DeviceInfo device;
  SceneCache cache;
  FramePipeline pipeline;
  gl::GpuTimer timer;
};

Renderer::Renderer(const RendererOptions& options) : impl_(std::make_unique<Impl>(options)) {}
Renderer::~Renderer() = default;

const DeviceInfo& Renderer::device() const { return impl_->device; }
const RendererOptions& Renderer::options() const { return impl_->options; }

Renderer::CacheStats Renderer::sceneCacheStats() const { return impl_->cache.stats(); }

RenderResult Renderer::render(const RenderRequest& request) {
  const auto start = Clock::now();
  RenderResult result;
  result.device = impl_->device;

  SceneCache::Lookup lookup = impl_->cache.get(request.scene);
  result.sceneCacheHit = lookup.hit;
  result.paths["scene_cache"] = lookup.hit ? "hit" : "miss";
  result.timings.add("scene load", TimingRow::Clock::Cpu, lookup.hit ? 0.0 : lookup.loadMs);
  result.timings.add("upload", TimingRow::Clock::Cpu, lookup.hit ? 0.0 : lookup.uploadMs);
  result.warnings = lookup.entry->scene.warnings;

  try {
    impl_->pipeline.render(request, *lookup.entry, impl_->timer, result);
  } catch (...) {
    impl_->timer.discard();
    throw;
  }

  const auto encodeStart = Clock::now();
  result.encoded = result.encode(request.output);
  result.mimeType = mimeType(request.output.format);
  result.timings.add("encode", TimingRow::Clock::Cpu, millisecondsSince(encodeStart));
  result.timings.add("total", TimingRow::Clock::Cpu, millisecondsSince(start));
  return result;
}

nlohmann::json DeviceInfo::toJson() const {
  return {{"context_path", contextPath},        {"egl_device_index", eglDeviceIndex},
          {"egl_device_count", eglDeviceCount}, {"gl_vendor", glVendor},
          {"gl_renderer", glRenderer},          {"gl_version", glVersion},
          {"glsl_version", glslVersion},        {"software_renderer", softwareRenderer},
          {"image_backend", imageBackend}};
}

ImageMetadata RenderResult::metadata() const {
  return {{"Software", "lghd " LGH_VERSION},
          {"lgh:gl_renderer", device.glRenderer},
          {"lgh:context_path", device.contextPath},
          {"lgh:timings", timings.toJson().dump()}};
}

std::vector<std::uint8_t> RenderResult::encode(const OutputSettings& output) const {
  return encodeImage(image, output, metadata());
}

nlohmann::json RenderResult::summaryJson() const {
  return {{"timings", timings.toJson()},
          {"device", device.toJson()},
          {"paths", paths},
          {"warnings", warnings},
          {"scene_cache_hit", sceneCacheHit}};
}

}  // namespace lgh
