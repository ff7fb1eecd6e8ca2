// The closest-hit half of the tracer (shadow_tracer.hpp, "Closest hits"): its own two-buffer
// layout, recorders for the paths the device has, submissions in flight, shared buffers and
// interop semaphores, beside the shadow rays' and independent of them. VulkanShadowTracer owns
// one and forwards the closest-hit calls to it.
#pragma once

#include <memory>
#include <optional>

#include "vk/exported_semaphores.hpp"
#include "vk/hit_buffer_set.hpp"
#include "vk/shadow_tracer.hpp"
#include "vk/trace_layout.hpp"
#include "vk/trace_recorder.hpp"
#include "vk/trace_submissions.hpp"

namespace lgh::vk {

class AccelerationScene;
class VulkanDevice;

// The push constants and the launch of a closest-hit batch.
HitPushConstants hitBatchConstants(const HitBatchShape& shape);
TraceLaunch hitBatchLaunch(const HitBatchShape& shape);

// The trace layout of closest-hit batches: the top level, rays and hits, HitPushConstants.
TraceLayout createHitTraceLayout(const VulkanDevice& device, ::vk::ShaderStageFlags stages,
                                 std::uint32_t sets);

class HitTracer {
 public:
  // `stages`: the shader stages of the tracing paths the device has.
  HitTracer(const VulkanDevice& device, ::vk::ShaderStageFlags stages);

  const HitBuffers& buffers(std::uint32_t rays, Transport transport);
  SemaphoreFds exportSemaphores();
  void trace(const AccelerationScene& scene, TracePath path, const HitBatchShape& shape,
             bool useSemaphores);
  TraceTimings collectTimings();

  // The recorder of `path` (the light paths record it into their own submission, with sets of
  // an identical TraceLayout). Throws lgh::Error(Unavailable) when the device lacks the path.
  const TraceRecorder& recorder(TracePath path) const;

 private:
  const VulkanDevice* device_;
  TraceLayout layout_;
  std::unique_ptr<TraceRecorder> rayQuery_;
  std::unique_ptr<TraceRecorder> pipeline_;
  TraceSubmissions submissions_;
  HitBufferSet buffers_;
  std::optional<ExportedSemaphores> semaphores_;
};

}  // namespace lgh::vk
