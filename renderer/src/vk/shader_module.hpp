// A shader module from the embedded SPIR-V (spirv_shaders.hpp), and a compute pipeline of one.
#pragma once

#include <cstdint>
#include <span>

#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

::vk::raii::ShaderModule createShaderModule(const VulkanDevice& device,
                                            std::span<const std::uint32_t> spirv);

// A compute pipeline of `spirv`'s "main" with `layout`.
::vk::raii::Pipeline createComputePipeline(const VulkanDevice& device, ::vk::PipelineLayout layout,
                                           std::span<const std::uint32_t> spirv);

}  // namespace lgh::vk
