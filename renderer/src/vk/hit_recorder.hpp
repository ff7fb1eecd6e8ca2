// A tracing path's recorder of closest-hit batches (shadow_tracer.hpp, "Closest hits"): a compute
// shader with ray queries, or a ray-tracing pipeline (raygen + miss + closest hit). Both bind the
// same two-buffer TraceLayout and run the same ray code (glsl/vk/include/hit_rays.glsl), so they
// write the same records.
#pragma once

#include <cstdint>
#include <memory>

#include "vk/trace_layout.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

// HitConstants in glsl/vk/include/hit_rays.glsl.
struct HitPushConstants {
  std::uint32_t rayCount = 0;
  std::uint32_t anyHit = 0;
  std::uint32_t launchWidth = 0;  // rays per row of the 2D launch
  std::uint32_t unused = 0;
};
static_assert(sizeof(HitPushConstants) == 16, "std430 push constants: 4 scalars");

// Rays per row of the launch: a 1D launch of a million rays would pass the limits of one
// dimension on some devices, so batches launch rows of this many rays.
inline constexpr std::uint32_t kHitLaunchWidth = 16384;

class HitRecorder {
 public:
  virtual ~HitRecorder() = default;
  // The stage whose shaders read the scene and the buffers, for barriers and semaphore waits.
  virtual ::vk::PipelineStageFlags stage() const = 0;
  virtual void record(const ::vk::raii::CommandBuffer& commands, ::vk::DescriptorSet set,
                      const HitPushConstants& constants) const = 0;
};

std::unique_ptr<HitRecorder> createHitQueryRecorder(const VulkanDevice& device,
                                                    const TraceLayout& layout);
std::unique_ptr<HitRecorder> createHitPipelineRecorder(const VulkanDevice& device,
                                                       const TraceLayout& layout);

// Rows of the launch for `rays` rays.
constexpr std::uint32_t hitLaunchRows(std::uint32_t rays) {
  return (rays + kHitLaunchWidth - 1) / kHitLaunchWidth;
}

}  // namespace lgh::vk
