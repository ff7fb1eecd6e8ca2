// Records one command buffer, submits it to the tracer's queue and waits for it: the
// acceleration-structure builds, which the caller waits for anyway.
#pragma once

#include <functional>

#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

void submitAndWait(const VulkanDevice& device,
                   const std::function<void(const ::vk::raii::CommandBuffer&)>& record);

}  // namespace lgh::vk
