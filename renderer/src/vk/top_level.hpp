// The top-level acceleration structure over a scene's instances; with no instances it is empty
// and every ray misses.
#pragma once

#include <vector>

#include "vk/acceleration_structure.hpp"

namespace lgh::vk {

class VulkanDevice;

struct TopLevel {
  AccelerationStructure structure;
  double buildGpuMs = 0.0;
};

// The bottom levels the instances name must be built (and visible to later submissions).
TopLevel buildTopLevel(const VulkanDevice& device,
                       const std::vector<::vk::AccelerationStructureInstanceKHR>& instances);

}  // namespace lgh::vk
