#include "vk/shader_binding_table.hpp"

#include <cstring>
#include <vector>

#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

// Where each group's record goes: one region per group, each at a base-aligned offset.
struct TableLayout {
  ::vk::DeviceSize recordStride = 0;
  ::vk::DeviceSize regionStride = 0;
  ::vk::DeviceSize bytes() const { return regionStride * kShaderGroupCount; }
  ::vk::DeviceSize offset(ShaderGroup group) const {
    return regionStride * static_cast<std::uint32_t>(group);
  }
};

TableLayout layoutFor(const DeviceLimits& limits) {
  TableLayout layout;
  layout.recordStride = alignUp(limits.shaderGroupHandleSize, limits.shaderGroupHandleAlignment);
  layout.regionStride = alignUp(layout.recordStride, limits.shaderGroupBaseAlignment);
  return layout;
}

}  // namespace

ShaderBindingTable::ShaderBindingTable(const VulkanDevice& device,
                                       const ::vk::raii::Pipeline& pipeline)
    : buffer_(device, {.size = layoutFor(device.limits()).bytes(),
                       .usage = ::vk::BufferUsageFlagBits::eShaderBindingTableKHR,
                       .memory = MemoryKind::HostVisible,
                       .deviceAddress = true,
                       .addressAlignment = device.limits().shaderGroupBaseAlignment}) {
  const TableLayout layout = layoutFor(device.limits());
  const std::uint32_t handleSize = device.limits().shaderGroupHandleSize;
  const std::vector<std::uint8_t> handles =
      pipeline.getRayTracingShaderGroupHandlesKHR<std::uint8_t>(
          0, kShaderGroupCount, std::size_t{kShaderGroupCount} * handleSize);
  std::memset(buffer_.mapped(), 0, layout.bytes());
  for (std::uint32_t group = 0; group < kShaderGroupCount; ++group) {
    std::memcpy(buffer_.mapped() + layout.offset(static_cast<ShaderGroup>(group)),
                handles.data() + std::size_t{group} * handleSize, handleSize);
  }
  const auto region = [&](ShaderGroup group, ::vk::DeviceSize stride) {
    return ::vk::StridedDeviceAddressRegionKHR{
        .deviceAddress = buffer_.address() + layout.offset(group),
        .stride = stride,
        .size = stride};
  };
  // The raygen region's stride must equal its size; the others hold a single record each.
  rayGeneration_ = region(ShaderGroup::RayGeneration, layout.recordStride);
  miss_ = region(ShaderGroup::Miss, layout.recordStride);
  hit_ = region(ShaderGroup::Hit, layout.recordStride);
}

}  // namespace lgh::vk
