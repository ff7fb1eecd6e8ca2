// The tracer's submissions in flight: a few slots, each with its command buffer, fence and
// timestamp pair (and, by index, its descriptor set), reused round robin. A slot is reused once
// its fence says the GPU is done with it, and its GPU time is banked for collectTimings().
#pragma once

#include <cstdint>
#include <vector>

#include "vk/timestamp_queries.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

class TraceSubmissions {
 public:
  TraceSubmissions(const VulkanDevice& device, std::uint32_t slots);

  // The next slot, idle, its command buffer reset and its fence unsignalled.
  std::uint32_t acquire();
  const ::vk::raii::CommandBuffer& commands(std::uint32_t slot) const { return commands_[slot]; }
  const TimestampQueries& timestamps() const { return timestamps_; }
  // Submits the slot's commands, waiting on `wait` (if any) at `waitStage` and signalling
  // `signal` (if any).
  void submit(std::uint32_t slot, ::vk::Semaphore wait, ::vk::PipelineStageFlags waitStage,
              ::vk::Semaphore signal);
  // Waits for the slot's submission and banks its GPU time.
  void retire(std::uint32_t slot);
  // Retires every slot in flight.
  void retireAll();
  // The GPU time banked since the last call.
  double takeGpuMs();

 private:
  const VulkanDevice* device_;
  ::vk::raii::CommandPool pool_;
  ::vk::raii::CommandBuffers commands_;
  std::vector<::vk::raii::Fence> fences_;
  std::vector<bool> inFlight_;
  TimestampQueries timestamps_;
  std::uint32_t next_ = 0;
  double bankedGpuMs_ = 0.0;
};

}  // namespace lgh::vk
