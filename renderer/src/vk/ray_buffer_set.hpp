// The ray batch buffers (origins, targets, visibility) of shadow_tracer.hpp, as GL gets to see
// them: host-visible and mapped (staging) or exported as opaque fds (interop). They only grow.
#pragma once

#include <optional>

#include "vk/device_buffer.hpp"
#include "vk/shadow_tracer.hpp"

namespace lgh::vk {

class VulkanDevice;

class RayBufferSet {
 public:
  // Whether the buffers hold `shape` in `transport` as they are.
  bool fits(const RayBatchShape& shape, Transport transport) const;
  // Reallocates for `shape` (at least as large as before in every buffer): a new generation,
  // and for interop new fds, which the caller owns (shadow_tracer.hpp). Nothing may still use
  // the old buffers.
  void reallocate(const VulkanDevice& device, const RayBatchShape& shape, Transport transport);

  const RayBuffers& shared() const { return shared_; }
  bool allocated() const { return buffers_.has_value(); }
  ::vk::Buffer origins() const { return buffers_->origins.handle(); }
  ::vk::Buffer targets() const { return buffers_->targets.handle(); }
  ::vk::Buffer visibility() const { return buffers_->visibility.handle(); }

 private:
  struct Buffers {
    DeviceBuffer origins;
    DeviceBuffer targets;
    DeviceBuffer visibility;
  };
  static RayBuffers describeAll(const Buffers& buffers, Transport transport,
                                std::uint64_t generation);

  std::optional<Buffers> buffers_;
  RayBuffers shared_;
};

// The bytes of each buffer for `shape`.
struct RayBatchBytes {
  std::uint64_t origins = 0;
  std::uint64_t targets = 0;
  std::uint64_t visibility = 0;
};
RayBatchBytes rayBatchBytes(const RayBatchShape& shape);

// Throws lgh::Error(Invalid) unless 1 <= raysPerPixel <= kMaxRaysPerPixel and the batch has
// pixels; lgh::Error(TooLarge) when a buffer would exceed what one storage binding can hold.
void checkShape(const RayBatchShape& shape, std::uint64_t maxBufferBytes);

}  // namespace lgh::vk
