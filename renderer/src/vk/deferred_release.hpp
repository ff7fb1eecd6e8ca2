// Objects the GPU may still be using when their owner lets go of them: a scene's acceleration
// structures, evicted from the scene cache while a trace that reads them is still in flight. They
// are kept until the queue has finished everything submitted before their release, then destroyed.
// A release submits no work, only an empty batch with a fence, which signals once all work
// submitted before it is done; nobody waits for it. Waiting for the whole device instead, as a
// scene's destructor did, drained every frame in flight each time a thumbnail batch with the
// scene cache off moved on to its next asset.
#pragma once

#include <cstddef>
#include <deque>
#include <memory>
#include <mutex>
#include <vector>

#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

class DeferredRelease {
 public:
  // Releases not yet known to be done beyond this many: the oldest is waited for.
  static constexpr std::size_t kMaxPending = 16;

  // `device` outlives this (VulkanDevice owns it).
  explicit DeferredRelease(const VulkanDevice& device);
  // Waits for what is still pending, then destroys it.
  ~DeferredRelease();
  DeferredRelease(const DeferredRelease&) = delete;
  DeferredRelease& operator=(const DeferredRelease&) = delete;

  // Takes `held` (destroying it when the object is its last owner) once the queue has finished
  // the work submitted so far; destroys what earlier releases held that is done by now. Throws
  // nothing: where the empty submission fails (a lost device), it waits for the device and
  // destroys `held` at once.
  void release(std::shared_ptr<void> held) noexcept;
  // Destroys what is done, without waiting.
  void collect() noexcept;
  // Releases still pending (for tests and logs).
  std::size_t pending() const;

 private:
  struct Pending {
    ::vk::raii::Fence fence;
    std::shared_ptr<void> held;
  };

  ::vk::raii::Fence takeFence();
  void collectLocked(bool waitForOldest) noexcept;

  const VulkanDevice* device_;
  mutable std::mutex mutex_;
  std::deque<Pending> pending_;
  std::vector<::vk::raii::Fence> spareFences_;  // signalled fences, reset before reuse
};

}  // namespace lgh::vk
