// Buffers that Vulkan owns and GL sees (shadow_tracer.hpp, SharedBuffer): allocated exportable for
// interop or host-visible for staging, and described for GL. Used by the shadow rays' and the
// closest-hit batches' buffer sets.
#pragma once

#include <cstdint>
#include <initializer_list>

#include "vk/device_buffer.hpp"
#include "vk/shadow_tracer.hpp"

namespace lgh::vk {

class VulkanDevice;

// A storage buffer (transfers too: whoever imports it may copy) of `size` bytes, exportable
// (interop) or host-visible and mapped (staging).
DeviceBuffer createSharedBuffer(const VulkanDevice& device, std::uint64_t size,
                                Transport transport);

// How GL sees it: a new fd (interop; the caller owns it) or the mapped pointer (staging).
SharedBuffer describeShared(const DeviceBuffer& buffer, Transport transport);

// Closes the fds of buffers described for interop whose ownership never passed on.
void closeSharedFds(std::initializer_list<const SharedBuffer*> buffers);

}  // namespace lgh::vk
