#include "vk/device_buffer.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "lgh/error.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

constexpr auto kOpaqueFd = ::vk::ExternalMemoryHandleTypeFlagBits::eOpaqueFd;

struct MemoryNeeds {
  ::vk::MemoryPropertyFlags required;
  ::vk::MemoryPropertyFlags preferred;
};

MemoryNeeds needsOf(MemoryKind kind) {
  using Flag = ::vk::MemoryPropertyFlagBits;
  switch (kind) {
    case MemoryKind::HostVisible:
      // Cached where possible: the host reads the visibility back.
      return {Flag::eHostVisible | Flag::eHostCoherent, Flag::eHostCached};
    case MemoryKind::DeviceLocal:
    case MemoryKind::Exportable:
      break;
  }
  return {{}, Flag::eDeviceLocal};
}

std::uint32_t chooseMemoryType(const ::vk::PhysicalDeviceMemoryProperties& memory,
                               std::uint32_t allowed, MemoryNeeds needs) {
  std::uint32_t fallback = VK_MAX_MEMORY_TYPES;
  for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
    const auto flags = memory.memoryTypes[i].propertyFlags;
    if ((allowed & (1U << i)) == 0 || (flags & needs.required) != needs.required) continue;
    if ((flags & needs.preferred) == needs.preferred) return i;
    if (fallback == VK_MAX_MEMORY_TYPES) fallback = i;
  }
  if (fallback == VK_MAX_MEMORY_TYPES) {
    throw Error(ErrorCode::Internal, "no Vulkan memory type fits the tracer's buffer");
  }
  return fallback;
}

::vk::raii::Buffer createBuffer(const ::vk::raii::Device& device, const BufferSpec& spec) {
  const ::vk::ExternalMemoryBufferCreateInfo external{.handleTypes = kOpaqueFd};
  ::vk::BufferUsageFlags usage = spec.usage;
  if (spec.deviceAddress) usage |= ::vk::BufferUsageFlagBits::eShaderDeviceAddress;
  return {device, ::vk::BufferCreateInfo{
                      .pNext = spec.memory == MemoryKind::Exportable ? &external : nullptr,
                      // Never empty: Vulkan has no buffers of 0 bytes.
                      .size = std::max<::vk::DeviceSize>(spec.size, 4) + spec.addressAlignment - 1,
                      .usage = usage,
                      .sharingMode = ::vk::SharingMode::eExclusive}};
}

::vk::raii::DeviceMemory allocateFor(const VulkanDevice& device, const ::vk::raii::Buffer& buffer,
                                     const BufferSpec& spec) {
  const ::vk::MemoryRequirements requirements = buffer.getMemoryRequirements();
  const ::vk::MemoryAllocateFlagsInfo addressFlags{
      .flags = ::vk::MemoryAllocateFlagBits::eDeviceAddress};
  const ::vk::MemoryDedicatedAllocateInfo dedicated{
      .pNext = spec.deviceAddress ? &addressFlags : nullptr, .buffer = *buffer};
  const ::vk::ExportMemoryAllocateInfo exported{.pNext = &dedicated, .handleTypes = kOpaqueFd};
  const void* chain = spec.deviceAddress ? &addressFlags : nullptr;
  if (spec.memory == MemoryKind::Exportable) chain = &exported;
  return {device.device(),
          ::vk::MemoryAllocateInfo{
              .pNext = chain,
              .allocationSize = requirements.size,
              .memoryTypeIndex = chooseMemoryType(device.memory(), requirements.memoryTypeBits,
                                                  needsOf(spec.memory))}};
}

}  // namespace

DeviceBuffer::DeviceBuffer(const VulkanDevice& device, const BufferSpec& spec)
    : DeviceBuffer(device, createBuffer(device.device(), spec), spec) {}

DeviceBuffer::DeviceBuffer(const VulkanDevice& device, ::vk::raii::Buffer buffer,
                           const BufferSpec& spec)
    : device_(&device.device()),
      memory_(allocateFor(device, buffer, spec)),
      buffer_(std::move(buffer)),
      size_(spec.size) {
  buffer_.bindMemory(*memory_, 0);
  allocationSize_ = buffer_.getMemoryRequirements().size;
  if (spec.deviceAddress) {
    const ::vk::DeviceAddress base =
        device.device().getBufferAddress(::vk::BufferDeviceAddressInfo{.buffer = *buffer_});
    address_ = alignUp(base, spec.addressAlignment);
    offset_ = address_ - base;
  }
  if (spec.memory == MemoryKind::HostVisible) {
    mapped_ = static_cast<std::byte*>(memory_.mapMemory(0, VK_WHOLE_SIZE)) + offset_;
  }
}

int DeviceBuffer::exportFd() const {
  return device_->getMemoryFdKHR(
      ::vk::MemoryGetFdInfoKHR{.memory = *memory_, .handleType = kOpaqueFd});
}

}  // namespace lgh::vk
