// GPU timestamps in pairs: write one before and one after some work, read the milliseconds
// between them. Without timestamps on the tracer's queue every reading is 0.
//
// The queue itself copies each pair's results into host-visible memory at the end of the work,
// and the host reads them from there: lavapipe's vkGetQueryPoolResults waits for the whole queue
// to go idle first, whatever the flags, so reading a frame's trace time on the host waited for
// the next frame's trace too, which the render thread had just submitted (docs/BENCHMARKS.md).
#pragma once

#include <cstdint>
#include <optional>

#include "vk/device_buffer.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

// Records the queue's copy of queries [first, first + count) of `pool` into `results` from `offset`
// (a uint64 each, waited for on the device), and the barrier that makes it visible to the host
// once the submission's fence has signalled.
void copyQueriesToHost(const ::vk::raii::CommandBuffer& commands, ::vk::QueryPool pool,
                       std::uint32_t first, std::uint32_t count, const DeviceBuffer& results,
                       ::vk::DeviceSize offset);

class TimestampQueries {
 public:
  TimestampQueries(const VulkanDevice& device, std::uint32_t pairs);

  // Resets pair `pair` and writes its first timestamp as the work after it starts. The pair's
  // earlier reading is cleared: the pair must not be in use by a submission still running.
  void begin(const ::vk::raii::CommandBuffer& commands, std::uint32_t pair) const;
  // Writes the pair's second timestamp once the work before has finished, and the queue's copy
  // of the pair into host memory.
  void end(const ::vk::raii::CommandBuffer& commands, std::uint32_t pair) const;
  // The milliseconds between the pair's timestamps, read after the submission's fence; 0 before
  // the submission has run.
  double elapsedMs(std::uint32_t pair) const;

 private:
  std::uint64_t* ticks(std::uint32_t pair) const;

  std::optional<::vk::raii::QueryPool> pool_;
  std::optional<DeviceBuffer> results_;  // two uint64 per pair, written by the queue
  double periodNs_;
};

}  // namespace lgh::vk
