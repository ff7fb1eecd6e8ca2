// A scene's instances as the top-level build reads them.
#pragma once

#include <optional>
#include <vector>

#include <glm/mat4x4.hpp>

#include "vk/vulkan_hpp.hpp"

namespace lgh {
struct Scene;
}

namespace lgh::vk {

// glm's column-major 4x4 as Vulkan's row-major 3x4 (the bottom row, always 0 0 0 1, dropped).
::vk::TransformMatrixKHR toTransformMatrix(const glm::mat4& world);

// One instance per scene instance whose mesh has a bottom level (`meshAddress`, by mesh index;
// nullopt: none): all 8 mask bits, no face culling, its index in Scene::instances as custom index.
std::vector<::vk::AccelerationStructureInstanceKHR> tlasInstances(
    const Scene& scene, const std::vector<std::optional<::vk::DeviceAddress>>& meshAddress);

}  // namespace lgh::vk
