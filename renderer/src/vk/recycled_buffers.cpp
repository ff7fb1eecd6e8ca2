#include "vk/recycled_buffers.hpp"

#include <algorithm>
#include <bit>
#include <utility>

namespace lgh::vk {

std::shared_ptr<RecycledBuffers> RecycledBuffers::create(const VulkanDevice& device,
                                                         BufferSpec kind) {
  // make_shared cannot reach the private constructor.
  return std::shared_ptr<RecycledBuffers>(new RecycledBuffers(device, kind));
}

RecycledBuffers::RecycledBuffers(const VulkanDevice& device, BufferSpec kind)
    : device_(&device), kind_(kind) {}

RecycledBuffers::~RecycledBuffers() = default;

::vk::DeviceSize RecycledBuffers::classOf(::vk::DeviceSize size) {
  if (size > kMaxRecycledBytes) return size;
  return std::bit_ceil(std::max(size, kMinBytes));
}

std::shared_ptr<const DeviceBuffer> RecycledBuffers::take(::vk::DeviceSize size) {
  const ::vk::DeviceSize usable = classOf(size);
  std::unique_ptr<DeviceBuffer> buffer;
  {
    const std::lock_guard lock(mutex_);
    ++taken_;
    if (const auto kept = kept_.find(usable); kept != kept_.end()) {
      buffer = std::move(kept->second);
      kept_.erase(kept);
      keptBytes_ -= usable;
      ++recycled_;
    }
  }
  if (!buffer) {
    BufferSpec spec = kind_;
    spec.size = usable;
    buffer = std::make_unique<DeviceBuffer>(*device_, spec);
  }
  // The deleter owns the buffer from here on, even if making the control block throws.
  return {buffer.release(), [home = weak_from_this()](DeviceBuffer* returned) {
            std::unique_ptr<DeviceBuffer> owned(returned);
            if (const std::shared_ptr<RecycledBuffers> recycler = home.lock()) {
              recycler->giveBack(std::move(owned));
            }
          }};
}

void RecycledBuffers::giveBack(std::unique_ptr<DeviceBuffer> buffer) noexcept {
  const ::vk::DeviceSize usable = buffer->size();
  if (usable > kMaxRecycledBytes) return;  // freed here, as it was never meant to be kept
  try {
    const std::lock_guard lock(mutex_);
    if (keptBytes_ + usable > kKeptBytes) return;
    kept_.emplace(usable, std::move(buffer));
    keptBytes_ += usable;
  } catch (...) {  // std::bad_alloc of the map's node, std::system_error of the lock: freed
  }
}

RecycledBuffers::Stats RecycledBuffers::stats() const {
  const std::lock_guard lock(mutex_);
  return {.taken = taken_, .recycled = recycled_, .kept = kept_.size(), .keptBytes = keptBytes_};
}

}  // namespace lgh::vk
