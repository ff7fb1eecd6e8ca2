// The ray-tracing pipeline path: glsl/vk/shadow_ray.rgen launched once per pixel, with
// shadow_ray.rmiss as its only miss shader and an empty hit group.
#include <array>

#include "vk/shader_binding_table.hpp"
#include "vk/shader_module.hpp"
#include "vk/spirv_shaders.hpp"
#include "vk/trace_recorder.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

::vk::RayTracingShaderGroupCreateInfoKHR generalGroup(std::uint32_t shader) {
  return {.type = ::vk::RayTracingShaderGroupTypeKHR::eGeneral,
          .generalShader = shader,
          .closestHitShader = VK_SHADER_UNUSED_KHR,
          .anyHitShader = VK_SHADER_UNUSED_KHR,
          .intersectionShader = VK_SHADER_UNUSED_KHR};
}

::vk::RayTracingShaderGroupCreateInfoKHR emptyHitGroup() {
  return {.type = ::vk::RayTracingShaderGroupTypeKHR::eTrianglesHitGroup,
          .generalShader = VK_SHADER_UNUSED_KHR,
          .closestHitShader = VK_SHADER_UNUSED_KHR,
          .anyHitShader = VK_SHADER_UNUSED_KHR,
          .intersectionShader = VK_SHADER_UNUSED_KHR};
}

::vk::raii::Pipeline createPipeline(const VulkanDevice& device, const TraceLayout& layout) {
  const ::vk::raii::ShaderModule rayGeneration =
      createShaderModule(device, spirv::shadow_ray_rgen());
  const ::vk::raii::ShaderModule miss = createShaderModule(device, spirv::shadow_ray_rmiss());
  const std::array<::vk::PipelineShaderStageCreateInfo, 2> stages{{
      {.stage = ::vk::ShaderStageFlagBits::eRaygenKHR, .module = *rayGeneration, .pName = "main"},
      {.stage = ::vk::ShaderStageFlagBits::eMissKHR, .module = *miss, .pName = "main"},
  }};
  // In ShaderGroup order.
  const std::array<::vk::RayTracingShaderGroupCreateInfoKHR, kShaderGroupCount> groups{
      generalGroup(0), generalGroup(1), emptyHitGroup()};
  return {
      device.device(), nullptr, nullptr,
      ::vk::RayTracingPipelineCreateInfoKHR{.stageCount = static_cast<std::uint32_t>(stages.size()),
                                            .pStages = stages.data(),
                                            .groupCount = static_cast<std::uint32_t>(groups.size()),
                                            .pGroups = groups.data(),
                                            .maxPipelineRayRecursionDepth = 1,
                                            .layout = *layout.pipelineLayout()}};
}

class RayTracingPipelineRecorder final : public TraceRecorder {
 public:
  RayTracingPipelineRecorder(const VulkanDevice& device, const TraceLayout& layout)
      : layout_(&layout), pipeline_(createPipeline(device, layout)), table_(device, pipeline_) {}

  ::vk::PipelineStageFlags stage() const override {
    return ::vk::PipelineStageFlagBits::eRayTracingShaderKHR;
  }

  void record(const ::vk::raii::CommandBuffer& commands, ::vk::DescriptorSet set,
              const TracePushConstants& constants) const override {
    commands.bindPipeline(::vk::PipelineBindPoint::eRayTracingKHR, *pipeline_);
    commands.bindDescriptorSets(::vk::PipelineBindPoint::eRayTracingKHR, *layout_->pipelineLayout(),
                                0, set, nullptr);
    layout_->pushConstants(commands, constants);
    commands.traceRaysKHR(table_.rayGeneration(), table_.miss(), table_.hit(), table_.callable(),
                          constants.width, constants.height, 1);
  }

 private:
  const TraceLayout* layout_;
  ::vk::raii::Pipeline pipeline_;
  ShaderBindingTable table_;
};

}  // namespace

std::unique_ptr<TraceRecorder> createRayTracingPipelineRecorder(const VulkanDevice& device,
                                                                const TraceLayout& layout) {
  return std::make_unique<RayTracingPipelineRecorder>(device, layout);
}

}  // namespace lgh::vk
