// ShadowTracer on Vulkan: the device that is the GL device, the tracing paths it offers, the ray
// buffers and semaphores shared with GL, and the submissions in flight. Every public function
// turns Vulkan failures into lgh::Error at its boundary.
#include <array>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/stopwatch.hpp"
#include "lgh/error.hpp"
#include "vk/acceleration_scene.hpp"
#include "vk/exported_semaphores.hpp"
#include "vk/hit_tracer.hpp"
#include "vk/light_path_tracer.hpp"
#include "vk/physical_device.hpp"
#include "vk/ray_buffer_set.hpp"
#include "vk/shadow_tracer.hpp"
#include "vk/spirv_shaders.hpp"
#include "vk/trace_batch.hpp"
#include "vk/trace_layout.hpp"
#include "vk/trace_recorder.hpp"
#include "vk/trace_submissions.hpp"
#include "vk/vulkan_device.hpp"
#include "vk/vulkan_errors.hpp"

namespace lgh::vk {
namespace {

// Submissions in flight at once: one per frame the renderer keeps unfinished
// (RendererOptions::framesInFlight, 8) and as many again, so that submitting a frame's trace never
// waits on the host for an earlier frame's (with 4, the fifth frame in flight waited for the
// first one's trace to finish on the GPU).
constexpr std::uint32_t kSlots = 16;

::vk::ShaderStageFlags traceStages(const DeviceCapabilities& capabilities) {
  ::vk::ShaderStageFlags stages;
  if (capabilities.rayQuery) stages |= ::vk::ShaderStageFlagBits::eCompute;
  if (capabilities.rayTracingPipeline) stages |= ::vk::ShaderStageFlagBits::eRaygenKHR;
  return stages;
}

std::string pathNames(const TracerInfo& info) {
  if (info.rayQuery && info.rayTracingPipeline) return "ray query + ray-tracing pipeline";
  return info.rayQuery ? "ray query" : "ray-tracing pipeline";
}

// The tiles a path launches: the batch's own where the path zeroes every word first.
std::optional<RayTiles> launchedTiles(const RayBatchShape& shape, TracePath path) {
  return path == TracePath::RayQuery ? shape.tiles : std::nullopt;
}

TracePushConstants pushConstants(const RayBatchShape& shape, const TraceParams& params,
                                 TracePath path) {
  const RayTiles tiles = launchedTiles(shape, path).value_or(RayTiles{});
  return {.width = shape.width,
          .height = shape.height,
          .raysPerPixel = shape.raysPerPixel,
          .words = shape.words(),
          .tMin = params.tMin,
          .tMaxInfinite = params.tMaxInfinite,
          .endEpsilon = params.endEpsilon,
          .firstTileX = tiles.first[0],
          .firstTileY = tiles.first[1]};
}

// The invocations launched: every pixel, or the tiles' pixels.
TraceLaunch launchOf(const RayBatchShape& shape, TracePath path) {
  const std::optional<RayTiles> tiles = launchedTiles(shape, path);
  if (!tiles) return {.width = shape.width, .height = shape.height};
  return {.width = tiles->count[0] * kRayTileSize, .height = tiles->count[1] * kRayTileSize};
}

// glsl/vk/shadow_ray_query.comp: one invocation per pixel in 8 x 8 groups.
RayQueryProgram shadowQueryProgram() {
  return {.shader = spirv::shadow_ray_query_comp(), .groupWidth = 8, .groupHeight = 8};
}

// glsl/vk/shadow_ray.rgen launched once per pixel, with shadow_ray.rmiss as its only miss shader
// and an empty hit group.
PipelineProgram shadowPipelineProgram() {
  return {.rayGeneration = spirv::shadow_ray_rgen(),
          .miss = spirv::shadow_ray_rmiss(),
          .closestHit = {}};
}

class VulkanShadowTracer final : public ShadowTracer {
 public:
  explicit VulkanShadowTracer(std::shared_ptr<const VulkanDevice> device)
      : device_(std::move(device)),
        info_(device_->info()),
        layout_(*device_, traceStages(device_->capabilities()), kSlots),
        submissions_(*device_, kSlots),
        hits_(*device_, traceStages(device_->capabilities())),
        lightPaths_(*device_, hits_, traceStages(device_->capabilities())) {
    if (info_.rayQuery) {
      rayQuery_ = createRayQueryRecorder(*device_, layout_, shadowQueryProgram());
    }
    if (info_.rayTracingPipeline) {
      pipeline_ = createRayTracingPipelineRecorder(*device_, layout_, shadowPipelineProgram());
    }
  }
  ~VulkanShadowTracer() override { device_->waitIdleNoThrow(); }
  VulkanShadowTracer(const VulkanShadowTracer&) = delete;
  VulkanShadowTracer& operator=(const VulkanShadowTracer&) = delete;

  void setCreateMs(double ms) { info_.createMs = ms; }
  const TracerInfo& info() const override { return info_; }

  std::unique_ptr<TraceScene> buildScene(const Scene& scene) override {
    return translateVulkanErrors("buildScene",
                                 [&] { return AccelerationScene::build(device_, scene); });
  }

  SceneBuilder sceneBuilder() const override {
    return [device = device_](const Scene& scene) -> std::unique_ptr<TraceScene> {
      return translateVulkanErrors("buildScene", [&] {
        // On the builds' own queue: waiting here waits for this build, not for the frames'
        // traces queued before it. Held until then, so that the next build ahead with these
        // commands does not wait for this one.
        const VulkanDevice::AheadLease lease = device->leaseAheadCommands();
        std::unique_ptr<AccelerationScene> built =
            AccelerationScene::build(device, scene, lease.commands());
        built->buildGpuMs();  // waits here, on the caller's thread, not on the render thread
        return built;
      });
    };
  }

  const RayBuffers& rayBuffers(const RayBatchShape& shape, Transport transport,
                               RayLane lane) override {
    return translateVulkanErrors("rayBuffers", [&]() -> const RayBuffers& {
      checkShape(shape, device_->limits().maxStorageBufferRange);
      if (transport == Transport::Interop && !info_.externalMemoryFd) {
        throw Error(
            ErrorCode::Unavailable,
            fmt::format("interop ray buffers: {} cannot export memory as fds", info_.deviceName));
      }
      RayBufferSet& buffers = rayBuffers_.at(checkLane(lane));
      if (!buffers.fits(shape, transport)) {
        submissions_.retireAll();  // no trace may still use the old buffers
        buffers.reallocate(*device_, shape, transport);
      }
      return buffers.shared();
    });
  }

  SemaphoreFds exportSemaphores(RayLane lane) override {
    return translateVulkanErrors("exportSemaphores", [&] {
      if (!info_.externalSemaphoreFd) {
        throw Error(ErrorCode::Unavailable,
                    fmt::format("{} cannot export semaphores as fds", info_.deviceName));
      }
      std::optional<ExportedSemaphores>& semaphores = semaphores_.at(checkLane(lane));
      submissions_.retireAll();  // no submission may still wait on or signal the old pair
      semaphores.emplace(*device_);
      return semaphores->exportFds();
    });
  }

  void trace(const TraceScene& scene, TracePath path, const RayBatchShape& shape,
             const TraceParams& params, bool useSemaphores, RayLane lane) override {
    translateVulkanErrors("trace", [&] {
      const std::uint32_t slot = submitRays(scene, path, shape, params, useSemaphores, lane);
      if (!useSemaphores) submissions_.retire(slot);
    });
  }

  std::uint64_t submitTrace(const TraceScene& scene, TracePath path, const RayBatchShape& shape,
                            const TraceParams& params, RayLane lane) override {
    return translateVulkanErrors("trace", [&] {
      submitRays(scene, path, shape, params, false, lane);
      return submissions_.lastSubmission();
    });
  }

  void awaitTrace(std::uint64_t number) override {
    translateVulkanErrors("awaitTrace", [&] { submissions_.retireThrough(number); });
  }

  bool traceFinished(std::uint64_t number) override {
    return translateVulkanErrors("traceFinished", [&] { return submissions_.finished(number); });
  }

  std::uint64_t lastTrace() const override { return submissions_.lastSubmission(); }
  TraceTimings collectTimingsThrough(std::uint64_t through) override {
    return translateVulkanErrors("collectTimings", [&] {
      return TraceTimings{.traceGpuMs = submissions_.takeGpuMs(through)};
    });
  }

  // Closest hits: forwarded to their own half (vk/hit_tracer.hpp).
  const HitBuffers& hitBuffers(std::uint32_t rays, Transport transport) override {
    return translateVulkanErrors(
        "hitBuffers", [&]() -> const HitBuffers& { return hits_.buffers(rays, transport); });
  }
  SemaphoreFds exportHitSemaphores() override {
    return translateVulkanErrors("exportHitSemaphores", [&] { return hits_.exportSemaphores(); });
  }
  void traceHits(const TraceScene& scene, TracePath path, const HitBatchShape& shape,
                 bool useSemaphores) override {
    translateVulkanErrors("traceHits",
                          [&] { hits_.trace(ownScene(scene), path, shape, useSemaphores); });
  }
  TraceTimings collectHitTimings() override {
    return translateVulkanErrors("collectHitTimings", [&] { return hits_.collectTimings(); });
  }

  // Light paths: forwarded to their own half (vk/light_path_tracer.hpp).
  const VplBuffers& vplBuffers(std::uint32_t vplCount, Transport transport) override {
    return translateVulkanErrors("vplBuffers", [&]() -> const VplBuffers& {
      return lightPaths_.buffers(vplCount, transport);
    });
  }
  SemaphoreFds exportLightPathSemaphores() override {
    return translateVulkanErrors("exportLightPathSemaphores",
                                 [&] { return lightPaths_.exportSemaphores(); });
  }
  void traceLightPaths(const TraceScene& scene, TracePath path, const LightPathScene& surfaces,
                       const LightPathBatch& batch, bool useSemaphores) override {
    translateVulkanErrors("traceLightPaths", [&] {
      lightPaths_.trace(ownScene(scene), path, surfaces, batch, useSemaphores);
    });
  }
  std::uint64_t lastLightPathTrace() const override { return lightPaths_.lastSubmission(); }
  LightPathTimings collectLightPathTimingsThrough(std::uint64_t through) override {
    return translateVulkanErrors("collectLightPathTimings",
                                 [&] { return lightPaths_.collectTimings(through); });
  }

 private:
  const AccelerationScene& ownScene(const TraceScene& scene) const {
    const auto* built = dynamic_cast<const AccelerationScene*>(&scene);
    if (built == nullptr || &built->device() != device_.get()) {
      throw Error(ErrorCode::Invalid, "trace: the scene was built by another shadow tracer");
    }
    return *built;
  }

  const TraceRecorder& pathFor(TracePath path) const {
    const auto& recorder = path == TracePath::RayQuery ? rayQuery_ : pipeline_;
    if (!recorder) {
      throw Error(ErrorCode::Unavailable,
                  fmt::format("trace: {} has no {} path", info_.deviceName, enumName(path)));
    }
    return *recorder;
  }

  static RayLane checkLane(RayLane lane) {
    if (lane >= kRayLanes) {
      throw Error(ErrorCode::Invalid,
                  fmt::format("ray lane {}: the tracer has lanes 0 to {}", lane, kRayLanes - 1));
    }
    return lane;
  }

  // Records and submits the batch in `lane`'s buffers; returns its submission slot.
  std::uint32_t submitRays(const TraceScene& scene, TracePath path, const RayBatchShape& shape,
                           const TraceParams& params, bool useSemaphores, RayLane lane) {
    const AccelerationScene& built = ownScene(scene);
    const TraceRecorder& recorder = pathFor(path);
    checkBatch(shape, useSemaphores, lane);
    const RayBufferSet& buffers = rayBuffers_[lane];
    const std::uint32_t slot = submissions_.acquire();
    layout_.write(slot, {.scene = built.topLevel(),
                         .origins = buffers.origins(),
                         .targets = buffers.targets(),
                         .visibility = buffers.visibility()});
    const TracePushConstants constants = pushConstants(shape, params, path);
    const std::array<::vk::Buffer, 3> shared{buffers.origins(), buffers.targets(),
                                             buffers.visibility()};
    // The ray-query shader skips SIMD groups of pixels without a surface (their words stay 0).
    const bool skipsBackground = path == TracePath::RayQuery;
    submitTraceBatch(submissions_, slot, device_->queueFamily(),
                     {.recorder = &recorder,
                      .set = layout_.set(slot),
                      .constants = constantBytes(constants),
                      .launch = launchOf(shape, path),
                      .transport = buffers.shared().transport,
                      .buffers = shared,
                      .zeroed = buffers.visibility(),
                      .zeroedBytes = skipsBackground ? rayBatchBytes(shape).visibility : 0},
                     useSemaphores ? &*semaphores_[lane] : nullptr);
    return slot;
  }

  void checkBatch(const RayBatchShape& shape, bool useSemaphores, RayLane lane) const {
    checkShape(shape, device_->limits().maxStorageBufferRange);
    const RayBufferSet& buffers = rayBuffers_.at(checkLane(lane));
    if (!buffers.allocated() || !buffers.fits(shape, buffers.shared().transport)) {
      throw Error(ErrorCode::Invalid,
                  "trace: the ray buffers do not hold the batch: call rayBuffers() with its "
                  "shape first");
    }
    if (useSemaphores && !semaphores_[lane]) {
      throw Error(ErrorCode::Invalid, "trace: no semaphores to wait on: call exportSemaphores()");
    }
  }

  std::shared_ptr<const VulkanDevice> device_;
  TracerInfo info_;
  TraceLayout layout_;
  std::unique_ptr<TraceRecorder> rayQuery_;
  std::unique_ptr<TraceRecorder> pipeline_;
  TraceSubmissions submissions_;
  std::array<RayBufferSet, kRayLanes> rayBuffers_;
  std::array<std::optional<ExportedSemaphores>, kRayLanes> semaphores_;
  HitTracer hits_;
  LightPathTracer lightPaths_;
};

}  // namespace

std::unique_ptr<ShadowTracer> ShadowTracer::create(const DeviceUuid& glDevice) {
  const Stopwatch wallClock;
  auto tracer = translateVulkanErrors("ShadowTracer::create", [&] {
    return std::make_unique<VulkanShadowTracer>(VulkanDevice::create(glDevice));
  });
  tracer->setCreateMs(wallClock.elapsedMs());
  const TracerInfo& info = tracer->info();
  spdlog::info(
      "vulkan: shadow tracer on {} ({}, Vulkan {}, UUID {}): {}; interop memory {}, interop "
      "semaphores {}; created in {:.0f} ms",
      info.deviceName, info.driverName, info.apiVersion, uuidText(glDevice), pathNames(info),
      info.externalMemoryFd ? "yes" : "no", info.externalSemaphoreFd ? "yes" : "no", info.createMs);
  return tracer;
}

}  // namespace lgh::vk
