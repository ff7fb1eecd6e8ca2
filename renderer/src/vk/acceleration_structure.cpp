#include "vk/acceleration_structure.hpp"

#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

BufferSpec storageFor(::vk::DeviceSize size) {
  return {.size = size,
          .usage = ::vk::BufferUsageFlagBits::eAccelerationStructureStorageKHR,
          .memory = MemoryKind::DeviceLocal,
          .deviceAddress = true};
}

}  // namespace

AccelerationStructure::AccelerationStructure(const VulkanDevice& device,
                                             ::vk::AccelerationStructureTypeKHR type,
                                             ::vk::DeviceSize size)
    : buffer_(device, storageFor(size)),
      structure_(device.device(),
                 ::vk::AccelerationStructureCreateInfoKHR{
                     .buffer = buffer_.handle(), .offset = 0, .size = size, .type = type}),
      address_(device.device().getAccelerationStructureAddressKHR(
          ::vk::AccelerationStructureDeviceAddressInfoKHR{.accelerationStructure = *structure_})) {}

}  // namespace lgh::vk
