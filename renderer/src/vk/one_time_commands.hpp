// Records one command buffer and submits it to one of the tracer's queues (the frames' or the
// builds-ahead one: QueueRole): the acceleration-structure builds and uploads. Most callers wait
// for it; a small scene's build on the render thread does not (submit): the traces that use it
// come later on the same queue, and the render thread goes on with the frame. A build made ahead
// is waited for on its prefetch thread.
// The submission is then waited for by the next one, or by retire(). The command pool, its one
// command buffer and the fence are made once per device and reused (VulkanDevice owns them): made
// per submission they were a large part of a small scene's build on the H200.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>

#include "vk/queue_role.hpp"
#include "vk/timestamp_queries.hpp"
#include "vk/transient_buffers.hpp"
#include "vk/vulkan_hpp.hpp"

namespace lgh::vk {

class VulkanDevice;

using CommandRecorder = std::function<void(const ::vk::raii::CommandBuffer&)>;

class OneTimeCommands {
 public:
  // Submitting to the queue of `role` (vk/vulkan_device.hpp).
  OneTimeCommands(const VulkanDevice& device, QueueRole role);
  // Waits for a submission still pending.
  ~OneTimeCommands();
  OneTimeCommands(const OneTimeCommands&) = delete;
  OneTimeCommands& operator=(const OneTimeCommands&) = delete;

  // Retires the pending submission (if any), then records and submits `record` without waiting.
  // `retired` runs once the submission is waited for (it may read the timestamps). Throws as
  // retire() does, and vk::SystemError for a failing submission.
  void submit(const VulkanDevice& device, const CommandRecorder& record,
              std::function<void()> retired = {});
  // Waits for the pending submission, if any, and runs its `retired`. Throws lgh::Error(Internal)
  // when the wait times out, and vk::SystemError when the device is lost; after either, the
  // command buffer may still be pending, so every later call throws lgh::Error(Internal) instead
  // of reusing it (the tracer is made anew on a new device).
  void retire(const VulkanDevice& device);
  void submitAndWait(const VulkanDevice& device, const CommandRecorder& record);
  // Two timestamp pairs for the builds' GPU times, read after their submissions' waits (the
  // builds that use these commands run one after the other: buildLock).
  const TimestampQueries& timestamps() const { return timestamps_; }
  // The builds' staging, geometry, scratch and instance buffers, kept between them. A pending
  // submission may still read them: a build retires it before it first writes one
  // (AccelerationScene::build); the build's own steps may use them while they record.
  TransientBuffers& transientBuffers() { return transient_; }
  // Held by an acceleration-structure build from start to end: the builds that use these
  // commands share their transient buffers, one build at a time.
  std::unique_lock<std::mutex> buildLock() { return std::unique_lock(buildMutex_); }

 private:
  void retireLocked(const VulkanDevice& device);

  std::mutex mutex_;  // one submission at a time: the buffer and the fence are reused
  std::mutex buildMutex_;
  const VulkanDevice* device_;
  QueueRole role_;
  bool pending_ = false;     // submitted, not yet waited for
  bool unfinished_ = false;  // a wait failed: the buffer and the fence may still be in use
  std::function<void()> retired_;
  ::vk::raii::CommandPool pool_;
  ::vk::raii::CommandBuffers buffers_;
  ::vk::raii::Fence fence_;
  TimestampQueries timestamps_;
  TransientBuffers transient_;
};

void submitAndWait(const VulkanDevice& device, const CommandRecorder& record);

}  // namespace lgh::vk
