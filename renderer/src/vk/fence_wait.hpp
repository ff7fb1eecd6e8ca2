// Waiting for the GPU, bounded: a trace that waits on a GL semaphore GL never signals would
// otherwise hang the render thread for good.
#pragma once

#include <string_view>

#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

// Throws lgh::Error(Internal) when `fence` is not signalled within a few minutes; `work` names
// what was waited for in that message.
void waitForFence(const VulkanDevice& device, ::vk::Fence fence, std::string_view work);

}  // namespace lgh::vk
