// Buffers that live for one submission that is waited for (the acceleration structures' staging,
// geometry, scratch and instance buffers), kept between builds: one per kind (usage, memory,
// address alignment), grown when a build needs more. Made per build they were most of a small
// scene's build time on the H200 (docs/BENCHMARKS.md). A buffer is handed out again by the next
// get() of its kind, so a caller holds it only until its submission's wait; the builds of a
// device run one after the other on the thread that renders.
#pragma once

#include <memory>
#include <vector>

#include "vk/device_buffer.hpp"

namespace lgh::vk {

class TransientBuffers {
 public:
  // A buffer of this kind with at least spec.size usable bytes. One much larger than needed is
  // replaced once it passes kKeptBytes, so that one large scene does not hold its memory forever.
  const DeviceBuffer& get(const VulkanDevice& device, const BufferSpec& spec);

  static constexpr ::vk::DeviceSize kKeptBytes = ::vk::DeviceSize{16} << 20U;

 private:
  struct Entry {
    BufferSpec spec;
    std::unique_ptr<DeviceBuffer> buffer;
  };
  std::vector<Entry> entries_;
};

}  // namespace lgh::vk
