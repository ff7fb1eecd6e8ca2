#include "vk/shared_buffer.hpp"

#include <unistd.h>

#include "vk/vulkan_device.hpp"

namespace lgh::vk {

DeviceBuffer createSharedBuffer(const VulkanDevice& device, std::uint64_t size,
                                Transport transport) {
  return {
      device,
      {.size = size,
       .usage = ::vk::BufferUsageFlagBits::eStorageBuffer |
                ::vk::BufferUsageFlagBits::eTransferSrc | ::vk::BufferUsageFlagBits::eTransferDst,
       .memory =
           transport == Transport::Interop ? MemoryKind::Exportable : MemoryKind::HostVisible}};
}

SharedBuffer describeShared(const DeviceBuffer& buffer, Transport transport) {
  SharedBuffer shared;
  shared.size = buffer.size();
  if (transport == Transport::Interop) {
    shared.fd = buffer.exportFd();
    shared.allocationSize = buffer.allocationSize();
    shared.dedicated = true;
  } else {
    shared.mapped = buffer.mapped();
  }
  return shared;
}

void closeSharedFds(std::initializer_list<const SharedBuffer*> buffers) {
  for (const SharedBuffer* buffer : buffers) {
    if (buffer->fd >= 0) close(buffer->fd);
  }
}

}  // namespace lgh::vk
