// GPU timestamps in pairs: write one before and one after some work, read the milliseconds
// between them. Without timestamps on the tracer's queue every reading is 0.
#pragma once

#include <cstdint>
#include <optional>

#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

class TimestampQueries {
 public:
  TimestampQueries(const VulkanDevice& device, std::uint32_t pairs);

  // Resets pair `pair` and writes its first timestamp as the work after it starts.
  void begin(const ::vk::raii::CommandBuffer& commands, std::uint32_t pair) const;
  // Writes the pair's second timestamp once the work before has finished.
  void end(const ::vk::raii::CommandBuffer& commands, std::uint32_t pair) const;
  // The milliseconds between the pair's timestamps; 0 when they are not written yet. Read after
  // the submission's fence: its queries are then available. No wait flag: lavapipe's wait for a
  // query waits for the whole queue, later submissions too.
  double elapsedMs(std::uint32_t pair) const;

 private:
  std::optional<::vk::raii::QueryPool> pool_;
  double periodNs_;
};

}  // namespace lgh::vk
