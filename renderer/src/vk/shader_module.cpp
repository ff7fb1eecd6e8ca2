#include "vk/shader_module.hpp"

#include "vk/vulkan_device.hpp"

namespace lgh::vk {

::vk::raii::ShaderModule createShaderModule(const VulkanDevice& device,
                                            std::span<const std::uint32_t> spirv) {
  return {device.device(),
          ::vk::ShaderModuleCreateInfo{.codeSize = spirv.size_bytes(), .pCode = spirv.data()}};
}

}  // namespace lgh::vk
