#include "vk/trace_barriers.hpp"

#include <vector>

namespace lgh::vk {
namespace {

using Access = ::vk::AccessFlagBits;
using Stage = ::vk::PipelineStageFlagBits;

// The shared buffers handed between queue families: from `from` to `to`.
std::vector<::vk::BufferMemoryBarrier> ownershipTransfer(const TraceBarrierScope& scope,
                                                         std::uint32_t from, std::uint32_t to,
                                                         ::vk::AccessFlags written,
                                                         ::vk::AccessFlags read) {
  std::vector<::vk::BufferMemoryBarrier> barriers;
  barriers.reserve(scope.buffers.size());
  for (const ::vk::Buffer buffer : scope.buffers) {
    barriers.push_back({.srcAccessMask = written,
                        .dstAccessMask = read,
                        .srcQueueFamilyIndex = from,
                        .dstQueueFamilyIndex = to,
                        .buffer = buffer,
                        .offset = 0,
                        .size = VK_WHOLE_SIZE});
  }
  return barriers;
}

}  // namespace

void recordBarriersBeforeTrace(const ::vk::raii::CommandBuffer& commands,
                               const TraceBarrierScope& scope) {
  const ::vk::MemoryBarrier sceneBuilt{.srcAccessMask = Access::eAccelerationStructureWriteKHR,
                                       .dstAccessMask = Access::eAccelerationStructureReadKHR};
  if (scope.transport == Transport::Interop) {
    // Acquire: what GL wrote (made available by GL's semaphore signal or glFinish), for the
    // trace and for a fill before it.
    const ::vk::PipelineStageFlags users =
        scope.fillsFirst ? scope.traceStage | Stage::eTransfer : scope.traceStage;
    const ::vk::AccessFlags access =
        scope.fillsFirst ? Access::eShaderRead | Access::eShaderWrite | Access::eTransferWrite
                         : Access::eShaderRead | Access::eShaderWrite;
    commands.pipelineBarrier(
        Stage::eAccelerationStructureBuildKHR | Stage::eTopOfPipe, users, {}, sceneBuilt,
        ownershipTransfer(scope, VK_QUEUE_FAMILY_EXTERNAL, scope.queueFamily, {}, access), nullptr);
  } else {
    // The host's writes to the staging buffers are visible to the submission already.
    commands.pipelineBarrier(Stage::eAccelerationStructureBuildKHR, scope.traceStage, {},
                             sceneBuilt, nullptr, nullptr);
  }
}

void recordFillBeforeTrace(const ::vk::raii::CommandBuffer& commands,
                           const TraceBarrierScope& scope) {
  const ::vk::MemoryBarrier filled{.srcAccessMask = Access::eTransferWrite,
                                   .dstAccessMask = Access::eShaderRead | Access::eShaderWrite};
  commands.pipelineBarrier(Stage::eTransfer, scope.traceStage, {}, filled, nullptr, nullptr);
}

void recordBarriersAfterTrace(const ::vk::raii::CommandBuffer& commands,
                              const TraceBarrierScope& scope) {
  if (scope.transport == Transport::Interop) {
    // Release to GL, which reads after the vkDone semaphore (or once trace() has returned).
    commands.pipelineBarrier(scope.traceStage, Stage::eBottomOfPipe, {}, nullptr,
                             ownershipTransfer(scope, scope.queueFamily, VK_QUEUE_FAMILY_EXTERNAL,
                                               Access::eShaderWrite, {}),
                             nullptr);
  } else {
    const ::vk::MemoryBarrier hostRead{.srcAccessMask = Access::eShaderWrite,
                                       .dstAccessMask = Access::eHostRead};
    commands.pipelineBarrier(scope.traceStage, Stage::eHost, {}, hostRead, nullptr, nullptr);
  }
}

}  // namespace lgh::vk
