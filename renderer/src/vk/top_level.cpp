#include "vk/top_level.hpp"

#include <cstring>

#include "vk/one_time_commands.hpp"
#include "vk/timestamp_queries.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

// Instance data must start 16-byte aligned.
constexpr ::vk::DeviceSize kInstanceAlignment = 16;

DeviceBuffer uploadInstances(const VulkanDevice& device,
                             const std::vector<::vk::AccelerationStructureInstanceKHR>& instances) {
  const ::vk::DeviceSize bytes = instances.size() * sizeof(::vk::AccelerationStructureInstanceKHR);
  DeviceBuffer buffer(
      device, {.size = bytes,
               .usage = ::vk::BufferUsageFlagBits::eAccelerationStructureBuildInputReadOnlyKHR,
               .memory = MemoryKind::HostVisible,
               .deviceAddress = true,
               .addressAlignment = kInstanceAlignment});
  if (bytes > 0) std::memcpy(buffer.mapped(), instances.data(), bytes);
  return buffer;
}

}  // namespace

TopLevel buildTopLevel(const VulkanDevice& device,
                       const std::vector<::vk::AccelerationStructureInstanceKHR>& instances) {
  const DeviceBuffer instanceBuffer = uploadInstances(device, instances);
  const ::vk::AccelerationStructureGeometryKHR geometry{
      .geometryType = ::vk::GeometryTypeKHR::eInstances,
      .geometry = ::vk::AccelerationStructureGeometryInstancesDataKHR{
          .arrayOfPointers = VK_FALSE, .data = instanceBuffer.address()}};
  ::vk::AccelerationStructureBuildGeometryInfoKHR info{
      .type = ::vk::AccelerationStructureTypeKHR::eTopLevel,
      .flags = ::vk::BuildAccelerationStructureFlagBitsKHR::ePreferFastTrace,
      .mode = ::vk::BuildAccelerationStructureModeKHR::eBuild,
      .geometryCount = 1,
      .pGeometries = &geometry};
  const auto count = static_cast<std::uint32_t>(instances.size());
  const auto sizes = device.device().getAccelerationStructureBuildSizesKHR(
      ::vk::AccelerationStructureBuildTypeKHR::eDevice, info, count);
  TopLevel top{.structure =
                   AccelerationStructure(device, ::vk::AccelerationStructureTypeKHR::eTopLevel,
                                         sizes.accelerationStructureSize)};
  const DeviceBuffer scratch(device, {.size = sizes.buildScratchSize,
                                      .usage = ::vk::BufferUsageFlagBits::eStorageBuffer,
                                      .memory = MemoryKind::DeviceLocal,
                                      .deviceAddress = true,
                                      .addressAlignment = device.limits().scratchAlignment});
  info.dstAccelerationStructure = top.structure.handle();
  info.scratchData = scratch.address();
  const ::vk::AccelerationStructureBuildRangeInfoKHR range{.primitiveCount = count};
  const TimestampQueries timestamps(device, 1);
  submitAndWait(device, [&](const ::vk::raii::CommandBuffer& commands) {
    // The bottom levels were built (or compacted) by earlier submissions.
    commands.pipelineBarrier(
        ::vk::PipelineStageFlagBits::eAccelerationStructureBuildKHR,
        ::vk::PipelineStageFlagBits::eAccelerationStructureBuildKHR, {},
        ::vk::MemoryBarrier{.srcAccessMask = ::vk::AccessFlagBits::eAccelerationStructureWriteKHR,
                            .dstAccessMask = ::vk::AccessFlagBits::eAccelerationStructureReadKHR},
        nullptr, nullptr);
    timestamps.begin(commands, 0);
    commands.buildAccelerationStructuresKHR(info, &range);
    timestamps.end(commands, 0);
  });
  top.buildGpuMs = timestamps.elapsedMs(0);
  return top;
}

}  // namespace lgh::vk
