#include "vk/one_time_commands.hpp"

#include <spdlog/spdlog.h>

#include "lgh/error.hpp"
#include "vk/fence_wait.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {

OneTimeCommands::OneTimeCommands(const VulkanDevice& device, QueueRole role)
    : device_(&device),
      role_(role),
      pool_(
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

OneTimeCommands::~OneTimeCommands() {
  const std::lock_guard lock(mutex_);
  if (!pending_) return;
  try {
    waitForFence(*device_, *fence_, "the acceleration-structure build");
  } catch (const std::exception& error) {
    spdlog::warn("vulkan: a pending acceleration-structure build did not finish: {}", error.what());
  }
}

void OneTimeCommands::retireLocked(const VulkanDevice& device) {
  if (unfinished_) {
    throw Error(ErrorCode::Internal,
                "an earlier acceleration-structure build on this Vulkan device never finished");
  }
  if (!pending_) return;
  unfinished_ = true;
  waitForFence(device, *fence_, "the acceleration-structure build");
  unfinished_ = false;
  pending_ = false;
  const std::function<void()> retired = std::move(retired_);
  retired_ = {};
  if (retired) retired();
}

void OneTimeCommands::retire(const VulkanDevice& device) {
  const std::lock_guard lock(mutex_);
  retireLocked(device);
}

void OneTimeCommands::submit(const VulkanDevice& device, const CommandRecorder& record,
                             std::function<void()> retired) {
  const std::lock_guard lock(mutex_);
  retireLocked(device);
  const ::vk::raii::CommandBuffer& commands = buffers_.front();
  commands.reset();
  commands.begin({.flags = ::vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  record(commands);
  commands.end();
  device.device().resetFences(*fence_);
  device.submit(*commands, *fence_, {}, {}, {}, role_);
  pending_ = true;
  retired_ = std::move(retired);
}

void OneTimeCommands::submitAndWait(const VulkanDevice& device, const CommandRecorder& record) {
  submit(device, record);
  retire(device);
}

void submitAndWait(const VulkanDevice& device, const CommandRecorder& record) {
  device.oneTimeCommands().submitAndWait(device, record);
}

}  // namespace lgh::vk
