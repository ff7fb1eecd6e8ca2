#include "vk/device_capabilities.hpp"

#include <algorithm>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "lgh/error.hpp"

namespace lgh::vk {
namespace {

class ExtensionList {
 public:
  explicit ExtensionList(const ::vk::raii::PhysicalDevice& device)
      : properties_(device.enumerateDeviceExtensionProperties()) {}
  bool has(std::string_view name) const {
    return std::any_of(properties_.begin(), properties_.end(),
                       [name](const auto& p) { return name == p.extensionName.data(); });
  }

 private:
  std::vector<::vk::ExtensionProperties> properties_;
};

bool storageBuffersExportable(const ::vk::raii::PhysicalDevice& device) {
  const auto properties = device.getExternalBufferProperties(
      {.usage = ::vk::BufferUsageFlagBits::eStorageBuffer,
       .handleType = ::vk::ExternalMemoryHandleTypeFlagBits::eOpaqueFd});
  return static_cast<bool>(properties.externalMemoryProperties.externalMemoryFeatures &
                           ::vk::ExternalMemoryFeatureFlagBits::eExportable);
}

bool semaphoresExportable(const ::vk::raii::PhysicalDevice& device) {
  const auto properties = device.getExternalSemaphoreProperties(
      {.handleType = ::vk::ExternalSemaphoreHandleTypeFlagBits::eOpaqueFd});
  return static_cast<bool>(properties.externalSemaphoreFeatures &
                           ::vk::ExternalSemaphoreFeatureFlagBits::eExportable);
}

[[noreturn]] void unavailable(const ::vk::raii::PhysicalDevice& device, std::string_view why) {
  throw Error(ErrorCode::Unavailable, fmt::format("the Vulkan device {} cannot trace shadows: {}",
                                                  device.getProperties().deviceName.data(), why));
}

void requireBasics(const ::vk::raii::PhysicalDevice& device, const ExtensionList& extensions) {
  const std::uint32_t api = device.getProperties().apiVersion;
  if (api < VK_API_VERSION_1_2) {
    unavailable(device, fmt::format("it offers Vulkan {}.{}, not 1.2", VK_API_VERSION_MAJOR(api),
                                    VK_API_VERSION_MINOR(api)));
  }
  for (const char* name : {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                           VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME}) {
    if (!extensions.has(name)) unavailable(device, fmt::format("no {}", name));
  }
}

// The ray-query shadow shader votes across a subgroup (glsl/vk/shadow_ray_query.comp).
bool computeSubgroupsVote(const ::vk::raii::PhysicalDevice& device) {
  const auto chain = device.getProperties2<::vk::PhysicalDeviceProperties2,
                                           ::vk::PhysicalDeviceSubgroupProperties>();
  const auto& subgroups = chain.get<::vk::PhysicalDeviceSubgroupProperties>();
  return (subgroups.supportedStages & ::vk::ShaderStageFlagBits::eCompute) &&
         (subgroups.supportedOperations & ::vk::SubgroupFeatureFlagBits::eVote);
}

}  // namespace

DeviceCapabilities probeCapabilities(const ::vk::raii::PhysicalDevice& device) {
  const ExtensionList extensions(device);
  requireBasics(device, extensions);
  FeatureChain supported(extensions.has(VK_KHR_RAY_QUERY_EXTENSION_NAME),
                         extensions.has(VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME));
  supported.queryFrom(device);
  if (!supported.bufferDeviceAddress()) unavailable(device, "no bufferDeviceAddress");
  if (!supported.accelerationStructure()) unavailable(device, "no accelerationStructure");
  DeviceCapabilities capabilities;
  capabilities.rayQuery = supported.rayQuery() && computeSubgroupsVote(device);
  capabilities.rayTracingPipeline = supported.rayTracingPipeline();
  if (!capabilities.rayQuery && !capabilities.rayTracingPipeline) {
    unavailable(device, "neither ray queries nor ray-tracing pipelines");
  }
  capabilities.externalMemoryFd =
      extensions.has(VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME) && storageBuffersExportable(device);
  capabilities.externalSemaphoreFd =
      extensions.has(VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME) && semaphoresExportable(device);
  return capabilities;
}

std::vector<const char*> deviceExtensions(const DeviceCapabilities& capabilities) {
  std::vector<const char*> names = {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                                    VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};
  if (capabilities.rayQuery) names.push_back(VK_KHR_RAY_QUERY_EXTENSION_NAME);
  if (capabilities.rayTracingPipeline) names.push_back(VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME);
  if (capabilities.externalMemoryFd) names.push_back(VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME);
  if (capabilities.externalSemaphoreFd) {
    names.push_back(VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME);
  }
  return names;
}

FeatureChain::FeatureChain(bool rayQuery, bool rayTracingPipeline)
    : withRayQuery_(rayQuery), withPipeline_(rayTracingPipeline) {
  link();
}

void FeatureChain::link() {
  features_.pNext = &vulkan12_;
  vulkan12_.pNext = &accelerationStructure_;
  void** tail = &accelerationStructure_.pNext;
  if (withRayQuery_) {
    *tail = &rayQuery_;
    tail = &rayQuery_.pNext;
  }
  if (withPipeline_) {
    *tail = &pipeline_;
    tail = &pipeline_.pNext;
  }
  *tail = nullptr;
}

void FeatureChain::queryFrom(const ::vk::raii::PhysicalDevice& device) {
  // Through the dispatcher: vk::raii's getFeatures2 takes a chain fixed at compile time, and
  // this one holds the tracing paths' structures only where the device has their extensions.
  device.getDispatcher()->vkGetPhysicalDeviceFeatures2(
      static_cast<VkPhysicalDevice>(*device),
      reinterpret_cast<VkPhysicalDeviceFeatures2*>(&features_));
}

void FeatureChain::requestTracerFeatures() {
  features_ = ::vk::PhysicalDeviceFeatures2{};
  vulkan12_ = ::vk::PhysicalDeviceVulkan12Features{.bufferDeviceAddress = VK_TRUE};
  accelerationStructure_ =
      ::vk::PhysicalDeviceAccelerationStructureFeaturesKHR{.accelerationStructure = VK_TRUE};
  rayQuery_ = ::vk::PhysicalDeviceRayQueryFeaturesKHR{.rayQuery = VK_TRUE};
  pipeline_ = ::vk::PhysicalDeviceRayTracingPipelineFeaturesKHR{.rayTracingPipeline = VK_TRUE};
  link();
}

}  // namespace lgh::vk
