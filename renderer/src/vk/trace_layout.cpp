#include "vk/trace_layout.hpp"

#include <array>
#include <vector>

#include "vk/vulkan_device.hpp"

namespace lgh::vk {
namespace {

constexpr std::uint32_t kBufferBindings = 3;  // origins, targets, visibility

::vk::raii::DescriptorSetLayout createSetLayout(const ::vk::raii::Device& device,
                                                ::vk::ShaderStageFlags stages) {
  std::array<::vk::DescriptorSetLayoutBinding, 1 + kBufferBindings> bindings{};
  bindings[0] = {.binding = 0,
                 .descriptorType = ::vk::DescriptorType::eAccelerationStructureKHR,
                 .descriptorCount = 1,
                 .stageFlags = stages};
  for (std::uint32_t i = 1; i <= kBufferBindings; ++i) {
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
                                                ::vk::ShaderStageFlags stages) {
  const ::vk::DescriptorSetLayout set = *setLayout;
  const ::vk::PushConstantRange constants{
      .stageFlags = stages, .offset = 0, .size = sizeof(TracePushConstants)};
  return {device, ::vk::PipelineLayoutCreateInfo{.setLayoutCount = 1,
                                                 .pSetLayouts = &set,
                                                 .pushConstantRangeCount = 1,
                                                 .pPushConstantRanges = &constants}};
}

::vk::raii::DescriptorPool createPool(const ::vk::raii::Device& device, std::uint32_t sets) {
  const std::array<::vk::DescriptorPoolSize, 2> sizes{{
      {.type = ::vk::DescriptorType::eAccelerationStructureKHR, .descriptorCount = sets},
      {.type = ::vk::DescriptorType::eStorageBuffer, .descriptorCount = kBufferBindings * sets},
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
                         std::uint32_t sets)
    : device_(&device.device()),
      stages_(stages),
      setLayout_(createSetLayout(device.device(), stages)),
      pipelineLayout_(createPipelineLayout(device.device(), setLayout_, stages)),
      pool_(createPool(device.device(), sets)),
      sets_(allocateSets(device.device(), pool_, setLayout_, sets)) {}

void TraceLayout::write(std::uint32_t index, const TraceBindings& bindings) const {
  const ::vk::WriteDescriptorSetAccelerationStructureKHR scene{
      .accelerationStructureCount = 1, .pAccelerationStructures = &bindings.scene};
  const std::array<::vk::DescriptorBufferInfo, kBufferBindings> buffers{{
      {.buffer = bindings.origins, .offset = 0, .range = VK_WHOLE_SIZE},
      {.buffer = bindings.targets, .offset = 0, .range = VK_WHOLE_SIZE},
      {.buffer = bindings.visibility, .offset = 0, .range = VK_WHOLE_SIZE},
  }};
  const ::vk::DescriptorSet set = *sets_[index];
  const std::array<::vk::WriteDescriptorSet, 2> writes{{
      {.pNext = &scene,
       .dstSet = set,
       .dstBinding = 0,
       .descriptorCount = 1,
       .descriptorType = ::vk::DescriptorType::eAccelerationStructureKHR},
      {.dstSet = set,
       .dstBinding = 1,
       .descriptorCount = kBufferBindings,
       .descriptorType = ::vk::DescriptorType::eStorageBuffer,
       .pBufferInfo = buffers.data()},
  }};
  device_->updateDescriptorSets(writes, nullptr);
}

void TraceLayout::pushConstants(const ::vk::raii::CommandBuffer& commands,
                                const TracePushConstants& constants) const {
  commands.pushConstants<TracePushConstants>(*pipelineLayout_, stages_, 0, constants);
}

}  // namespace lgh::vk
