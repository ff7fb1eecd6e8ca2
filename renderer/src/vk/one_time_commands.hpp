// Records one command buffer, submits it to the tracer's queue and waits for it: the
// acceleration-structure builds and uploads, which the caller waits for anyway. The command pool,
// its one command buffer and the fence are made once per device and reused (VulkanDevice owns
// them): made per submission they were a large part of a small scene's build on the H200.
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>

#include "vk/timestamp_queries.hpp"
#include "vk/transient_buffers.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

using CommandRecorder = std::function<void(const ::vk::raii::CommandBuffer&)>;

class OneTimeCommands {
 public:
  explicit OneTimeCommands(const VulkanDevice& device);
  // Throws lgh::Error(Internal) when the wait times out, and vk::SystemError when the device is
  // lost; after either, the command buffer may still be pending, so every later call throws
  // lgh::Error(Internal) instead of reusing it (the tracer is made anew on a new device).
  void submitAndWait(const VulkanDevice& device, const CommandRecorder& record);
  // Two timestamp pairs for the builds' GPU times, read after their submissions' waits (the
  // builds of a device run one after the other, on the thread that renders).
  const TimestampQueries& timestamps() const { return timestamps_; }
  // The builds' staging, geometry, scratch and instance buffers, kept between them.
  TransientBuffers& transientBuffers() { return transient_; }

 private:
  std::mutex mutex_;         // one submission at a time: the buffer and the fence are reused
  bool unfinished_ = false;  // a wait failed: the buffer and the fence may still be in use
  ::vk::raii::CommandPool pool_;
  ::vk::raii::CommandBuffers buffers_;
  ::vk::raii::Fence fence_;
  TimestampQueries timestamps_;
  TransientBuffers transient_;
};

void submitAndWait(const VulkanDevice& device, const CommandRecorder& record);

}  // namespace lgh::vk
