#include "vk/ray_buffer_set.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "lgh/error.hpp"
#include "vk/shared_buffer.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

constexpr std::uint64_t kVec4Bytes = 16;
constexpr std::uint64_t kWordBytes = 4;

void checkTiles(const RayBatchShape& shape) {
  if (!shape.tiles) return;
  const std::array<std::uint32_t, 2> frameTiles{(shape.width + kRayTileSize - 1) / kRayTileSize,
                                                (shape.height + kRayTileSize - 1) / kRayTileSize};
  for (std::size_t axis = 0; axis < 2; ++axis) {
    const std::uint64_t end = std::uint64_t{shape.tiles->first[axis]} + shape.tiles->count[axis];
    if (end > frameTiles[axis]) {
      throw Error(ErrorCode::Invalid,
                  fmt::format("ray tiles {} to {} along axis {}: a {} x {} batch has {}",
                              shape.tiles->first[axis], end, axis, shape.width, shape.height,
                              frameTiles[axis]));
    }
  }
}

}  // namespace

RayBuffers RayBufferSet::describeAll(const Buffers& buffers, Transport transport,
                                     std::uint64_t generation) {
  RayBuffers shared;
  shared.transport = transport;
  shared.generation = generation;
  try {
    shared.origins = describeShared(buffers.origins, transport);
    shared.targets = describeShared(buffers.targets, transport);
    shared.visibility = describeShared(buffers.visibility, transport);
  } catch (...) {
    // Those exported before the failure: nobody else will close them.
    closeSharedFds({&shared.origins, &shared.targets, &shared.visibility});
    throw;
  }
  return shared;
}

RayBatchBytes rayBatchBytes(const RayBatchShape& shape) {
  return {.origins = shape.pixels() * kVec4Bytes,
          .targets = shape.pixels() * shape.raysPerPixel * kVec4Bytes,
          .visibility = shape.pixels() * shape.words() * kWordBytes};
}

void checkShape(const RayBatchShape& shape, std::uint64_t maxBufferBytes) {
  if (shape.raysPerPixel < 1 || shape.raysPerPixel > kMaxRaysPerPixel) {
    throw Error(ErrorCode::Invalid,
                fmt::format("{} rays per pixel; the shadow tracer takes 1 to {}",
                            shape.raysPerPixel, kMaxRaysPerPixel));
  }
  if (shape.pixels() == 0) {
    throw Error(ErrorCode::Invalid,
                fmt::format("an empty ray batch ({} x {})", shape.width, shape.height));
  }
  checkTiles(shape);
  const RayBatchBytes bytes = rayBatchBytes(shape);
  const std::uint64_t largest = std::max({bytes.origins, bytes.targets, bytes.visibility});
  if (largest > maxBufferBytes) {
    throw Error(
        ErrorCode::TooLarge,
        fmt::format("a ray batch of {} x {} x {} rays needs a {} byte buffer; the Vulkan "
                    "device binds at most {}: trace it in smaller batches",
                    shape.width, shape.height, shape.raysPerPixel, largest, maxBufferBytes));
  }
}

bool RayBufferSet::fits(const RayBatchShape& shape, Transport transport) const {
  if (!buffers_ || shared_.transport != transport) return false;
  const RayBatchBytes bytes = rayBatchBytes(shape);
  return bytes.origins <= shared_.origins.size && bytes.targets <= shared_.targets.size &&
         bytes.visibility <= shared_.visibility.size;
}

void RayBufferSet::reallocate(const VulkanDevice& device, const RayBatchShape& shape,
                              Transport transport) {
  RayBatchBytes bytes = rayBatchBytes(shape);
  if (buffers_ && shared_.transport == transport) {
    bytes.origins = std::max(bytes.origins, shared_.origins.size);
    bytes.targets = std::max(bytes.targets, shared_.targets.size);
    bytes.visibility = std::max(bytes.visibility, shared_.visibility.size);
  }
  // The old buffers go first (they may be large), and nothing describes them afterwards, even
  // when the new ones fail.
  buffers_.reset();
  const std::uint64_t generation = shared_.generation + 1;
  shared_ = RayBuffers{};
  shared_.transport = transport;
  shared_.generation = generation;
  buffers_.emplace(Buffers{createSharedBuffer(device, bytes.origins, transport),
                           createSharedBuffer(device, bytes.targets, transport),
                           createSharedBuffer(device, bytes.visibility, transport)});
  shared_ = describeAll(*buffers_, transport, shared_.generation);
  spdlog::debug("vulkan: ray buffers, generation {}: {} + {} + {} bytes ({})", shared_.generation,
                bytes.origins, bytes.targets, bytes.visibility,
                transport == Transport::Interop ? "interop" : "staging");
}

}  // namespace lgh::vk
