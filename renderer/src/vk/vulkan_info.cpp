#include "lgh/vulkan_info.hpp"

#define VK_NO_PROTOTYPES
#include <dlfcn.h>
#include <vulkan/vulkan.h>

#include <algorithm>
#include <string_view>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace lgh {
namespace {

std::string versionText(std::uint32_t version) {
  return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(version), VK_API_VERSION_MINOR(version),
                     VK_API_VERSION_PATCH(version));
}

std::string deviceTypeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "cpu";
    default:
      return "other";
  }
}

// The instance and the entry points resolved through it; destroys the instance when it goes.
class Instance {
 public:
  Instance(PFN_vkGetInstanceProcAddr getProcAddr, VkInstance instance)
      : getProcAddr_(getProcAddr), instance_(instance) {}
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;
  ~Instance() {
    auto destroy = function<PFN_vkDestroyInstance>("vkDestroyInstance");
    if (destroy != nullptr) destroy(instance_, nullptr);
  }

  template <typename Function>
  Function function(const char* name) const {
    return reinterpret_cast<Function>(getProcAddr_(instance_, name));
  }
  VkInstance handle() const { return instance_; }

 private:
  PFN_vkGetInstanceProcAddr getProcAddr_;
  VkInstance instance_;
};

std::vector<std::string> extensionNames(const Instance& instance, VkPhysicalDevice device) {
  auto enumerate = instance.function<PFN_vkEnumerateDeviceExtensionProperties>(
      "vkEnumerateDeviceExtensionProperties");
  std::uint32_t count = 0;
  if (enumerate == nullptr || enumerate(device, nullptr, &count, nullptr) != VK_SUCCESS) return {};
  std::vector<VkExtensionProperties> properties(count);
  if (enumerate(device, nullptr, &count, properties.data()) != VK_SUCCESS) return {};
  std::vector<std::string> names;
  names.reserve(count);
  for (const auto& property : properties) names.emplace_back(property.extensionName);
  return names;
}

VulkanDeviceInfo describeDevice(const Instance& instance, VkPhysicalDevice device) {
  VkPhysicalDeviceProperties properties{};
  instance.function<PFN_vkGetPhysicalDeviceProperties>("vkGetPhysicalDeviceProperties")(
      device, &properties);
  const std::vector<std::string> extensions = extensionNames(instance, device);
  const auto has = [&extensions](std::string_view name) {
    return std::find(extensions.begin(), extensions.end(), name) != extensions.end();
  };
  VulkanDeviceInfo info;
  info.name = properties.deviceName;
  info.type = deviceTypeName(properties.deviceType);
  info.apiVersion = versionText(properties.apiVersion);
  info.driverVersion = properties.driverVersion;
  info.vendorId = properties.vendorID;
  info.deviceId = properties.deviceID;
  info.accelerationStructure = has(VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME);
  info.rayQuery = has(VK_KHR_RAY_QUERY_EXTENSION_NAME);
  info.rayTracingPipeline = has(VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME);
  return info;
}

VkInstance createInstance(PFN_vkGetInstanceProcAddr getProcAddr, std::uint32_t apiVersion) {
  auto create = reinterpret_cast<PFN_vkCreateInstance>(getProcAddr(nullptr, "vkCreateInstance"));
  if (create == nullptr) return VK_NULL_HANDLE;
  VkApplicationInfo application{};
  application.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  application.pApplicationName = "lghd";
  application.apiVersion = apiVersion;
  VkInstanceCreateInfo createInfo{};
  createInfo.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  createInfo.pApplicationInfo = &application;
  VkInstance instance = VK_NULL_HANDLE;
  const VkResult result = create(&createInfo, nullptr, &instance);
  return result == VK_SUCCESS ? instance : VK_NULL_HANDLE;
}

void listDevices(const Instance& instance, VulkanInfo& info) {
  auto enumerate = instance.function<PFN_vkEnumeratePhysicalDevices>("vkEnumeratePhysicalDevices");
  std::uint32_t count = 0;
  if (enumerate == nullptr || enumerate(instance.handle(), &count, nullptr) != VK_SUCCESS) {
    info.error = "vkEnumeratePhysicalDevices failed";
    return;
  }
  std::vector<VkPhysicalDevice> devices(count);
  if (enumerate(instance.handle(), &count, devices.data()) != VK_SUCCESS) {
    info.error = "vkEnumeratePhysicalDevices failed";
    return;
  }
  for (VkPhysicalDevice device : devices) info.devices.push_back(describeDevice(instance, device));
  info.available = !info.devices.empty();
  if (!info.available) info.error = "the Vulkan loader found no physical device (no ICD?)";
}

}  // namespace

nlohmann::json VulkanInfo::toJson() const {
  nlohmann::json devicesJson = nlohmann::json::array();
  for (const auto& device : devices) {
    devicesJson.push_back({{"name", device.name},
                           {"type", device.type},
                           {"api_version", device.apiVersion},
                           {"driver_version", device.driverVersion},
                           {"vendor_id", device.vendorId},
                           {"device_id", device.deviceId},
                           {"acceleration_structure", device.accelerationStructure},
                           {"ray_query", device.rayQuery},
                           {"ray_tracing_pipeline", device.rayTracingPipeline}});
  }
  nlohmann::json json = {
      {"available", available},
      {"loader_version", loaderVersion.empty() ? nlohmann::json() : nlohmann::json(loaderVersion)},
      {"devices", devicesJson}};
  if (!error.empty()) json["error"] = error;
  return json;
}

VulkanInfo probeVulkan() {
  VulkanInfo info;
  // Loaded once and never closed: unloading the loader would unload the driver (ICD) with it,
  // and drivers that share code with their GL driver (NVIDIA's) do not survive that mid-process.
  static void* const library = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    info.error = fmt::format("no Vulkan loader: {}", dlerror());
    return info;
  }
  auto getProcAddr =
      reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(library, "vkGetInstanceProcAddr"));
  if (getProcAddr == nullptr) {
    info.error = "libvulkan.so.1 has no vkGetInstanceProcAddr";
    return info;
  }
  std::uint32_t loaderVersion = VK_API_VERSION_1_0;  // loaders before 1.1 lack the query
  auto enumerateVersion = reinterpret_cast<PFN_vkEnumerateInstanceVersion>(
      getProcAddr(nullptr, "vkEnumerateInstanceVersion"));
  if (enumerateVersion != nullptr) enumerateVersion(&loaderVersion);
  info.loaderVersion = versionText(loaderVersion);
  const VkInstance handle = createInstance(getProcAddr, loaderVersion);
  if (handle == VK_NULL_HANDLE) {
    info.error = "vkCreateInstance failed (no Vulkan driver installed?)";
    return info;
  }
  listDevices(Instance(getProcAddr, handle), info);
  for (const auto& device : info.devices) {
    spdlog::info("vulkan: {} ({}), API {}, ray query {}, ray-tracing pipeline {}", device.name,
                 device.type, device.apiVersion, device.rayQuery, device.rayTracingPipeline);
  }
  if (!info.available) spdlog::info("vulkan: unavailable: {}", info.error);
  return info;
}

}  // namespace lgh
