#include "vk/trace_layout.hpp"

#include <array>
#include <vector>

#include "lgh/error.hpp"
#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

::vk::raii::DescriptorSetLayout createSetLayout(const ::vk::raii::Device& device,
                                                ::vk::ShaderStageFlags stages,
                                                std::uint32_t buffers) {
  std::vector<::vk::DescriptorSetLayoutBinding> bindings(1 + buffers);
  bindings[0] = {.binding = 0,
                 .descriptorType = ::vk::DescriptorType::eAccelerationStructureKHR,
                 .descriptorCount = 1,
                 .stageFlags = stages};
  for (std::uint32_t i = 1; i <= buffers; ++i) {
    bindings[i] = {.binding = i,
                   .descriptorType = ::vk::DescriptorType::eStorageBuffer,
                   .descriptorCount = 1,
                   .stageFlags = stages};
  }
  return {device, ::vk::DescriptorSetLayoutCreateInfo{
                      .bindingCount = static_cast<std::uint32_t>(bindings.size()),
                      .pBindings = bindings.data()}};
}

::vk::raii::PipelineLayout createPipelineLayout(const ::vk::raii::Device& device,
                                                const ::vk::raii::DescriptorSetLayout& setLayout,
                                                ::vk::ShaderStageFlags stages,
                                                std::uint32_t constantBytes) {
  const ::vk::DescriptorSetLayout set = *setLayout;
  const ::vk::PushConstantRange constants{.stageFlags = stages, .offset = 0, .size = constantBytes};
  return {device, ::vk::PipelineLayoutCreateInfo{.setLayoutCount = 1,
                                                 .pSetLayouts = &set,
                                                 .pushConstantRangeCount = 1,
                                                 .pPushConstantRanges = &constants}};
}

::vk::raii::DescriptorPool createPool(const ::vk::raii::Device& device, std::uint32_t sets,
                                      std::uint32_t buffers) {
  const std::array<::vk::DescriptorPoolSize, 2> sizes{{
      {.type = ::vk::DescriptorType::eAccelerationStructureKHR, .descriptorCount = sets},
      {.type = ::vk::DescriptorType::eStorageBuffer, .descriptorCount = buffers * sets},
  }};
  // Free-able sets: vk::raii frees each set it holds.
  return {device, ::vk::DescriptorPoolCreateInfo{
                      .flags = ::vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet,
                      .maxSets = sets,
                      .poolSizeCount = static_cast<std::uint32_t>(sizes.size()),
                      .pPoolSizes = sizes.data()}};
}

::vk::raii::DescriptorSets allocateSets(const ::vk::raii::Device& device,
                                        const ::vk::raii::DescriptorPool& pool,
                                        const ::vk::raii::DescriptorSetLayout& layout,
                                        std::uint32_t count) {
  const std::vector<::vk::DescriptorSetLayout> layouts(count, *layout);
  return {device,
          ::vk::DescriptorSetAllocateInfo{
              .descriptorPool = *pool, .descriptorSetCount = count, .pSetLayouts = layouts.data()}};
}

}  // namespace

TraceLayout::TraceLayout(const VulkanDevice& device, ::vk::ShaderStageFlags stages,
                         std::uint32_t sets, std::uint32_t buffers, std::uint32_t constantBytes)
    : device_(&device.device()),
      stages_(stages),
      buffers_(buffers),
      setLayout_(createSetLayout(device.device(), stages, buffers)),
      pipelineLayout_(createPipelineLayout(device.device(), setLayout_, stages, constantBytes)),
      pool_(createPool(device.device(), sets, buffers)),
      sets_(allocateSets(device.device(), pool_, setLayout_, sets)) {}

void TraceLayout::write(std::uint32_t index, const TraceBindings& bindings) const {
  const std::array<::vk::Buffer, 3> buffers{bindings.origins, bindings.targets,
                                            bindings.visibility};
  write(index, bindings.scene, buffers);
}

void TraceLayout::write(std::uint32_t index, ::vk::AccelerationStructureKHR scene,
                        std::span<const ::vk::Buffer> buffers) const {
  if (buffers.size() != buffers_) {
    throw Error(ErrorCode::Internal, "a trace layout written with the wrong number of buffers");
  }
  const ::vk::WriteDescriptorSetAccelerationStructureKHR structure{
      .accelerationStructureCount = 1, .pAccelerationStructures = &scene};
  std::vector<::vk::DescriptorBufferInfo> infos;
  infos.reserve(buffers.size());
  for (const ::vk::Buffer buffer : buffers) {
    infos.push_back({.buffer = buffer, .offset = 0, .range = VK_WHOLE_SIZE});
  }
  const ::vk::DescriptorSet set = *sets_[index];
  const std::array<::vk::WriteDescriptorSet, 2> writes{{
      {.pNext = &structure,
       .dstSet = set,
       .dstBinding = 0,
       .descriptorCount = 1,
       .descriptorType = ::vk::DescriptorType::eAccelerationStructureKHR},
      {.dstSet = set,
       .dstBinding = 1,
       .descriptorCount = static_cast<std::uint32_t>(infos.size()),
       .descriptorType = ::vk::DescriptorType::eStorageBuffer,
       .pBufferInfo = infos.data()},
  }};
  device_->updateDescriptorSets(writes, nullptr);
}

void TraceLayout::pushConstants(const ::vk::raii::CommandBuffer& commands,
                                std::span<const std::byte> constants) const {
  commands.pushConstants<std::byte>(
      *pipelineLayout_, stages_, 0,
      ::vk::ArrayProxy<const std::byte>(static_cast<std::uint32_t>(constants.size()),
                                        constants.data()));
}

}  // namespace lgh::vk
