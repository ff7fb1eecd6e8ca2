// What Vulkan offers on this machine: the loader's instance version and each physical device's
// name, API and driver versions, and whether it can trace rays. Reported by lghd's /v1/info so that
// an operator sees the Vulkan side of the GPU next to the GL one.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace lgh {

struct VulkanDeviceInfo {
  std::string name;
  std::string type;        // "discrete-gpu", "integrated-gpu", "virtual-gpu", "cpu", "other"
  std::string apiVersion;  // "1.3.289"
  std::uint32_t driverVersion = 0;  // vendor-encoded, as VkPhysicalDeviceProperties gives it
  std::uint32_t vendorId = 0;
  std::uint32_t deviceId = 0;
  bool accelerationStructure = false;  // VK_KHR_acceleration_structure
  bool rayQuery = false;               // VK_KHR_ray_query
  bool rayTracingPipeline = false;     // VK_KHR_ray_tracing_pipeline
};

struct VulkanInfo {
  bool available = false;
  std::string loaderVersion;  // vkEnumerateInstanceVersion, "1.3.239"
  std::vector<VulkanDeviceInfo> devices;
  std::string error;  // why Vulkan is unavailable, when it is

  nlohmann::json toJson() const;
};

// Loads libvulkan.so.1 at run time (no link dependency: machines without Vulkan still run the GL
// renderer), creates a bare instance, lists the physical devices and destroys the instance.
// Never throws: a missing loader or driver is reported in `error`.
VulkanInfo probeVulkan();

}  // namespace lgh
