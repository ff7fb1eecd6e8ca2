// A buffer with memory of its own: one allocation per buffer, which keeps ownership obvious and
// is plenty for the tracer's few, large buffers. Device-local, host-visible (mapped for its
// life), or exportable to GL as an opaque fd (a dedicated allocation).
#pragma once

#include <cstddef>
#include <cstdint>

#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

enum class MemoryKind {
  DeviceLocal,  // device-local where the device has it
  HostVisible,  // host-visible and host-coherent, mapped for the buffer's life
  Exportable,   // device-local, dedicated, exportable as an opaque fd
};

struct BufferSpec {
  ::vk::DeviceSize size = 0;
  ::vk::BufferUsageFlags usage;
  MemoryKind memory = MemoryKind::DeviceLocal;
  bool deviceAddress = false;
  // The buffer's usable part starts at a device address aligned to this (scratch memory, shader
  // binding tables): the buffer is made larger by up to that much and offset() says where.
  ::vk::DeviceSize addressAlignment = 1;
};

class DeviceBuffer {
 public:
  DeviceBuffer(const VulkanDevice& device, const BufferSpec& spec);

  ::vk::Buffer handle() const { return *buffer_; }
  ::vk::DeviceSize size() const { return size_; }  // the usable bytes, from offset()
  ::vk::DeviceSize offset() const { return offset_; }
  ::vk::DeviceSize allocationSize() const { return allocationSize_; }
  ::vk::DeviceAddress address() const { return address_; }  // 0 without spec.deviceAddress
  std::byte* mapped() const { return mapped_; }             // nullptr unless HostVisible
  // Exportable only: a new fd for the memory, which the caller owns.
  int exportFd() const;

 private:
  DeviceBuffer(const VulkanDevice& device, ::vk::raii::Buffer buffer, const BufferSpec& spec);

  const ::vk::raii::Device* device_;
  // The memory first, so that the buffer goes before the memory it is bound to.
  ::vk::raii::DeviceMemory memory_;
  ::vk::raii::Buffer buffer_;
  ::vk::DeviceSize size_;
  ::vk::DeviceSize offset_ = 0;
  ::vk::DeviceSize allocationSize_ = 0;
  ::vk::DeviceAddress address_ = 0;
  std::byte* mapped_ = nullptr;
};

constexpr ::vk::DeviceSize alignUp(::vk::DeviceSize value, ::vk::DeviceSize alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

}  // namespace lgh::vk
