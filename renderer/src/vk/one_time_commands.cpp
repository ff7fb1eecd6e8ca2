#include "vk/one_time_commands.hpp"

#include "vk/fence_wait.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {

void submitAndWait(const VulkanDevice& device,
                   const std::function<void(const ::vk::raii::CommandBuffer&)>& record) {
  const ::vk::raii::CommandPool pool(
      device.device(),
      ::vk::CommandPoolCreateInfo{.flags = ::vk::CommandPoolCreateFlagBits::eTransient,
                                  .queueFamilyIndex = device.queueFamily()});
  ::vk::raii::CommandBuffers buffers(
      device.device(), ::vk::CommandBufferAllocateInfo{.commandPool = *pool,
                                                       .level = ::vk::CommandBufferLevel::ePrimary,
                                                       .commandBufferCount = 1});
  const ::vk::raii::CommandBuffer& commands = buffers.front();
  commands.begin({.flags = ::vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  record(commands);
  commands.end();
  const ::vk::raii::Fence fence(device.device(), ::vk::FenceCreateInfo{});
  const ::vk::CommandBuffer handle = *commands;
  device.queue().submit(::vk::SubmitInfo{.commandBufferCount = 1, .pCommandBuffers = &handle},
                        *fence);
  waitForFence(device, *fence, "the acceleration-structure build");
}

}  // namespace lgh::vk
