#include "vk/tlas_instances.hpp"

#include "scene/scene.hpp"

namespace lgh::vk {

::vk::TransformMatrixKHR toTransformMatrix(const glm::mat4& world) {
  ::vk::TransformMatrixKHR matrix{};
  for (int row = 0; row < 3; ++row) {
    for (int column = 0; column < 4; ++column) {
      matrix.matrix[row][column] = world[column][row];
    }
  }
  return matrix;
}

std::vector<::vk::AccelerationStructureInstanceKHR> tlasInstances(
    const Scene& scene, const std::vector<std::optional<::vk::DeviceAddress>>& meshAddress) {
  std::vector<::vk::AccelerationStructureInstanceKHR> instances;
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const int mesh = scene.instances[i].mesh;
    if (mesh < 0 || static_cast<std::size_t>(mesh) >= meshAddress.size()) continue;
    const std::optional<::vk::DeviceAddress>& address = meshAddress[static_cast<std::size_t>(mesh)];
    if (!address) continue;
    ::vk::AccelerationStructureInstanceKHR instance{};
    instance.transform = toTransformMatrix(scene.instances[i].world);
    instance.instanceCustomIndex = static_cast<std::uint32_t>(i) & 0xFFFFFFU;
    instance.mask = 0xFFU;
    instance.instanceShaderBindingTableRecordOffset = 0;
    instance.flags = static_cast<VkGeometryInstanceFlagsKHR>(
        ::vk::GeometryInstanceFlagBitsKHR::eTriangleFacingCullDisable);
    instance.accelerationStructureReference = *address;
    instances.push_back(instance);
  }
  return instances;
}

}  // namespace lgh::vk
