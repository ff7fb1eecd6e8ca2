// A tracing path's recorder records the tracing of one batch into a command buffer: a compute
// shader with ray queries, or a ray-tracing pipeline (raygen + miss + one triangle hit group).
// Each kind of batch has one of each, built from its shaders (shadow rays:
// glsl/vk/include/shadow_rays.glsl; closest hits: glsl/vk/include/hit_rays.glsl); both bind the
// kind's TraceLayout and run the same ray code, so they give the same results.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include "vk/trace_layout.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

// The invocations of one batch: a ray-tracing pipeline launches width x height of them; a
// compute dispatch covers them with work groups of its shader's local size.
struct TraceLaunch {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

class TraceRecorder {
 public:
  virtual ~TraceRecorder() = default;
  // The stage whose shaders read the scene and the buffers, for barriers and semaphore waits.
  virtual ::vk::PipelineStageFlags stage() const = 0;
  // Binds the pipeline and `set`, pushes `constants` (the layout's push-constant block, as bytes)
  // and launches.
  virtual void record(const ::vk::raii::CommandBuffer& commands, ::vk::DescriptorSet set,
                      std::span<const std::byte> constants, TraceLaunch launch) const = 0;
};

// The ray-query path's compute shader and its local size.
struct RayQueryProgram {
  std::span<const std::uint32_t> shader;
  std::uint32_t groupWidth = 1;   // local_size_x
  std::uint32_t groupHeight = 1;  // local_size_y
};

// The ray-tracing pipeline's shaders. Without a closest-hit shader the hit group is empty (shadow
// rays skip closest hits on opaque geometry).
struct PipelineProgram {
  std::span<const std::uint32_t> rayGeneration;
  std::span<const std::uint32_t> miss;
  std::span<const std::uint32_t> closestHit;  // empty: none
};

std::unique_ptr<TraceRecorder> createRayQueryRecorder(const VulkanDevice& device,
                                                      const TraceLayout& layout,
                                                      const RayQueryProgram& program);
std::unique_ptr<TraceRecorder> createRayTracingPipelineRecorder(const VulkanDevice& device,
                                                                const TraceLayout& layout,
                                                                const PipelineProgram& program);

// A push-constant block as the recorders take it.
template <typename Constants>
std::span<const std::byte> constantBytes(const Constants& constants) {
  return std::as_bytes(std::span<const Constants, 1>(&constants, 1));
}

}  // namespace lgh::vk
