// The ray-query path of closest-hit batches: glsl/vk/closest_hit_query.comp, 64 rays per work
// group along a row of the launch, one row of work groups per launch row.
#include "vk/hit_recorder.hpp"
#include "vk/shader_module.hpp"
#include "vk/spirv_shaders.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

constexpr std::uint32_t kGroupSize = 64;  // local_size_x in the shader

class HitQueryRecorder final : public HitRecorder {
 public:
  HitQueryRecorder(const VulkanDevice& device, const TraceLayout& layout)
      : layout_(&layout), pipeline_(createPipeline(device, layout)) {}

  ::vk::PipelineStageFlags stage() const override {
    return ::vk::PipelineStageFlagBits::eComputeShader;
  }

  void record(const ::vk::raii::CommandBuffer& commands, ::vk::DescriptorSet set,
              const HitPushConstants& constants) const override {
    commands.bindPipeline(::vk::PipelineBindPoint::eCompute, *pipeline_);
    commands.bindDescriptorSets(::vk::PipelineBindPoint::eCompute, *layout_->pipelineLayout(), 0,
                                set, nullptr);
    layout_->pushConstantsOf(commands, constants);
    commands.dispatch((constants.launchWidth + kGroupSize - 1) / kGroupSize,
                      hitLaunchRows(constants.rayCount), 1);
  }

 private:
  static ::vk::raii::Pipeline createPipeline(const VulkanDevice& device,
                                             const TraceLayout& layout) {
    const ::vk::raii::ShaderModule shader =
        createShaderModule(device, spirv::closest_hit_query_comp());
    return {device.device(), nullptr,
            ::vk::ComputePipelineCreateInfo{.stage = {.stage = ::vk::ShaderStageFlagBits::eCompute,
                                                      .module = *shader,
                                                      .pName = "main"},
                                            .layout = *layout.pipelineLayout()}};
  }

  const TraceLayout* layout_;
  ::vk::raii::Pipeline pipeline_;
};

}  // namespace

std::unique_ptr<HitRecorder> createHitQueryRecorder(const VulkanDevice& device,
                                                    const TraceLayout& layout) {
  return std::make_unique<HitQueryRecorder>(device, layout);
}

}  // namespace lgh::vk
