#include "vk/transient_buffers.hpp"

namespace lgh::vk {
namespace {

bool sameKind(const BufferSpec& a, const BufferSpec& b) {
  return a.usage == b.usage && a.memory == b.memory && a.deviceAddress == b.deviceAddress &&
         a.addressAlignment == b.addressAlignment;
}

bool fits(const DeviceBuffer& buffer, ::vk::DeviceSize needed) {
  const ::vk::DeviceSize size = buffer.size();
  return size >= needed && (size <= TransientBuffers::kKeptBytes || size <= 2 * needed);
}

}  // namespace

const DeviceBuffer& TransientBuffers::get(const VulkanDevice& device, const BufferSpec& spec) {
  for (Entry& entry : entries_) {
    if (!sameKind(entry.spec, spec)) continue;
    if (entry.buffer == nullptr || !fits(*entry.buffer, spec.size)) {
      entry.buffer.reset();  // the memory goes back before the new buffer takes its own
      entry.buffer = std::make_unique<DeviceBuffer>(device, spec);
    }
    return *entry.buffer;
  }
  entries_.push_back({spec, std::make_unique<DeviceBuffer>(device, spec)});
  return *entries_.back().buffer;
}

}  // namespace lgh::vk
