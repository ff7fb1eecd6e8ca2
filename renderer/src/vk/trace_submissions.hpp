// The tracer's submissions in flight: a few slots, each with its command buffer, fence and
// timestamp pair (and, by index, its descriptor set), reused round robin. A slot is reused once
// its fence says the GPU is done with it, and its GPU time is banked, under the submission's
// number (1, 2, ...), until takeGpuMs() asks for it: a frame asks for its own submissions when it
// is taken, so that drawing the next frame never waits for this one's trace.
#pragma once

#include <cstdint>
#include <deque>
#include <utility>
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
  // The number of the last submission (0: none yet).
  std::uint64_t lastSubmission() const { return submitted_; }
  // Waits for the slot's submission and banks its GPU time.
  void retire(std::uint32_t slot);
  // Retires every slot in flight.
  void retireAll();
  // Retires the slots in flight whose submissions are numbered `through` or lower.
  void retireThrough(std::uint64_t through);
  // Whether the submissions numbered `through` or lower have all finished: their fences are asked,
  // nothing is waited for or retired.
  bool finished(std::uint64_t through) const;
  // The GPU time of submissions up to and including number `through` that no earlier call
  // returned, summed; waits for those still running, not for later ones.
  double takeGpuMs(std::uint64_t through);
  // Banked times kept for frames that never ask (a failed frame): beyond this, the oldest go.
  static constexpr std::size_t kMaxBanked = 256;

 private:
  const VulkanDevice* device_;
  ::vk::raii::CommandPool pool_;
  ::vk::raii::CommandBuffers commands_;
  std::vector<::vk::raii::Fence> fences_;
  std::vector<bool> inFlight_;
  TimestampQueries timestamps_;
  std::vector<std::uint64_t> numberOf_;  // per slot: its submission's number
  std::uint32_t next_ = 0;
  std::uint64_t submitted_ = 0;
  std::deque<std::pair<std::uint64_t, double>> banked_;  // (submission, GPU ms), oldest first
};

}  // namespace lgh::vk
