// One acceleration structure and the buffer that holds it (the structure is destroyed first):
// a buffer of its own, or a range of one that several structures of a scene share (one
// allocation for all of them).
#pragma once

#include <memory>

#include "vk/device_buffer.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

class AccelerationStructure {
 public:
  // Structures start at offsets that are multiples of this in a shared buffer.
  static constexpr ::vk::DeviceSize kOffsetAlignment = 256;

  // In a buffer of its own.
  AccelerationStructure(const VulkanDevice& device, ::vk::AccelerationStructureTypeKHR type,
                        ::vk::DeviceSize size);
  // At `offset` (a multiple of kOffsetAlignment) in `storage`, which it keeps alive; the buffer
  // needs eAccelerationStructureStorageKHR usage and a device address.
  AccelerationStructure(const VulkanDevice& device, ::vk::AccelerationStructureTypeKHR type,
                        std::shared_ptr<const DeviceBuffer> storage, ::vk::DeviceSize offset,
                        ::vk::DeviceSize size);

  ::vk::AccelerationStructureKHR handle() const { return *structure_; }
  ::vk::DeviceAddress address() const { return address_; }
  // Its own buffer's allocation, or its range of the shared one.
  ::vk::DeviceSize memoryBytes() const { return memoryBytes_; }

 private:
  std::shared_ptr<const DeviceBuffer> buffer_;
  ::vk::raii::AccelerationStructureKHR structure_;
  ::vk::DeviceAddress address_;
  ::vk::DeviceSize memoryBytes_;
};

// The usage and memory of a buffer that holds acceleration structures.
BufferSpec accelerationStorage(::vk::DeviceSize size);
// Scratch memory for acceleration-structure builds, its address aligned as `device` wants.
BufferSpec accelerationScratch(const VulkanDevice& device, ::vk::DeviceSize size);

}  // namespace lgh::vk
