// Device buffers of one kind that come back here when their last owner lets go, and are handed
// out again to a later request of their size class. Every new scene's acceleration structures
// used to take an allocation of their own, and their release a free: with the scene cache off,
// one of each per thumbnail. On NVIDIA's driver both enter the kernel driver under a lock that the
// render thread's GL calls then wait for (docs/BENCHMARKS.md, "GPU targets, tenth round"); on
// lavapipe every new allocation is fresh memory that the kernel zeroes page by page.
//
// Sizes are rounded up to a power of two (at least kMinBytes), so that any kept buffer of a class
// serves any request of that class. Requests above kMaxRecycledBytes get a buffer of their own,
// freed as usual: large scenes are rare and their memory should go back. At most kKeptBytes
// wait here; a buffer returned beyond that is freed.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <mutex>

#include "vk/device_buffer.hpp"

namespace lgh::vk {

class VulkanDevice;

class RecycledBuffers : public std::enable_shared_from_this<RecycledBuffers> {
 public:
  static constexpr ::vk::DeviceSize kMinBytes = ::vk::DeviceSize{64} << 10U;
  static constexpr ::vk::DeviceSize kMaxRecycledBytes = ::vk::DeviceSize{16} << 20U;
  static constexpr ::vk::DeviceSize kKeptBytes = ::vk::DeviceSize{64} << 20U;

  // Buffers like `kind` (its size is not used). `device` outlives every buffer handed out: its
  // owner keeps this alive no longer than itself, and the buffers' users hold the device.
  static std::shared_ptr<RecycledBuffers> create(const VulkanDevice& device, BufferSpec kind);

  RecycledBuffers(const RecycledBuffers&) = delete;
  RecycledBuffers& operator=(const RecycledBuffers&) = delete;
  ~RecycledBuffers();

  // A buffer with at least `size` usable bytes: a kept one of its class, or a new one. It comes
  // back here once its last owner lets go (thread-safe); callers that need the GPU to be done with
  // it first hold it until then (DeferredRelease).
  std::shared_ptr<const DeviceBuffer> take(::vk::DeviceSize size);

  // The usable size a request of `size` bytes gets.
  static ::vk::DeviceSize classOf(::vk::DeviceSize size);

  struct Stats {
    std::size_t taken = 0;     // take() calls
    std::size_t recycled = 0;  // of them, served by a kept buffer
    std::size_t kept = 0;      // buffers waiting here now
    ::vk::DeviceSize keptBytes = 0;
  };
  Stats stats() const;

 private:
  RecycledBuffers(const VulkanDevice& device, BufferSpec kind);
  void giveBack(std::unique_ptr<DeviceBuffer> buffer) noexcept;

  const VulkanDevice* device_;
  BufferSpec kind_;
  mutable std::mutex mutex_;
  std::multimap<::vk::DeviceSize, std::unique_ptr<DeviceBuffer>> kept_;  // by usable size
  ::vk::DeviceSize keptBytes_ = 0;
  std::size_t taken_ = 0;
  std::size_t recycled_ = 0;
};

}  // namespace lgh::vk
