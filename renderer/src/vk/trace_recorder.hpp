// A tracing path's recorder records the tracing of one batch into a command buffer: a compute
// shader with ray queries, or a ray-tracing pipeline (raygen + miss). Both bind the same
// TraceLayout and run the same ray setup (glsl/vk/include/shadow_rays.glsl), so they set the same
// bits.
#pragma once

#include <cstdint>
#include <memory>

#include "vk/trace_layout.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

class TraceRecorder {
 public:
  virtual ~TraceRecorder() = default;
  // The stage whose shaders read the scene and the buffers, for barriers and semaphore waits.
  virtual ::vk::PipelineStageFlags stage() const = 0;
  virtual void record(const ::vk::raii::CommandBuffer& commands, ::vk::DescriptorSet set,
                      const TracePushConstants& constants) const = 0;
};

std::unique_ptr<TraceRecorder> createRayQueryRecorder(const VulkanDevice& device,
                                                      const TraceLayout& layout);
std::unique_ptr<TraceRecorder> createRayTracingPipelineRecorder(const VulkanDevice& device,
                                                                const TraceLayout& layout);

}  // namespace lgh::vk
