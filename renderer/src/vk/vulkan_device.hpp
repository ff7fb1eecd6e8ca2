// The tracer's Vulkan device: the instance, the physical device that is the GL device, a logical
// device with acceleration structures and every tracing path it offers, one queue that computes,
// and the limits the rest of the tracer aligns to. Shared (std::shared_ptr) by the tracer and the
// TraceScenes it built, so that either may go first. The render thread traces on it while a
// prefetch thread may build a scene's acceleration structures (ShadowTracer::sceneBuilder): each
// queue is submitted to under a lock (submit), and builds take their one-time commands'
// buildLock() for their whole run. Builds made ahead go to a queue of their own where the family
// has a second one (QueueRole).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "vk/deferred_release.hpp"
#include "vk/device_capabilities.hpp"
#include "vk/one_time_commands.hpp"
#include "vk/queue_role.hpp"
#include "vk/recycled_buffers.hpp"
#include "vk/shadow_tracer.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

struct DeviceLimits {
  ::vk::DeviceSize scratchAlignment = 1;  // minAccelerationStructureScratchOffsetAlignment
  ::vk::DeviceSize maxStorageBufferRange = 0;
  std::uint32_t shaderGroupHandleSize = 0;  // the ray-tracing pipeline's, when it has one
  std::uint32_t shaderGroupHandleAlignment = 1;
  std::uint32_t shaderGroupBaseAlignment = 1;
  bool timestamps = false;         // the queue writes timestamps
  double timestampPeriodNs = 0.0;  // nanoseconds per timestamp tick
};

class VulkanDevice {
 public:
  // Throws lgh::Error(Unavailable) when there is no loader, no driver, no device with `uuid` or
  // no way to trace on it; vk::SystemError on a failing call.
  static std::shared_ptr<VulkanDevice> create(const DeviceUuid& uuid);

  VulkanDevice(const VulkanDevice&) = delete;
  VulkanDevice& operator=(const VulkanDevice&) = delete;

  const ::vk::raii::Device& device() const { return device_; }
  // The frames' queue, for what needs it besides submissions; submit to it with submit().
  const ::vk::raii::Queue& queue() const { return queue_; }
  // vkQueueSubmit under the queue's lock: the queues are shared by threads.
  void submit(const ::vk::SubmitInfo& info, ::vk::Fence fence,
              QueueRole role = QueueRole::Frames) const;
  // One command buffer, waiting on `wait` at `waitStage` and signalling `signal` where given
  // (null semaphores: none), signalling `fence` when done.
  void submit(::vk::CommandBuffer commands, ::vk::Fence fence, ::vk::Semaphore wait = {},
              ::vk::PipelineStageFlags waitStage = {}, ::vk::Semaphore signal = {},
              QueueRole role = QueueRole::Frames) const;
  std::uint32_t queueFamily() const { return queueFamily_; }
  const DeviceCapabilities& capabilities() const { return capabilities_; }
  const DeviceLimits& limits() const { return limits_; }
  const ::vk::PhysicalDeviceMemoryProperties& memory() const { return memory_; }
  // Device name, driver and API version, and the capabilities (createMs left to the tracer).
  const TracerInfo& info() const { return info_; }

  // The reused command buffer of the frames' queue: the render thread's builds, and the uploads
  // that are waited for (submitAndWait).
  OneTimeCommands& oneTimeCommands() const { return *oneTimeCommands_; }

  // One of the one-time commands of the builds made ahead (QueueRole::BuildsAhead), held from the
  // build's start to the wait for its GPU work: up to kAheadBuilders builds run side by side, each
  // with its own command buffer, fence and transient buffers (with one set they waited for one
  // another, a fence round trip each: turns of 3.7 ms on average, up to 23 ms, on the H200
  // machine).
  static constexpr std::size_t kAheadBuilders = 4;
  class AheadLease {
   public:
    AheadLease(const VulkanDevice& device, OneTimeCommands& commands)
        : device_(&device), commands_(&commands) {}
    ~AheadLease();
    AheadLease(const AheadLease&) = delete;
    AheadLease& operator=(const AheadLease&) = delete;
    OneTimeCommands& commands() const { return *commands_; }

   private:
    const VulkanDevice* device_;
    OneTimeCommands* commands_;
  };
  // Waits while all of them are held.
  AheadLease leaseAheadCommands() const;

  // Where small scenes' acceleration structures live: storage buffers kept across scenes
  // (vk/recycled_buffers.hpp).
  RecycledBuffers& structureStorage() const { return *structureStorage_; }

  // Holds objects until the work submitted so far is done (vk/deferred_release.hpp).
  DeferredRelease& deferredRelease() const { return *deferredRelease_; }

  // Waits for the queues to finish (under their locks). Throws vk::SystemError when the device
  // is lost.
  void waitIdle() const;
  // The same for destructors, so it throws nothing (a lost device has nothing left to wait for).
  void waitIdleNoThrow() const noexcept;

 private:
  VulkanDevice(::vk::raii::Instance instance, ::vk::raii::PhysicalDevice physical);

  ::vk::raii::Instance instance_;
  ::vk::raii::PhysicalDevice physical_;
  DeviceCapabilities capabilities_;
  std::uint32_t queueFamily_;
  ::vk::raii::Device device_;
  ::vk::raii::Queue queue_;
  std::optional<::vk::raii::Queue> buildQueue_;  // the family's second queue, where it has one
  DeviceLimits limits_;
  ::vk::PhysicalDeviceMemoryProperties memory_;
  TracerInfo info_;
  mutable std::mutex queueMutex_;
  mutable std::mutex buildQueueMutex_;
  // Declared after device_: destroyed before it. The kept structure storage goes after the
  // deferred releases, which give theirs back to it.
  std::shared_ptr<RecycledBuffers> structureStorage_;
  std::unique_ptr<OneTimeCommands> oneTimeCommands_;
  std::vector<std::unique_ptr<OneTimeCommands>> aheadCommands_;
  mutable std::mutex aheadMutex_;
  mutable std::condition_variable aheadReturned_;
  mutable std::vector<OneTimeCommands*> idleAheadCommands_;
  std::unique_ptr<DeferredRelease> deferredRelease_;
};

}  // namespace lgh::vk
