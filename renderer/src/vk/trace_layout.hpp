// What both tracing paths bind (glsl/vk/include/shadow_rays.glsl): the top level and the three
// ray buffers in one descriptor set, and the batch's constants as push constants. One set per
// submission slot, so a set is never rewritten while the GPU may still read it. The closest-hit
// batches (vk/hit_tracer.hpp) use the same layout with two buffers and their own constants.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

// TraceConstants in shadow_rays.glsl.
struct TracePushConstants {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t raysPerPixel = 0;
  std::uint32_t words = 0;
  float tMin = 0.0F;
  float tMaxInfinite = 0.0F;
  float endEpsilon = 0.0F;
  std::uint32_t firstTileX = 0;  // the launch's first tile (RayBatchShape::tiles; ray query)
  std::uint32_t firstTileY = 0;
};
static_assert(sizeof(TracePushConstants) == 36, "std430 push constants: 9 scalars");

// HitConstants in glsl/vk/include/hit_rays.glsl: the closest-hit batches' constants.
struct HitPushConstants {
  std::uint32_t rayCount = 0;
  std::uint32_t anyHit = 0;
  std::uint32_t launchWidth = 0;  // rays per row of the 2D launch
  std::uint32_t unused = 0;
};
static_assert(sizeof(HitPushConstants) == 16, "std430 push constants: 4 scalars");

struct TraceBindings {
  ::vk::AccelerationStructureKHR scene;
  ::vk::Buffer origins;
  ::vk::Buffer targets;
  ::vk::Buffer visibility;
};

class TraceLayout {
 public:
  // `stages`: the shader stages of the tracing paths the device has; `buffers` storage buffers
  // at bindings 1..buffers after the top level; push constants of `constantBytes`.
  TraceLayout(const VulkanDevice& device, ::vk::ShaderStageFlags stages, std::uint32_t sets,
              std::uint32_t buffers = 3, std::uint32_t constantBytes = sizeof(TracePushConstants));

  const ::vk::raii::PipelineLayout& pipelineLayout() const { return pipelineLayout_; }
  ::vk::ShaderStageFlags stages() const { return stages_; }
  ::vk::DescriptorSet set(std::uint32_t index) const { return *sets_[index]; }
  // Points set `index` at `bindings`; the GPU must be done with that set.
  void write(std::uint32_t index, const TraceBindings& bindings) const;
  // The same for a layout of buffers.size() buffers.
  void write(std::uint32_t index, ::vk::AccelerationStructureKHR scene,
             std::span<const ::vk::Buffer> buffers) const;
  // Pushes a push-constant block (vk/trace_recorder.hpp: constantBytes).
  void pushConstants(const ::vk::raii::CommandBuffer& commands,
                     std::span<const std::byte> constants) const;

 private:
  const ::vk::raii::Device* device_;
  ::vk::ShaderStageFlags stages_;
  std::uint32_t buffers_;
  ::vk::raii::DescriptorSetLayout setLayout_;
  ::vk::raii::PipelineLayout pipelineLayout_;
  ::vk::raii::DescriptorPool pool_;
  ::vk::raii::DescriptorSets sets_;
};

}  // namespace lgh::vk
