// The ray-query path: a compute shader (glsl/vk/shadow_ray_query.comp, closest_hit_query.comp),
// one invocation per ray or pixel of the launch, in work groups of the program's local size.
#include "vk/shader_module.hpp"
#include "vk/trace_recorder.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

class RayQueryRecorder final : public TraceRecorder {
 public:
  RayQueryRecorder(const VulkanDevice& device, const TraceLayout& layout,
                   const RayQueryProgram& program)
      : layout_(&layout),
        groupWidth_(program.groupWidth),
        groupHeight_(program.groupHeight),
        pipeline_(createComputePipeline(device, *layout.pipelineLayout(), program.shader)) {}

  ::vk::PipelineStageFlags stage() const override {
    return ::vk::PipelineStageFlagBits::eComputeShader;
  }

  void record(const ::vk::raii::CommandBuffer& commands, ::vk::DescriptorSet set,
              std::span<const std::byte> constants, TraceLaunch launch) const override {
    commands.bindPipeline(::vk::PipelineBindPoint::eCompute, *pipeline_);
    commands.bindDescriptorSets(::vk::PipelineBindPoint::eCompute, *layout_->pipelineLayout(), 0,
                                set, nullptr);
    layout_->pushConstants(commands, constants);
    commands.dispatch((launch.width + groupWidth_ - 1) / groupWidth_,
                      (launch.height + groupHeight_ - 1) / groupHeight_, 1);
  }

 private:
  const TraceLayout* layout_;
  std::uint32_t groupWidth_;
  std::uint32_t groupHeight_;
  ::vk::raii::Pipeline pipeline_;
};

}  // namespace

std::unique_ptr<TraceRecorder> createRayQueryRecorder(const VulkanDevice& device,
                                                      const TraceLayout& layout,
                                                      const RayQueryProgram& program) {
  return std::make_unique<RayQueryRecorder>(device, layout, program);
}

}  // namespace lgh::vk
