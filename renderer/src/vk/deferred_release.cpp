#include "vk/deferred_release.hpp"

#include <chrono>
#include <cstdint>
#include <utility>

#include <spdlog/spdlog.h>

#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

// As waitForFence's bound: far beyond any batch on a GPU.
constexpr std::uint64_t kWaitNs = std::chrono::nanoseconds(std::chrono::seconds(300)).count();

}  // namespace

DeferredRelease::DeferredRelease(const VulkanDevice& device) : device_(&device) {}

DeferredRelease::~DeferredRelease() {
  const std::lock_guard lock(mutex_);
  try {
    device_->waitIdle();
  } catch (const ::vk::SystemError& error) {
    spdlog::warn("vulkan: waiting for the device before releasing its objects failed: {}",
                 error.what());
  }
  pending_.clear();
}

::vk::raii::Fence DeferredRelease::takeFence() {
  if (spareFences_.empty()) return {device_->device(), ::vk::FenceCreateInfo{}};
  ::vk::raii::Fence fence = std::move(spareFences_.back());
  spareFences_.pop_back();
  device_->device().resetFences(*fence);
  return fence;
}

void DeferredRelease::release(std::shared_ptr<void> held) noexcept {
  const std::lock_guard lock(mutex_);
  try {
    ::vk::raii::Fence fence = takeFence();
    device_->submit(::vk::SubmitInfo{}, *fence);
    pending_.push_back({std::move(fence), std::move(held)});
  } catch (const ::vk::SystemError& error) {
    spdlog::warn("vulkan: a deferred release could not be submitted ({}): waiting for the device",
                 error.what());
    try {
      device_->waitIdle();
    } catch (const ::vk::SystemError&) {
      // A lost device runs nothing any more: what it held can go.
    }
    held.reset();
  }
  collectLocked(pending_.size() > kMaxPending);
}

void DeferredRelease::collect() noexcept {
  const std::lock_guard lock(mutex_);
  collectLocked(false);
}

std::size_t DeferredRelease::pending() const {
  const std::lock_guard lock(mutex_);
  return pending_.size();
}

// Releases finish in submission order: the first one not done ends the sweep.
void DeferredRelease::collectLocked(bool waitForOldest) noexcept {
  while (!pending_.empty()) {
    Pending& oldest = pending_.front();
    ::vk::Result status = ::vk::Result::eNotReady;
    try {
      status = waitForOldest ? device_->device().waitForFences(*oldest.fence, VK_TRUE, kWaitNs)
                             : oldest.fence.getStatus();
    } catch (const ::vk::SystemError& error) {
      // The device is lost: nothing runs on it any more.
      spdlog::warn("vulkan: a deferred release's fence failed ({}): releasing", error.what());
      status = ::vk::Result::eSuccess;
    }
    waitForOldest = false;
    if (status != ::vk::Result::eSuccess) return;
    oldest.held.reset();
    spareFences_.push_back(std::move(oldest.fence));
    pending_.pop_front();
  }
}

}  // namespace lgh::vk
