#include "vk/shader_module.hpp"

#include "vk/vulkan_device.hpp"

namespace lgh::vk {

::vk::raii::ShaderModule createShaderModule(const VulkanDevice& device,
                                            std::span<const std::uint32_t> spirv) {
  return {device.device(),
          ::vk::ShaderModuleCreateInfo{.codeSize = spirv.size_bytes(), .pCode = spirv.data()}};
}

::vk::raii::Pipeline createComputePipeline(const VulkanDevice& device, ::vk::PipelineLayout layout,
                                           std::span<const std::uint32_t> spirv) {
  const ::vk::raii::ShaderModule shader = createShaderModule(device, spirv);
  return {device.device(), nullptr,
          ::vk::ComputePipelineCreateInfo{.stage = {.stage = ::vk::ShaderStageFlagBits::eCompute,
                                                    .module = *shader,
                                                    .pName = "main"},
                                          .layout = layout}};
}

}  // namespace lgh::vk
