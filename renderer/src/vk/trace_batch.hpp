// One batch on the GPU, the same for shadow rays and closest hits: its commands recorded into a
// submission slot (timestamps around the barriers that hand the buffers shared with GL to the
// trace and back, and the recorder's launch), then submitted. With semaphores, every command
// waits for GL's `glDone` (the first timestamp too: the GPU time is the trace's alone) and
// `vkDone` is signalled. The call returns once the work is submitted: a caller without semaphores
// retires the slot (TraceSubmissions::retire) before it reads what the trace wrote.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "vk/shadow_tracer.hpp"
#include "vk/trace_recorder.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class ExportedSemaphores;
class TraceSubmissions;

struct TraceBatch {
  const TraceRecorder* recorder = nullptr;
  ::vk::DescriptorSet set;  // the slot's, already written
  std::span<const std::byte> constants;
  TraceLaunch launch;
  Transport transport = Transport::Staging;
  std::span<const ::vk::Buffer> buffers;  // shared with GL
  // A buffer (one of `buffers`) that the launch writes only in part: its first `zeroedBytes` are
  // filled with zeros before it (the shadow rays' visibility, whose words of pixels without a
  // surface the ray-query shader leaves alone). 0: none.
  ::vk::Buffer zeroed;
  ::vk::DeviceSize zeroedBytes = 0;
};

// `slot`: acquired from `submissions`. `semaphores`: null for a batch without them.
void submitTraceBatch(TraceSubmissions& submissions, std::uint32_t slot, std::uint32_t queueFamily,
                      const TraceBatch& batch, const ExportedSemaphores* semaphores);

}  // namespace lgh::vk
