// The top-level acceleration structure over a scene's instances; with no instances it is empty
// and every ray misses. Sized first, then placed in a buffer of its own (build) or in one shared
// with the bottom levels, its build recorded after theirs in one submission (place, record).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "vk/acceleration_structure.hpp"

namespace lgh::vk {

class OneTimeCommands;
class VulkanDevice;

class TopLevelBuild {
 public:
  // Sized for up to `maxInstances` instances; its instances, scratch and submission are
  // `oneTime`'s.
  TopLevelBuild(const VulkanDevice& device, OneTimeCommands& oneTime, std::uint32_t maxInstances);

  ::vk::DeviceSize storageBytes() const { return sizes_.accelerationStructureSize; }
  ::vk::DeviceSize scratchBytes() const { return sizes_.buildScratchSize; }

  // Builds it in a buffer of its own and waits for the GPU; the bottom levels the instances name
  // must have been built by earlier submissions.
  AccelerationStructure build(const std::vector<::vk::AccelerationStructureInstanceKHR>& instances,
                              double& buildGpuMs);

  // Creates it at `offset` (a multiple of AccelerationStructure::kOffsetAlignment) in `storage`.
  AccelerationStructure place(const std::shared_ptr<const DeviceBuffer>& storage,
                              ::vk::DeviceSize offset);
  // Copies the instances into memory this object keeps and records the build of the placed
  // structure (`scratch`: scratchBytes() of device memory, aligned as the device wants) after a
  // barrier that waits for the bottom-level builds recorded before it.
  void record(const ::vk::raii::CommandBuffer& commands,
              const std::vector<::vk::AccelerationStructureInstanceKHR>& instances,
              ::vk::DeviceAddress scratch);

 private:
  ::vk::AccelerationStructureBuildGeometryInfoKHR info() const;

  const VulkanDevice& device_;
  OneTimeCommands& oneTime_;
  std::uint32_t maxInstances_;
  ::vk::AccelerationStructureGeometryKHR geometry_;
  ::vk::AccelerationStructureBuildSizesInfoKHR sizes_;
  ::vk::AccelerationStructureKHR destination_ = nullptr;
  const DeviceBuffer* instances_ = nullptr;  // transient (vk/transient_buffers.hpp)
};

}  // namespace lgh::vk
