#include "vk/one_time_commands.hpp"

#include "lgh/error.hpp"
#include "vk/fence_wait.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {

OneTimeCommands::OneTimeCommands(const VulkanDevice& device)
    : pool_(
          device.device(),
          ::vk::CommandPoolCreateInfo{.flags = ::vk::CommandPoolCreateFlagBits::eTransient |
                                               ::vk::CommandPoolCreateFlagBits::eResetCommandBuffer,
                                      .queueFamilyIndex = device.queueFamily()}),
      buffers_(device.device(),
               ::vk::CommandBufferAllocateInfo{.commandPool = *pool_,
                                               .level = ::vk::CommandBufferLevel::ePrimary,
                                               .commandBufferCount = 1}),
      fence_(device.device(), ::vk::FenceCreateInfo{}),
      timestamps_(device, 2) {}

void OneTimeCommands::submitAndWait(const VulkanDevice& device, const CommandRecorder& record) {
  const std::lock_guard lock(mutex_);
  if (unfinished_) {
    throw Error(ErrorCode::Internal,
                "an earlier acceleration-structure build on this Vulkan device never finished");
  }
  const ::vk::raii::CommandBuffer& commands = buffers_.front();
  commands.reset();
  commands.begin({.flags = ::vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  record(commands);
  commands.end();
  device.device().resetFences(*fence_);
  const ::vk::CommandBuffer handle = *commands;
  device.queue().submit(::vk::SubmitInfo{.commandBufferCount = 1, .pCommandBuffers = &handle},
                        *fence_);
  unfinished_ = true;
  waitForFence(device, *fence_, "the acceleration-structure build");
  unfinished_ = false;
}

void submitAndWait(const VulkanDevice& device, const CommandRecorder& record) {
  device.oneTimeCommands().submitAndWait(device, record);
}

}  // namespace lgh::vk
