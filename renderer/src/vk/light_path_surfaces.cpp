#include "vk/light_path_surfaces.hpp"

#include <algorithm>
#include <cstring>

#include <spdlog/spdlog.h>

#include "vk/one_time_commands.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

// Never empty: a buffer of 0 bytes cannot be bound.
constexpr ::vk::DeviceSize kMinBytes = 16;

std::array<std::span<const std::byte>, LightPathSurfaces::kArrays> arraysOf(
    const LightPathScene& scene) {
  return {scene.vertices,  scene.indices,   scene.geometries,
          scene.instances, scene.materials, scene.albedoTexels};
}

}  // namespace

LightPathSurfaces::LightPathSurfaces(const VulkanDevice& device, const LightPathScene& scene)
    : id_(scene.id) {
  const auto arrays = arraysOf(scene);
  std::array<::vk::DeviceSize, kArrays> offsets{};
  ::vk::DeviceSize total = 0;
  for (std::size_t i = 0; i < kArrays; ++i) {
    offsets[i] = alignUp(total, 16);
    total = offsets[i] + std::max<::vk::DeviceSize>(arrays[i].size(), kMinBytes);
  }
  const DeviceBuffer staging(device, {.size = total,
                                      .usage = ::vk::BufferUsageFlagBits::eTransferSrc,
                                      .memory = MemoryKind::HostVisible});
  buffers_.reserve(kArrays);
  for (std::size_t i = 0; i < kArrays; ++i) {
    if (!arrays[i].empty()) {
      std::memcpy(staging.mapped() + offsets[i], arrays[i].data(), arrays[i].size());
    }
    const ::vk::DeviceSize size = std::max<::vk::DeviceSize>(arrays[i].size(), kMinBytes);
    buffers_.emplace_back(device, BufferSpec{.size = size,
                                             .usage = ::vk::BufferUsageFlagBits::eStorageBuffer |
                                                      ::vk::BufferUsageFlagBits::eTransferDst,
                                             .memory = MemoryKind::DeviceLocal});
    bytes_ += size;
  }
  submitAndWait(device, [&](const ::vk::raii::CommandBuffer& commands) {
    for (std::size_t i = 0; i < kArrays; ++i) {
      if (arrays[i].empty()) continue;
      commands.copyBuffer(staging.handle(), buffers_[i].handle(),
                          ::vk::BufferCopy{.srcOffset = staging.offset() + offsets[i],
                                           .dstOffset = buffers_[i].offset(),
                                           .size = arrays[i].size()});
    }
  });
  spdlog::debug("vulkan: light-path surfaces {} uploaded: {:.1f} MB", id_,
                static_cast<double>(bytes_) / 1e6);
}

std::array<::vk::Buffer, LightPathSurfaces::kArrays> LightPathSurfaces::buffers() const {
  std::array<::vk::Buffer, kArrays> handles{};
  for (std::size_t i = 0; i < kArrays; ++i) handles[i] = buffers_[i].handle();
  return handles;
}

}  // namespace lgh::vk
