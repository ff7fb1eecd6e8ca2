#include "vk/hit_tracer.hpp"

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "lgh/error.hpp"
#include "vk/acceleration_scene.hpp"
#include "vk/trace_barriers.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

// Submissions in flight at once: a frame's bounces follow each other, so few are needed.
constexpr std::uint32_t kSlots = 4;
constexpr std::uint32_t kHitBuffers = 2;  // rays, hits

}  // namespace

HitTracer::HitTracer(const VulkanDevice& device, ::vk::ShaderStageFlags stages)
    : device_(&device),
      layout_(device, stages, kSlots, kHitBuffers, sizeof(HitPushConstants)),
      submissions_(device, kSlots) {
  if (device.capabilities().rayQuery) rayQuery_ = createHitQueryRecorder(device, layout_);
  if (device.capabilities().rayTracingPipeline) {
    pipeline_ = createHitPipelineRecorder(device, layout_);
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

const HitRecorder& HitTracer::recorderFor(TracePath path) const {
  const auto& recorder = path == TracePath::RayQuery ? rayQuery_ : pipeline_;
  if (!recorder) {
    throw Error(ErrorCode::Unavailable, fmt::format("traceHits: {} has no {} path",
                                                    device_->info().deviceName, enumName(path)));
  }
  return *recorder;
}

void HitTracer::trace(const AccelerationScene& scene, TracePath path, const HitBatchShape& shape,
                      bool useSemaphores) {
  const HitRecorder& recorder = recorderFor(path);
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
  record(slot, recorder,
         {.rayCount = shape.rays,
          .anyHit = shape.query == HitQuery::Any ? 1U : 0U,
          .launchWidth = std::min(shape.rays, kHitLaunchWidth)});
  submissions_.submit(slot, useSemaphores ? semaphores_->glDone() : ::vk::Semaphore{},
                      ::vk::PipelineStageFlagBits::eAllCommands,
                      useSemaphores ? semaphores_->vkDone() : ::vk::Semaphore{});
  if (!useSemaphores) submissions_.retire(slot);
}

void HitTracer::record(std::uint32_t slot, const HitRecorder& recorder,
                       const HitPushConstants& constants) const {
  const ::vk::raii::CommandBuffer& commands = submissions_.commands(slot);
  const std::array<::vk::Buffer, kHitBuffers> shared{buffers_.rays(), buffers_.hits()};
  const TraceBarrierScope scope{.traceStage = recorder.stage(),
                                .transport = buffers_.shared().transport,
                                .queueFamily = device_->queueFamily(),
                                .buffers = shared};
  commands.begin({.flags = ::vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  submissions_.timestamps().begin(commands, slot);
  recordBarriersBeforeTrace(commands, scope);
  recorder.record(commands, layout_.set(slot), constants);
  recordBarriersAfterTrace(commands, scope);
  submissions_.timestamps().end(commands, slot);
  commands.end();
}

TraceTimings HitTracer::collectTimings() {
  submissions_.retireAll();
  return TraceTimings{.traceGpuMs = submissions_.takeGpuMs()};
}

}  // namespace lgh::vk
