// The closest-hit batch buffers (rays, hits) of shadow_tracer.hpp, as GL gets to see them:
// host-visible and mapped (staging) or exported as opaque fds (interop). They only grow.
#pragma once

#include <cstdint>
#include <optional>

#include "vk/device_buffer.hpp"
#include "vk/shadow_tracer.hpp"

namespace lgh::vk {

class VulkanDevice;

class HitBufferSet {
 public:
  bool fits(std::uint32_t rays, Transport transport) const;
  // Reallocates for `rays` (at least as large as before): a new generation, and for interop new
  // fds, which the caller owns. Nothing may still use the old buffers.
  void reallocate(const VulkanDevice& device, std::uint32_t rays, Transport transport);

  const HitBuffers& shared() const { return shared_; }
  bool allocated() const { return buffers_.has_value(); }
  ::vk::Buffer rays() const { return buffers_->rays.handle(); }
  ::vk::Buffer hits() const { return buffers_->hits.handle(); }

 private:
  struct Buffers {
    DeviceBuffer rays;
    DeviceBuffer hits;
  };

  std::optional<Buffers> buffers_;
  HitBuffers shared_;
};

// Throws lgh::Error(Invalid) for an empty batch, lgh::Error(TooLarge) when a buffer would exceed
// what one storage binding can hold.
void checkHitBatch(std::uint32_t rays, std::uint64_t maxBufferBytes);

}  // namespace lgh::vk
