#include "vk/hit_buffer_set.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "lgh/error.hpp"
#include "vk/shared_buffer.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {

void checkHitBatch(std::uint32_t rays, std::uint64_t maxBufferBytes) {
  if (rays == 0) throw Error(ErrorCode::Invalid, "an empty closest-hit batch");
  const std::uint64_t bytes = std::uint64_t{rays} * std::max(kHitRayBytes, kHitRecordBytes);
  if (bytes > maxBufferBytes) {
    throw Error(ErrorCode::TooLarge,
                fmt::format("a closest-hit batch of {} rays needs a {} byte buffer; the Vulkan "
                            "device binds at most {}: trace it in smaller batches",
                            rays, bytes, maxBufferBytes));
  }
}

bool HitBufferSet::fits(std::uint32_t rays, Transport transport) const {
  return buffers_ && shared_.transport == transport &&
         std::uint64_t{rays} * kHitRayBytes <= shared_.rays.size &&
         std::uint64_t{rays} * kHitRecordBytes <= shared_.hits.size;
}

void HitBufferSet::reallocate(const VulkanDevice& device, std::uint32_t rays, Transport transport) {
  std::uint64_t rayBytes = std::uint64_t{rays} * kHitRayBytes;
  std::uint64_t hitBytes = std::uint64_t{rays} * kHitRecordBytes;
  if (buffers_ && shared_.transport == transport) {
    rayBytes = std::max(rayBytes, shared_.rays.size);
    hitBytes = std::max(hitBytes, shared_.hits.size);
  }
  // The old buffers go first, and nothing describes them afterwards, even when the new ones fail.
  buffers_.reset();
  const std::uint64_t generation = shared_.generation + 1;
  shared_ = HitBuffers{};
  shared_.transport = transport;
  shared_.generation = generation;
  buffers_.emplace(Buffers{createSharedBuffer(device, rayBytes, transport),
                           createSharedBuffer(device, hitBytes, transport)});
  HitBuffers described = shared_;
  try {
    described.rays = describeShared(buffers_->rays, transport);
    described.hits = describeShared(buffers_->hits, transport);
  } catch (...) {
    closeSharedFds({&described.rays, &described.hits});
    throw;
  }
  shared_ = described;
  spdlog::debug("vulkan: closest-hit buffers, generation {}: {} + {} bytes ({})", generation,
                rayBytes, hitBytes, transport == Transport::Interop ? "interop" : "staging");
}

}  // namespace lgh::vk
