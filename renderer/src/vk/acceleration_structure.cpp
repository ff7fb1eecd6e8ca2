#include "vk/acceleration_structure.hpp"

#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

::vk::raii::AccelerationStructureKHR createIn(const VulkanDevice& device,
                                              ::vk::AccelerationStructureTypeKHR type,
                                              const DeviceBuffer& buffer, ::vk::DeviceSize offset,
                                              ::vk::DeviceSize size) {
  return {device.device(),
          ::vk::AccelerationStructureCreateInfoKHR{
              .buffer = buffer.handle(), .offset = offset, .size = size, .type = type}};
}

::vk::DeviceAddress addressOf(const VulkanDevice& device,
                              const ::vk::raii::AccelerationStructureKHR& structure) {
  return device.device().getAccelerationStructureAddressKHR(
      ::vk::AccelerationStructureDeviceAddressInfoKHR{.accelerationStructure = *structure});
}

}  // namespace

BufferSpec accelerationStorage(::vk::DeviceSize size) {
  return {.size = size,
          .usage = ::vk::BufferUsageFlagBits::eAccelerationStructureStorageKHR,
          .memory = MemoryKind::DeviceLocal,
          .deviceAddress = true};
}

BufferSpec accelerationScratch(const VulkanDevice& device, ::vk::DeviceSize size) {
  return {.size = size,
          .usage = ::vk::BufferUsageFlagBits::eStorageBuffer,
          .memory = MemoryKind::DeviceLocal,
          .deviceAddress = true,
          .addressAlignment = device.limits().scratchAlignment};
}

AccelerationStructure::AccelerationStructure(const VulkanDevice& device,
                                             ::vk::AccelerationStructureTypeKHR type,
                                             ::vk::DeviceSize size)
    : buffer_(std::make_shared<const DeviceBuffer>(device, accelerationStorage(size))),
      structure_(createIn(device, type, *buffer_, 0, size)),
      address_(addressOf(device, structure_)),
      memoryBytes_(buffer_->allocationSize()) {}

AccelerationStructure::AccelerationStructure(const VulkanDevice& device,
                                             ::vk::AccelerationStructureTypeKHR type,
                                             std::shared_ptr<const DeviceBuffer> storage,
                                             ::vk::DeviceSize offset, ::vk::DeviceSize size)
    : buffer_(std::move(storage)),
      structure_(createIn(device, type, *buffer_, offset, size)),
      address_(addressOf(device, structure_)),
      memoryBytes_(size) {}

}  // namespace lgh::vk
