#include "vk/top_level.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "vk/one_time_commands.hpp"
#include "vk/timestamp_queries.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

// Instance data must start 16-byte aligned.
constexpr ::vk::DeviceSize kInstanceAlignment = 16;

const DeviceBuffer& uploadInstances(
    const VulkanDevice& device, OneTimeCommands& oneTime,
    const std::vector<::vk::AccelerationStructureInstanceKHR>& instances) {
  const ::vk::DeviceSize bytes = instances.size() * sizeof(::vk::AccelerationStructureInstanceKHR);
  const DeviceBuffer& buffer = oneTime.transientBuffers().get(
      device, {.size = bytes,
               .usage = ::vk::BufferUsageFlagBits::eAccelerationStructureBuildInputReadOnlyKHR,
               .memory = MemoryKind::HostVisible,
               .deviceAddress = true,
               .addressAlignment = kInstanceAlignment});
  if (bytes > 0) std::memcpy(buffer.mapped(), instances.data(), bytes);
  return buffer;
}

}  // namespace

TopLevelBuild::TopLevelBuild(const VulkanDevice& device, OneTimeCommands& oneTime,
                             std::uint32_t maxInstances)
    : device_(device),
      oneTime_(oneTime),
      maxInstances_(maxInstances),
      geometry_{.geometryType = ::vk::GeometryTypeKHR::eInstances,
                .geometry = ::vk::AccelerationStructureGeometryInstancesDataKHR{.arrayOfPointers =
                                                                                    VK_FALSE}},
      sizes_(device.device().getAccelerationStructureBuildSizesKHR(
          ::vk::AccelerationStructureBuildTypeKHR::eDevice, info(), maxInstances)) {}

::vk::AccelerationStructureBuildGeometryInfoKHR TopLevelBuild::info() const {
  return {.type = ::vk::AccelerationStructureTypeKHR::eTopLevel,
          .flags = ::vk::BuildAccelerationStructureFlagBitsKHR::ePreferFastTrace,
          .mode = ::vk::BuildAccelerationStructureModeKHR::eBuild,
          .dstAccelerationStructure = destination_,
          .geometryCount = 1,
          .pGeometries = &geometry_};
}

AccelerationStructure TopLevelBuild::build(
    const std::vector<::vk::AccelerationStructureInstanceKHR>& instances, double& buildGpuMs) {
  const auto storage = std::make_shared<const DeviceBuffer>(
      device_, accelerationStorage(std::max<::vk::DeviceSize>(storageBytes(), 1)));
  AccelerationStructure structure = place(storage, 0);
  const DeviceBuffer& scratch =
      oneTime_.transientBuffers().get(device_, accelerationScratch(device_, scratchBytes()));
  const TimestampQueries& timestamps = oneTime_.timestamps();
  oneTime_.submitAndWait(device_, [&](const ::vk::raii::CommandBuffer& commands) {
    timestamps.begin(commands, 0);
    record(commands, instances, scratch.address());
    timestamps.end(commands, 0);
  });
  buildGpuMs = timestamps.elapsedMs(0);
  return structure;
}

AccelerationStructure TopLevelBuild::place(const std::shared_ptr<const DeviceBuffer>& storage,
                                           ::vk::DeviceSize offset) {
  AccelerationStructure structure(device_, ::vk::AccelerationStructureTypeKHR::eTopLevel, storage,
                                  offset, storageBytes());
  destination_ = structure.handle();
  return structure;
}

void TopLevelBuild::record(const ::vk::raii::CommandBuffer& commands,
                           const std::vector<::vk::AccelerationStructureInstanceKHR>& instances,
                           ::vk::DeviceAddress scratch) {
  if (instances.size() > maxInstances_) {
    throw std::logic_error("TopLevelBuild: more instances than it was sized for");
  }
  instances_ = &uploadInstances(device_, oneTime_, instances);
  geometry_.geometry.instances.data = instances_->address();
  ::vk::AccelerationStructureBuildGeometryInfoKHR build = info();
  build.scratchData = scratch;
  const ::vk::AccelerationStructureBuildRangeInfoKHR range{
      .primitiveCount = static_cast<std::uint32_t>(instances.size())};
  // The bottom levels are built by the commands before these (or by earlier submissions).
  commands.pipelineBarrier(
      ::vk::PipelineStageFlagBits::eAccelerationStructureBuildKHR,
      ::vk::PipelineStageFlagBits::eAccelerationStructureBuildKHR, {},
      ::vk::MemoryBarrier{.srcAccessMask = ::vk::AccessFlagBits::eAccelerationStructureWriteKHR,
                          .dstAccessMask = ::vk::AccessFlagBits::eAccelerationStructureReadKHR},
      nullptr, nullptr);
  commands.buildAccelerationStructuresKHR(build, &range);
}

}  // namespace lgh::vk
