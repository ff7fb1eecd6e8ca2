// The ray-tracing pipeline path of closest-hit batches: glsl/vk/closest_hit.rgen launched per
// ray, closest_hit.rmiss its miss shader and closest_hit.rchit the closest-hit shader of its one
// triangle hit group.
#include <array>

#include "vk/hit_recorder.hpp"
#include "vk/shader_binding_table.hpp"
#include "vk/shader_module.hpp"
#include "vk/spirv_shaders.hpp"
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

::vk::RayTracingShaderGroupCreateInfoKHR closestHitGroup(std::uint32_t shader) {
  return {.type = ::vk::RayTracingShaderGroupTypeKHR::eTrianglesHitGroup,
          .generalShader = VK_SHADER_UNUSED_KHR,
          .closestHitShader = shader,
          .anyHitShader = VK_SHADER_UNUSED_KHR,
          .intersectionShader = VK_SHADER_UNUSED_KHR};
}

::vk::raii::Pipeline createPipeline(const VulkanDevice& device, const TraceLayout& layout) {
  const ::vk::raii::ShaderModule rayGeneration =
      createShaderModule(device, spirv::closest_hit_rgen());
  const ::vk::raii::ShaderModule miss = createShaderModule(device, spirv::closest_hit_rmiss());
  const ::vk::raii::ShaderModule closestHit =
      createShaderModule(device, spirv::closest_hit_rchit());
  const std::array<::vk::PipelineShaderStageCreateInfo, 3> stages{{
      {.stage = ::vk::ShaderStageFlagBits::eRaygenKHR, .module = *rayGeneration, .pName = "main"},
      {.stage = ::vk::ShaderStageFlagBits::eMissKHR, .module = *miss, .pName = "main"},
      {.stage = ::vk::ShaderStageFlagBits::eClosestHitKHR, .module = *closestHit, .pName = "main"},
  }};
  // In ShaderGroup order (shader_binding_table.hpp): raygen, miss, hit.
  const std::array<::vk::RayTracingShaderGroupCreateInfoKHR, kShaderGroupCount> groups{
      generalGroup(0), generalGroup(1), closestHitGroup(2)};
  return {
      device.device(), nullptr, nullptr,
      ::vk::RayTracingPipelineCreateInfoKHR{.stageCount = static_cast<std::uint32_t>(stages.size()),
                                            .pStages = stages.data(),
                                            .groupCount = static_cast<std::uint32_t>(groups.size()),
                                            .pGroups = groups.data(),
                                            .maxPipelineRayRecursionDepth = 1,
                                            .layout = *layout.pipelineLayout()}};
}

class HitPipelineRecorder final : public HitRecorder {
 public:
  HitPipelineRecorder(const VulkanDevice& device, const TraceLayout& layout)
      : layout_(&layout), pipeline_(createPipeline(device, layout)), table_(device, pipeline_) {}

  ::vk::PipelineStageFlags stage() const override {
    return ::vk::PipelineStageFlagBits::eRayTracingShaderKHR;
  }

  void record(const ::vk::raii::CommandBuffer& commands, ::vk::DescriptorSet set,
              const HitPushConstants& constants) const override {
    commands.bindPipeline(::vk::PipelineBindPoint::eRayTracingKHR, *pipeline_);
    commands.bindDescriptorSets(::vk::PipelineBindPoint::eRayTracingKHR, *layout_->pipelineLayout(),
                                0, set, nullptr);
    layout_->pushConstantsOf(commands, constants);
    commands.traceRaysKHR(table_.rayGeneration(), table_.miss(), table_.hit(), table_.callable(),
                          constants.launchWidth, hitLaunchRows(constants.rayCount), 1);
  }

 private:
  const TraceLayout* layout_;
  ::vk::raii::Pipeline pipeline_;
  ShaderBindingTable table_;
};

}  // namespace

std::unique_ptr<HitRecorder> createHitPipelineRecorder(const VulkanDevice& device,
                                                       const TraceLayout& layout) {
  return std::make_unique<HitPipelineRecorder>(device, layout);
}

}  // namespace lgh::vk
