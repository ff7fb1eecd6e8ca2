#include "vk/vulkan_device.hpp"

#include <algorithm>
#include <array>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "lgh/error.hpp"
#include "vk/acceleration_structure.hpp"
#include "vk/physical_device.hpp"
#include "vk/vulkan_instance.hpp"

namespace lgh::vk {
namespace {

std::uint32_t computeQueueFamily(const ::vk::raii::PhysicalDevice& physical) {
  const auto families = physical.getQueueFamilyProperties();
  for (std::uint32_t i = 0; i < families.size(); ++i) {
    if (families[i].queueFlags & ::vk::QueueFlagBits::eCompute) return i;
  }
  throw Error(ErrorCode::Unavailable, fmt::format("the Vulkan device {} has no queue that computes",
                                                  physical.getProperties().deviceName.data()));
}

// The frames' queue, and a second one for the builds made ahead where the family has it.
std::uint32_t queueCountOf(const ::vk::raii::PhysicalDevice& physical, std::uint32_t family) {
  return std::min(physical.getQueueFamilyProperties()[family].queueCount, 2U);
}

::vk::raii::Device createDevice(const ::vk::raii::PhysicalDevice& physical,
                                const DeviceCapabilities& capabilities, std::uint32_t family) {
  const std::array<float, 2> priorities{1.0F, 1.0F};
  const ::vk::DeviceQueueCreateInfo queue{.queueFamilyIndex = family,
                                          .queueCount = queueCountOf(physical, family),
                                          .pQueuePriorities = priorities.data()};
  FeatureChain features(capabilities.rayQuery, capabilities.rayTracingPipeline);
  features.requestTracerFeatures();
  const std::vector<const char*> extensions = deviceExtensions(capabilities);
  return {physical, ::vk::DeviceCreateInfo{
                        .pNext = &features.head(),
                        .queueCreateInfoCount = 1,
                        .pQueueCreateInfos = &queue,
                        .enabledExtensionCount = static_cast<std::uint32_t>(extensions.size()),
                        .ppEnabledExtensionNames = extensions.data()}};
}

DeviceLimits readLimits(const ::vk::raii::PhysicalDevice& physical, bool pipeline,
                        std::uint32_t family) {
  const auto chain =
      physical.getProperties2<::vk::PhysicalDeviceProperties2,
                              ::vk::PhysicalDeviceAccelerationStructurePropertiesKHR>();
  const auto& core = chain.get<::vk::PhysicalDeviceProperties2>().properties;
  const auto& structures = chain.get<::vk::PhysicalDeviceAccelerationStructurePropertiesKHR>();
  DeviceLimits limits;
  limits.scratchAlignment = structures.minAccelerationStructureScratchOffsetAlignment;
  limits.maxStorageBufferRange = core.limits.maxStorageBufferRange;
  limits.timestamps = physical.getQueueFamilyProperties()[family].timestampValidBits > 0;
  limits.timestampPeriodNs = core.limits.timestampPeriod;
  if (pipeline) {
    // Asked only where the extension is: its structure is not for devices without it.
    const auto tracing = physical
                             .getProperties2<::vk::PhysicalDeviceProperties2,
                                             ::vk::PhysicalDeviceRayTracingPipelinePropertiesKHR>()
                             .get<::vk::PhysicalDeviceRayTracingPipelinePropertiesKHR>();
    limits.shaderGroupHandleSize = tracing.shaderGroupHandleSize;
    limits.shaderGroupHandleAlignment = tracing.shaderGroupHandleAlignment;
    limits.shaderGroupBaseAlignment = tracing.shaderGroupBaseAlignment;
  }
  return limits;
}

std::string versionText(std::uint32_t version) {
  return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(version), VK_API_VERSION_MINOR(version),
                     VK_API_VERSION_PATCH(version));
}

TracerInfo describe(const ::vk::raii::PhysicalDevice& physical,
                    const DeviceCapabilities& capabilities) {
  const auto chain =
      physical
          .getProperties2<::vk::PhysicalDeviceProperties2, ::vk::PhysicalDeviceDriverProperties>();
  const auto& core = chain.get<::vk::PhysicalDeviceProperties2>().properties;
  const auto& driver = chain.get<::vk::PhysicalDeviceDriverProperties>();
  TracerInfo info;
  info.deviceName = core.deviceName.data();
  info.driverName = fmt::format("{} {}", driver.driverName.data(), driver.driverInfo.data());
  info.apiVersion = versionText(core.apiVersion);
  info.rayQuery = capabilities.rayQuery;
  info.rayTracingPipeline = capabilities.rayTracingPipeline;
  info.externalMemoryFd = capabilities.externalMemoryFd;
  info.externalSemaphoreFd = capabilities.externalSemaphoreFd;
  return info;
}

}  // namespace

std::shared_ptr<VulkanDevice> VulkanDevice::create(const DeviceUuid& uuid) {
  ::vk::raii::Instance instance = createInstance();
  ::vk::raii::PhysicalDevice physical = choosePhysicalDevice(instance, uuid);
  return std::shared_ptr<VulkanDevice>(new VulkanDevice(std::move(instance), std::move(physical)));
}

VulkanDevice::VulkanDevice(::vk::raii::Instance instance, ::vk::raii::PhysicalDevice physical)
    : instance_(std::move(instance)),
      physical_(std::move(physical)),
      capabilities_(probeCapabilities(physical_)),
      queueFamily_(computeQueueFamily(physical_)),
      device_(createDevice(physical_, capabilities_, queueFamily_)),
      queue_(device_, queueFamily_, 0),
      buildQueue_(queueCountOf(physical_, queueFamily_) > 1
                      ? std::optional<::vk::raii::Queue>(std::in_place, device_, queueFamily_, 1)
                      : std::nullopt),
      limits_(readLimits(physical_, capabilities_.rayTracingPipeline, queueFamily_)),
      memory_(physical_.getMemoryProperties()),
      info_(describe(physical_, capabilities_)),
      structureStorage_(RecycledBuffers::create(*this, accelerationStorage(0))),
      oneTimeCommands_(std::make_unique<OneTimeCommands>(*this, QueueRole::Frames)),
      deferredRelease_(std::make_unique<DeferredRelease>(*this)) {
  for (std::size_t i = 0; i < kAheadBuilders; ++i) {
    aheadCommands_.push_back(std::make_unique<OneTimeCommands>(*this, QueueRole::BuildsAhead));
    idleAheadCommands_.push_back(aheadCommands_.back().get());
  }
  spdlog::info("vulkan: builds made ahead go to {}",
               buildQueue_ ? "a queue of their own" : "the frames' queue (the family has one)");
}

VulkanDevice::AheadLease VulkanDevice::leaseAheadCommands() const {
  std::unique_lock lock(aheadMutex_);
  aheadReturned_.wait(lock, [&] { return !idleAheadCommands_.empty(); });
  OneTimeCommands* commands = idleAheadCommands_.back();
  idleAheadCommands_.pop_back();
  return {*this, *commands};
}

VulkanDevice::AheadLease::~AheadLease() {
  {
    const std::lock_guard lock(device_->aheadMutex_);
    device_->idleAheadCommands_.push_back(commands_);
  }
  device_->aheadReturned_.notify_one();
}

void VulkanDevice::submit(const ::vk::SubmitInfo& info, ::vk::Fence fence, QueueRole role) const {
  if (role == QueueRole::BuildsAhead && buildQueue_) {
    const std::lock_guard lock(buildQueueMutex_);
    buildQueue_->submit(info, fence);
    return;
  }
  const std::lock_guard lock(queueMutex_);
  queue_.submit(info, fence);
}

void VulkanDevice::submit(::vk::CommandBuffer commands, ::vk::Fence fence, ::vk::Semaphore wait,
                          ::vk::PipelineStageFlags waitStage, ::vk::Semaphore signal,
                          QueueRole role) const {
  const bool waits = static_cast<bool>(wait);
  const bool signals = static_cast<bool>(signal);
  submit(::vk::SubmitInfo{.waitSemaphoreCount = waits ? 1U : 0U,
                          .pWaitSemaphores = waits ? &wait : nullptr,
                          .pWaitDstStageMask = waits ? &waitStage : nullptr,
                          .commandBufferCount = 1,
                          .pCommandBuffers = &commands,
                          .signalSemaphoreCount = signals ? 1U : 0U,
                          .pSignalSemaphores = signals ? &signal : nullptr},
         fence, role);
}

void VulkanDevice::waitIdle() const {
  // vkDeviceWaitIdle asks for every queue of the device to be externally synchronised.
  const std::scoped_lock lock(queueMutex_, buildQueueMutex_);
  device_.waitIdle();
}

void VulkanDevice::waitIdleNoThrow() const noexcept {
  try {
    waitIdle();
  } catch (const ::vk::SystemError& error) {
    spdlog::warn("vulkan: waiting for the device failed: {}", error.what());
  }
}

}  // namespace lgh::vk
