// The bottom-level acceleration structures of a scene: one per mesh with triangles, a geometry
// per primitive (opaque), built for fast tracing and then compacted. The positions and indices
// go up through a staging buffer and are freed with the uncompacted structures once built.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "vk/acceleration_structure.hpp"

namespace lgh::vk {

class VulkanDevice;
struct PackedGeometry;

struct BottomLevels {
  std::vector<AccelerationStructure> structures;
  // For each of the scene's meshes, its structure's index in `structures`; nullopt: no triangles.
  std::vector<std::optional<std::size_t>> structureOfMesh;
  double buildGpuMs = 0.0;  // the builds and the compaction
};

BottomLevels buildBottomLevels(const VulkanDevice& device, const PackedGeometry& geometry);

}  // namespace lgh::vk
