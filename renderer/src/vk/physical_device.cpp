#include "vk/physical_device.hpp"

#include <algorithm>
#include <vector>

#include <fmt/format.h>

#include "lgh/error.hpp"

namespace lgh::vk {
namespace {

struct DeviceIdentity {
  std::string name;
  DeviceUuid uuid{};
};

DeviceIdentity identify(const ::vk::raii::PhysicalDevice& device) {
  const auto chain =
      device.getProperties2<::vk::PhysicalDeviceProperties2, ::vk::PhysicalDeviceIDProperties>();
  DeviceIdentity identity;
  identity.name = chain.get<::vk::PhysicalDeviceProperties2>().properties.deviceName.data();
  const auto& uuid = chain.get<::vk::PhysicalDeviceIDProperties>().deviceUUID;
  std::copy(uuid.begin(), uuid.end(), identity.uuid.begin());
  return identity;
}

std::string listDevices(const std::vector<DeviceIdentity>& found) {
  if (found.empty()) return "the Vulkan loader found no device (no driver installed?)";
  std::string list;
  for (const DeviceIdentity& device : found) {
    list += fmt::format("{}{} ({})", list.empty() ? "found " : "; ", device.name,
                        uuidText(device.uuid));
  }
  return list;
}

}  // namespace

std::string uuidText(const DeviceUuid& uuid) {
  std::string text;
  for (std::size_t i = 0; i < uuid.size(); ++i) {
    if (i == 4 || i == 6 || i == 8 || i == 10) text += '-';
    text += fmt::format("{:02x}", uuid[i]);
  }
  return text;
}

::vk::raii::PhysicalDevice choosePhysicalDevice(const ::vk::raii::Instance& instance,
                                                const DeviceUuid& uuid) {
  ::vk::raii::PhysicalDevices devices(instance);
  std::vector<DeviceIdentity> found;
  for (::vk::raii::PhysicalDevice& device : devices) {
    found.push_back(identify(device));
    if (found.back().uuid == uuid) return std::move(device);
  }
  throw Error(ErrorCode::Unavailable, fmt::format("no Vulkan device is the GL device (UUID {}): {}",
                                                  uuidText(uuid), listDevices(found)));
}

}  // namespace lgh::vk
