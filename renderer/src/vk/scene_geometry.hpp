// A Scene's triangles as the acceleration-structure builds read them: every position tightly
// packed (vec3) and every index (uint32) in two arrays, with each primitive's place in them.
// Plain CPU data, no Vulkan.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace lgh {
struct Scene;
}

namespace lgh::vk {

// One primitive's triangles: `vertexCount` positions from `firstVertex` and `triangleCount` * 3
// indices from `firstIndex`, each relative to the primitive's first vertex.
struct PackedPrimitive {
  std::uint32_t sourcePrimitive = 0;  // its index in the Scene mesh's primitives
  std::uint32_t firstVertex = 0;
  std::uint32_t vertexCount = 0;
  std::uint32_t firstIndex = 0;
  std::uint32_t triangleCount = 0;
};

struct PackedMesh {
  std::vector<PackedPrimitive> primitives;  // only those with triangles
  bool empty() const { return primitives.empty(); }
};

struct PackedGeometry {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
  std::vector<PackedMesh> meshes;  // one per Scene::meshes entry
  std::size_t triangleCount = 0;
  std::size_t droppedTriangles = 0;  // triangles with an index past their primitive's vertices
};

// Packs the scene's meshes. Triangles with an index out of range are dropped (the GL side skips
// them the same way), so no build ever reads outside its vertices.
PackedGeometry packGeometry(const Scene& scene);

}  // namespace lgh::vk
