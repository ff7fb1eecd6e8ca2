// The ray-query path: glsl/vk/shadow_ray_query.comp, one invocation per pixel in 8 x 8 groups.
#include "vk/shader_module.hpp"
#include "vk/spirv_shaders.hpp"
#include "vk/trace_recorder.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

constexpr std::uint32_t kGroupSize = 8;  // local_size_x and _y in the shader

class RayQueryRecorder final : public TraceRecorder {
 public:
  RayQueryRecorder(const VulkanDevice& device, const TraceLayout& layout)
      : layout_(&layout), pipeline_(createPipeline(device, layout)) {}

  ::vk::PipelineStageFlags stage() const override {
    return ::vk::PipelineStageFlagBits::eComputeShader;
  }

  void record(const ::vk::raii::CommandBuffer& commands, ::vk::DescriptorSet set,
              const TracePushConstants& constants) const override {
    commands.bindPipeline(::vk::PipelineBindPoint::eCompute, *pipeline_);
    commands.bindDescriptorSets(::vk::PipelineBindPoint::eCompute, *layout_->pipelineLayout(), 0,
                                set, nullptr);
    layout_->pushConstants(commands, constants);
    commands.dispatch((constants.width + kGroupSize - 1) / kGroupSize,
                      (constants.height + kGroupSize - 1) / kGroupSize, 1);
  }

 private:
  static ::vk::raii::Pipeline createPipeline(const VulkanDevice& device,
                                             const TraceLayout& layout) {
    const ::vk::raii::ShaderModule shader =
        createShaderModule(device, spirv::shadow_ray_query_comp());
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

std::unique_ptr<TraceRecorder> createRayQueryRecorder(const VulkanDevice& device,
                                                      const TraceLayout& layout) {
  return std::make_unique<RayQueryRecorder>(device, layout);
}

}  // namespace lgh::vk
