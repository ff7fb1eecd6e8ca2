// The shader binding table of a ray-tracing pipeline: one record each for the raygen group, the
// miss group and the hit group (empty for shadow rays, which skip closest hits on opaque
// geometry; a closest-hit shader for closest-hit batches), each region starting at
// shaderGroupBaseAlignment and each record shaderGroupHandleAlignment apart.
#pragma once

#include "vk/device_buffer.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

// The pipeline's shader groups, in this order.
enum class ShaderGroup : std::uint32_t { RayGeneration = 0, Miss = 1, Hit = 2 };
inline constexpr std::uint32_t kShaderGroupCount = 3;

class ShaderBindingTable {
 public:
  ShaderBindingTable(const VulkanDevice& device, const ::vk::raii::Pipeline& pipeline);

  const ::vk::StridedDeviceAddressRegionKHR& rayGeneration() const { return rayGeneration_; }
  const ::vk::StridedDeviceAddressRegionKHR& miss() const { return miss_; }
  const ::vk::StridedDeviceAddressRegionKHR& hit() const { return hit_; }
  const ::vk::StridedDeviceAddressRegionKHR& callable() const { return callable_; }

 private:
  DeviceBuffer buffer_;
  ::vk::StridedDeviceAddressRegionKHR rayGeneration_;
  ::vk::StridedDeviceAddressRegionKHR miss_;
  ::vk::StridedDeviceAddressRegionKHR hit_;
  ::vk::StridedDeviceAddressRegionKHR callable_{};  // none
};

}  // namespace lgh::vk
