// The ray-tracing pipeline path: the program's raygen shader launched once per ray or pixel, its
// miss shader the only miss shader, and one triangle hit group, empty (glsl/vk/shadow_ray.rgen,
// .rmiss) or with the closest-hit shader (glsl/vk/closest_hit.rgen, .rmiss, .rchit).
#include <array>
#include <vector>

#include "vk/shader_binding_table.hpp"
#include "vk/shader_module.hpp"
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

// `closestHit`: the stage of the closest-hit shader, or VK_SHADER_UNUSED_KHR for an empty group.
::vk::RayTracingShaderGroupCreateInfoKHR hitGroup(std::uint32_t closestHit) {
  return {.type = ::vk::RayTracingShaderGroupTypeKHR::eTrianglesHitGroup,
          .generalShader = VK_SHADER_UNUSED_KHR,
          .closestHitShader = closestHit,
          .anyHitShader = VK_SHADER_UNUSED_KHR,
          .intersectionShader = VK_SHADER_UNUSED_KHR};
}

::vk::raii::Pipeline createPipeline(const VulkanDevice& device, const TraceLayout& layout,
                                    const PipelineProgram& program) {
  const ::vk::raii::ShaderModule rayGeneration = createShaderModule(device, program.rayGeneration);
  const ::vk::raii::ShaderModule miss = createShaderModule(device, program.miss);
  std::vector<::vk::PipelineShaderStageCreateInfo> stages{
      {.stage = ::vk::ShaderStageFlagBits::eRaygenKHR, .module = *rayGeneration, .pName = "main"},
      {.stage = ::vk::ShaderStageFlagBits::eMissKHR, .module = *miss, .pName = "main"},
  };
  std::uint32_t closestHitStage = VK_SHADER_UNUSED_KHR;
  ::vk::raii::ShaderModule closestHit = nullptr;
  if (!program.closestHit.empty()) {
    closestHit = createShaderModule(device, program.closestHit);
    closestHitStage = static_cast<std::uint32_t>(stages.size());
    stages.push_back({.stage = ::vk::ShaderStageFlagBits::eClosestHitKHR,
                      .module = *closestHit,
                      .pName = "main"});
  }
  // In ShaderGroup order (shader_binding_table.hpp): raygen, miss, hit.
  const std::array<::vk::RayTracingShaderGroupCreateInfoKHR, kShaderGroupCount> groups{
      generalGroup(0), generalGroup(1), hitGroup(closestHitStage)};
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
  RayTracingPipelineRecorder(const VulkanDevice& device, const TraceLayout& layout,
                             const PipelineProgram& program)
      : layout_(&layout),
        pipeline_(createPipeline(device, layout, program)),
        table_(device, pipeline_) {}

  ::vk::PipelineStageFlags stage() const override {
    return ::vk::PipelineStageFlagBits::eRayTracingShaderKHR;
  }

  void record(const ::vk::raii::CommandBuffer& commands, ::vk::DescriptorSet set,
              std::span<const std::byte> constants, TraceLaunch launch) const override {
    commands.bindPipeline(::vk::PipelineBindPoint::eRayTracingKHR, *pipeline_);
    commands.bindDescriptorSets(::vk::PipelineBindPoint::eRayTracingKHR, *layout_->pipelineLayout(),
                                0, set, nullptr);
    layout_->pushConstants(commands, constants);
    commands.traceRaysKHR(table_.rayGeneration(), table_.miss(), table_.hit(), table_.callable(),
                          launch.width, launch.height, 1);
  }

 private:
  const TraceLayout* layout_;
  ::vk::raii::Pipeline pipeline_;
  ShaderBindingTable table_;
};

}  // namespace

std::unique_ptr<TraceRecorder> createRayTracingPipelineRecorder(const VulkanDevice& device,
                                                                const TraceLayout& layout,
                                                                const PipelineProgram& program) {
  return std::make_unique<RayTracingPipelineRecorder>(device, layout, program);
}

}  // namespace lgh::vk
