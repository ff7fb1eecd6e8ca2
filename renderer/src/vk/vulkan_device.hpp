// The tracer's Vulkan device: the instance, the physical device that is the GL device, a logical
// device with acceleration structures and every tracing path it offers, one queue that computes,
// and the limits the rest of the tracer aligns to. Shared (std::shared_ptr) by the tracer and the
// TraceScenes it built, so that either may go first.
#pragma once

#include <cstdint>
#include <memory>

#include "vk/deferred_release.hpp"
#include "vk/device_capabilities.hpp"
#include "vk/one_time_commands.hpp"
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
  const ::vk::raii::Queue& queue() const { return queue_; }
  std::uint32_t queueFamily() const { return queueFamily_; }
  const DeviceCapabilities& capabilities() const { return capabilities_; }
  const DeviceLimits& limits() const { return limits_; }
  const ::vk::PhysicalDeviceMemoryProperties& memory() const { return memory_; }
  // Device name, driver and API version, and the capabilities (createMs left to the tracer).
  const TracerInfo& info() const { return info_; }

  // The reused command buffer of the builds and uploads that are waited for (submitAndWait).
  OneTimeCommands& oneTimeCommands() const { return *oneTimeCommands_; }

  // Holds objects until the work submitted so far is done (vk/deferred_release.hpp).
  DeferredRelease& deferredRelease() const { return *deferredRelease_; }

  // Waits for the queue to finish; for destructors, so it throws nothing (a lost device has
  // nothing left to wait for).
  void waitIdleNoThrow() const noexcept;

 private:
  VulkanDevice(::vk::raii::Instance instance, ::vk::raii::PhysicalDevice physical);

  ::vk::raii::Instance instance_;
  ::vk::raii::PhysicalDevice physical_;
  DeviceCapabilities capabilities_;
  std::uint32_t queueFamily_;
  ::vk::raii::Device device_;
  ::vk::raii::Queue queue_;
  DeviceLimits limits_;
  ::vk::PhysicalDeviceMemoryProperties memory_;
  TracerInfo info_;
  // Declared after device_: destroyed before it.
  std::unique_ptr<OneTimeCommands> oneTimeCommands_;
  std::unique_ptr<DeferredRelease> deferredRelease_;
};

}  // namespace lgh::vk
