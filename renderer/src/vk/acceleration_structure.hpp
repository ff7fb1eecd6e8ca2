// One acceleration structure and the buffer that holds it (the structure is destroyed first).
#pragma once

#include "vk/device_buffer.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

class AccelerationStructure {
 public:
  AccelerationStructure(const VulkanDevice& device, ::vk::AccelerationStructureTypeKHR type,
                        ::vk::DeviceSize size);

  ::vk::AccelerationStructureKHR handle() const { return *structure_; }
  ::vk::DeviceAddress address() const { return address_; }
  ::vk::DeviceSize memoryBytes() const { return buffer_.allocationSize(); }

 private:
  DeviceBuffer buffer_;
  ::vk::raii::AccelerationStructureKHR structure_;
  ::vk::DeviceAddress address_;
};

}  // namespace lgh::vk
