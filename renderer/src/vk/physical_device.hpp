// Which Vulkan device is the GL device: the one whose deviceUUID (VkPhysicalDeviceIDProperties)
// equals the GL context's GL_DEVICE_UUID_EXT, so that the two can share memory and semaphores.
#pragma once

#include <string>

#include "vk/shadow_tracer.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

// "6d657361-3235-2e30-2e37-000000000000": the UUID as 32 hex digits in the usual groups.
std::string uuidText(const DeviceUuid& uuid);

// Throws lgh::Error(Unavailable) naming every device found, with its UUID, when none matches.
::vk::raii::PhysicalDevice choosePhysicalDevice(const ::vk::raii::Instance& instance,
                                                const DeviceUuid& uuid);

}  // namespace lgh::vk
