#include "vk/hit_tracer.hpp"

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "lgh/error.hpp"
#include "vk/acceleration_scene.hpp"
#include "vk/spirv_shaders.hpp"
#include "vk/trace_batch.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

// Submissions in flight at once: a frame's bounces follow each other, so few are needed.
constexpr std::uint32_t kSlots = 4;
constexpr std::uint32_t kHitBuffers = 2;  // rays, hits

// Rays per row of the launch: a 1D launch of a million rays would pass the limits of one
// dimension on some devices, so batches launch rows of this many rays.
constexpr std::uint32_t kHitLaunchWidth = 16384;

// glsl/vk/closest_hit_query.comp: 64 rays per work group along a row of the launch, one row of
// work groups per launch row.
RayQueryProgram hitQueryProgram() {
  return {.shader = spirv::closest_hit_query_comp(), .groupWidth = 64, .groupHeight = 1};
}

// glsl/vk/closest_hit.rgen launched per ray, closest_hit.rmiss its miss shader and
// closest_hit.rchit the closest-hit shader of its one triangle hit group.
PipelineProgram hitPipelineProgram() {
  return {.rayGeneration = spirv::closest_hit_rgen(),
          .miss = spirv::closest_hit_rmiss(),
          .closestHit = spirv::closest_hit_rchit()};
}

}  // namespace

HitPushConstants hitBatchConstants(const HitBatchShape& shape) {
  return {.rayCount = shape.rays,
          .anyHit = shape.query == HitQuery::Any ? 1U : 0U,
          .launchWidth = std::min(shape.rays, kHitLaunchWidth)};
}

TraceLaunch hitBatchLaunch(const HitBatchShape& shape) {
  return {.width = std::min(shape.rays, kHitLaunchWidth),
          .height = (shape.rays + kHitLaunchWidth - 1) / kHitLaunchWidth};
}

TraceLayout createHitTraceLayout(const VulkanDevice& device, ::vk::ShaderStageFlags stages,
                                 std::uint32_t sets) {
  return {device, stages, sets, kHitBuffers, sizeof(HitPushConstants)};
}

HitTracer::HitTracer(const VulkanDevice& device, ::vk::ShaderStageFlags stages)
    : device_(&device),
      layout_(createHitTraceLayout(device, stages, kSlots)),
      submissions_(device, kSlots) {
  if (device.capabilities().rayQuery) {
    rayQuery_ = createRayQueryRecorder(device, layout_, hitQueryProgram());
  }
  if (device.capabilities().rayTracingPipeline) {
    pipeline_ = createRayTracingPipelineRecorder(device, layout_, hitPipelineProgram());
  }
}

const HitBuffers& HitTracer::buffers(std::uint32_t rays, Transport transport) {
  checkHitBatch(rays, device_->limits().maxStorageBufferRange);
  if (transport == Transport::Interop && !device_->capabilities().externalMemoryFd) {
    throw Error(ErrorCode::Unavailable,
                fmt::format("interop closest-hit buffers: {} cannot export memory as fds",
                            device_->info().deviceName));
  }
  if (!buffers_.fits(rays, transport)) {
    submissions_.retireAll();  // no trace may still use the old buffers
    buffers_.reallocate(*device_, rays, transport);
  }
  return buffers_.shared();
}

SemaphoreFds HitTracer::exportSemaphores() {
  if (!device_->capabilities().externalSemaphoreFd) {
    throw Error(ErrorCode::Unavailable,
                fmt::format("{} cannot export semaphores as fds", device_->info().deviceName));
  }
  submissions_.retireAll();  // no submission may still wait on or signal the old pair
  semaphores_.emplace(*device_);
  return semaphores_->exportFds();
}

const TraceRecorder& HitTracer::recorder(TracePath path) const {
  const auto& recorder = path == TracePath::RayQuery ? rayQuery_ : pipeline_;
  if (!recorder) {
    throw Error(ErrorCode::Unavailable, fmt::format("traceHits: {} has no {} path",
                                                    device_->info().deviceName, enumName(path)));
  }
  return *recorder;
}

void HitTracer::trace(const AccelerationScene& scene, TracePath path, const HitBatchShape& shape,
                      bool useSemaphores) {
  const TraceRecorder& pathRecorder = recorder(path);
  checkHitBatch(shape.rays, device_->limits().maxStorageBufferRange);
  if (!buffers_.allocated() || !buffers_.fits(shape.rays, buffers_.shared().transport)) {
    throw Error(ErrorCode::Invalid,
                "traceHits: the buffers do not hold the batch: call hitBuffers() with its size "
                "first");
  }
  if (useSemaphores && !semaphores_) {
    throw Error(ErrorCode::Invalid,
                "traceHits: no semaphores to wait on: call exportHitSemaphores()");
  }
  const std::uint32_t slot = submissions_.acquire();
  const std::array<::vk::Buffer, kHitBuffers> shared{buffers_.rays(), buffers_.hits()};
  layout_.write(slot, scene.topLevel(), shared);
  const HitPushConstants constants = hitBatchConstants(shape);
  submitTraceBatch(submissions_, slot, device_->queueFamily(),
                   {.recorder = &pathRecorder,
                    .set = layout_.set(slot),
                    .constants = constantBytes(constants),
                    .launch = hitBatchLaunch(shape),
                    .transport = buffers_.shared().transport,
                    .buffers = shared,
                    .zeroed = {},
                    .zeroedBytes = 0},
                   useSemaphores ? &*semaphores_ : nullptr);
  if (!useSemaphores) submissions_.retire(slot);
}

TraceTimings HitTracer::collectTimings() {
  return TraceTimings{.traceGpuMs = submissions_.takeGpuMs(submissions_.lastSubmission())};
}

}  // namespace lgh::vk
