// What the chosen physical device offers the shadow tracer, from its extensions and features,
// and the extensions and feature structures that enable exactly that on a logical device.
#pragma once

#include <vector>

#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

struct DeviceCapabilities {
  bool rayQuery = false;             // VK_KHR_ray_query + rayQuery
  bool rayTracingPipeline = false;   // VK_KHR_ray_tracing_pipeline + rayTracingPipeline
  bool externalMemoryFd = false;     // VK_KHR_external_memory_fd, storage buffers exportable
  bool externalSemaphoreFd = false;  // VK_KHR_external_semaphore_fd, semaphores exportable
};

// Throws lgh::Error(Unavailable) saying what is missing when the device lacks API 1.2,
// bufferDeviceAddress, acceleration structures (with deferred host operations) or any tracing
// path.
DeviceCapabilities probeCapabilities(const ::vk::raii::PhysicalDevice& device);

std::vector<const char*> deviceExtensions(const DeviceCapabilities& capabilities);

// The feature structures of the tracer, chained from a VkPhysicalDeviceFeatures2 (the chain
// points into the object, so it neither copies nor moves): the Vulkan 1.2 features, acceleration
// structures, and ray query and the ray-tracing pipeline when asked for.
class FeatureChain {
 public:
  FeatureChain(bool rayQuery, bool rayTracingPipeline);
  FeatureChain(const FeatureChain&) = delete;
  FeatureChain& operator=(const FeatureChain&) = delete;

  // Fills every structure of the chain with what `device` supports.
  void queryFrom(const ::vk::raii::PhysicalDevice& device);
  // Clears every feature and sets those the tracer uses (the tracing paths in the chain).
  void requestTracerFeatures();

  const ::vk::PhysicalDeviceFeatures2& head() const { return features_; }
  bool bufferDeviceAddress() const { return vulkan12_.bufferDeviceAddress == VK_TRUE; }
  bool accelerationStructure() const {
    return accelerationStructure_.accelerationStructure == VK_TRUE;
  }
  bool rayQuery() const { return rayQuery_.rayQuery == VK_TRUE; }
  bool rayTracingPipeline() const { return pipeline_.rayTracingPipeline == VK_TRUE; }

 private:
  void link();

  bool withRayQuery_;
  bool withPipeline_;
  ::vk::PhysicalDeviceFeatures2 features_{};
  ::vk::PhysicalDeviceVulkan12Features vulkan12_{};
  ::vk::PhysicalDeviceAccelerationStructureFeaturesKHR accelerationStructure_{};
  ::vk::PhysicalDeviceRayQueryFeaturesKHR rayQuery_{};
  ::vk::PhysicalDeviceRayTracingPipelineFeaturesKHR pipeline_{};
};

}  // namespace lgh::vk
