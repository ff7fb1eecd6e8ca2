#include "shadows/shadow_device.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "context/container_hints.hpp"
#include "core/stopwatch.hpp"
#include "gl/gl_api.hpp"
#include "lgh/error.hpp"

namespace lgh {

ShadowDevice::ShadowDevice() = default;
ShadowDevice::~ShadowDevice() = default;

bool glDeviceUuid(vk::DeviceUuid& uuid, std::string& whyNot) {
  const gl::Api& api = gl::api("glGetUnsignedBytei_vEXT");
  if ((api.EXT_memory_object == 0 && api.EXT_semaphore == 0) ||
      api.GetUnsignedBytei_vEXT == nullptr) {
    whyNot =
        "the GL context has neither GL_EXT_memory_object nor GL_EXT_semaphore, so its "
        "device cannot be matched with a Vulkan device";
    return false;
  }
  while (glGetError() != GL_NO_ERROR) {
  }
  glGetUnsignedBytei_vEXT(GL_DEVICE_UUID_EXT, 0, uuid.data());
  if (glGetError() != GL_NO_ERROR) {
    whyNot = "the GL context reports no device UUID (glGetUnsignedBytei_vEXT failed)";
    return false;
  }
  return true;
}

vk::ShadowTracer* ShadowDevice::tracer() {
  if (tracer_ || tried_) return tracer_.get();
  tried_ = true;
  vk::DeviceUuid uuid{};
  if (!glDeviceUuid(uuid, reason_)) {
    spdlog::warn("shadows: unavailable: {}", reason_);
    return nullptr;
  }
  try {
    tracer_ = vk::ShadowTracer::create(uuid);
    ++epoch_;
    reason_.clear();
    const vk::TracerInfo& info = tracer_->info();
    spdlog::info(
        "shadows: Vulkan device {} ({}), ray query {}, ray-tracing pipeline {}, "
        "external memory {}, external semaphores {}, ready in {:.0f} ms",
        info.deviceName, info.driverName, info.rayQuery, info.rayTracingPipeline,
        info.externalMemoryFd, info.externalSemaphoreFd, info.createMs);
  } catch (const Error& error) {
    reason_ = error.message() + vulkanDriverHints();
    spdlog::warn("shadows: unavailable: {}", reason_);
  }
  return tracer_.get();
}

std::optional<double> readBuildGpuMs(const std::function<double()>& reader) {
  if (!reader) return std::nullopt;
  try {
    return reader();
  } catch (const std::exception& error) {  // lgh::Error, or vk::SystemError from the wait
    spdlog::warn("shadows: an acceleration-structure build's GPU time could not be read: {}",
                 error.what());
    return std::nullopt;
  }
}

ShadowDevice::SubmissionMark ShadowDevice::mark() const {
  if (!tracer_) return {};
  return {
      .epoch = epoch_, .trace = tracer_->lastTrace(), .lightPaths = tracer_->lastLightPathTrace()};
}

std::optional<double> ShadowDevice::traceGpuMs(const SubmissionMark& mark) {
  if (!tracer_ || mark.epoch != epoch_) return std::nullopt;
  try {
    return tracer_->collectTimingsThrough(mark.trace).traceGpuMs;
  } catch (const Error& error) {
    spdlog::warn("shadows: the shadow rays' GPU time could not be read: {}", error.message());
    return std::nullopt;
  }
}

std::optional<vk::LightPathTimings> ShadowDevice::lightPathTimings(const SubmissionMark& mark) {
  if (!tracer_ || mark.epoch != epoch_) return std::nullopt;
  try {
    return tracer_->collectLightPathTimingsThrough(mark.lightPaths);
  } catch (const Error& error) {
    spdlog::warn("gi: the light paths' GPU times could not be read: {}", error.message());
    return std::nullopt;
  }
}

ShadowInfo ShadowDevice::info(const std::string& transport) const {
  ShadowInfo info;
  if (!tracer_) {
    info.status = tried_ ? "unavailable" : "pending";
    info.reason = reason_;
    return info;
  }
  const vk::TracerInfo& tracer = tracer_->info();
  info.status = "ready";
  info.deviceName = tracer.deviceName;
  info.driverName = tracer.driverName;
  info.apiVersion = tracer.apiVersion;
  info.rayQuery = tracer.rayQuery;
  info.rayTracingPipeline = tracer.rayTracingPipeline;
  info.externalMemory = tracer.externalMemoryFd;
  info.externalSemaphores = tracer.externalSemaphoreFd;
  info.transport = transport;
  return info;
}

vk::TracePath chooseTracePath(const vk::ShadowTracer& tracer, ShadowTracing requested) {
  const bool rayQuery = tracer.supports(vk::TracePath::RayQuery);
  if (requested == ShadowTracing::Auto) {
    return rayQuery ? vk::TracePath::RayQuery : vk::TracePath::Pipeline;
  }
  const vk::TracePath path =
      requested == ShadowTracing::RayQuery ? vk::TracePath::RayQuery : vk::TracePath::Pipeline;
  if (!tracer.supports(path)) {
    throw Error(ErrorCode::Invalid,
                fmt::format("the Vulkan device '{}' has no {} ({}); ask for \"auto\"",
                            tracer.info().deviceName, enumName(path),
                            path == vk::TracePath::RayQuery ? "VK_KHR_ray_query"
                                                            : "VK_KHR_ray_tracing_pipeline"),
                "/settings/shadow_path");
  }
  return path;
}

const vk::TraceScene& ShadowDevice::traceScene(const CachedScene& scene,
                                               std::function<double()>* buildGpuMs,
                                               double* buildWallMs) {
  TraceSceneSlot& slot = scene.trace;
  if (!slot.scene || slot.epoch != epoch_) {
    const Stopwatch wall;
    slot.scene.reset();
    slot.scene = tracer()->buildScene(scene.scene);
    slot.epoch = epoch_;
    if (buildGpuMs != nullptr) *buildGpuMs = slot.scene->buildGpuMsReader();
    if (buildWallMs != nullptr) *buildWallMs = wall.elapsedMs();
  }
  return *slot.scene;
}

SceneCache::TraceBuilder ShadowDevice::prefetchBuilder() const {
  if (!tracer_) return {};
  return [build = tracer_->sceneBuilder(), epoch = epoch_](const Scene& scene) {
    return TraceSceneSlot{build(scene), epoch};
  };
}

void ShadowDevice::reset(const std::string& why) {
  spdlog::error("shadows: the Vulkan tracer is reset after a failure: {}", why);
  tracer_.reset();
  tried_ = false;
  reason_ = why;
}

}  // namespace lgh
