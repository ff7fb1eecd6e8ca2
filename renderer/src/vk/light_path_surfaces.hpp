// The scene's surfaces as the light paths' bounce kernel reads them at hits (shadow_tracer.hpp,
// LightPathScene): the triangles, instances, materials and albedo texels in device-local storage
// buffers, uploaded once through a staging buffer. Built again only for another id.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "vk/device_buffer.hpp"
#include "vk/shadow_tracer.hpp"

namespace lgh::vk {

class VulkanDevice;

class LightPathSurfaces {
 public:
  // In LightPathScene's order: vertices, indices, geometries, instances, materials, albedo.
  static constexpr std::size_t kArrays = 6;

  LightPathSurfaces(const VulkanDevice& device, const LightPathScene& scene);

  std::uint64_t id() const { return id_; }
  std::array<::vk::Buffer, kArrays> buffers() const;
  std::size_t bytes() const { return bytes_; }

 private:
  std::uint64_t id_;
  std::vector<DeviceBuffer> buffers_;
  std::size_t bytes_ = 0;
};

}  // namespace lgh::vk
