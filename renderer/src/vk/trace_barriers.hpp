// The barriers around a trace: the scene built by earlier submissions becomes readable by the
// trace's shaders; interop buffers pass from GL (the external queue family) to Vulkan and back;
// staging results become visible to the host that reads them. Shadow batches share three
// buffers with GL, closest-hit batches two.
#pragma once

#include <cstdint>
#include <span>

#include "vk/shadow_tracer.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

struct TraceBarrierScope {
  ::vk::PipelineStageFlags traceStage;  // the stage of the tracing path's shaders
  Transport transport = Transport::Staging;
  std::uint32_t queueFamily = 0;
  std::span<const ::vk::Buffer> buffers;  // the buffers shared with GL
  bool fillsFirst = false;                // a transfer fills one of them before the trace
};

void recordBarriersBeforeTrace(const ::vk::raii::CommandBuffer& commands,
                               const TraceBarrierScope& scope);
// Between a fill of a shared buffer (TraceBatch::zeroed) and the trace that writes the rest.
void recordFillBeforeTrace(const ::vk::raii::CommandBuffer& commands,
                           const TraceBarrierScope& scope);
void recordBarriersAfterTrace(const ::vk::raii::CommandBuffer& commands,
                              const TraceBarrierScope& scope);

}  // namespace lgh::vk
