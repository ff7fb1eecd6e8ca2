#include "scene/scene.hpp"

namespace lgh {
namespace {

const Mesh* meshOf(const Scene& scene, const MeshInstance& instance) {
  if (instance.mesh < 0 || static_cast<std::size_t>(instance.mesh) >= scene.meshes.size()) {
    return nullptr;
  }
  return &scene.meshes[static_cast<std::size_t>(instance.mesh)];
}

std::size_t meshTriangles(const Mesh& mesh) {
  std::size_t count = 0;
  for (const Primitive& primitive : mesh.primitives) count += primitive.indices.size() / 3;
  return count;
}

}  // namespace

// Triangles as drawn: a mesh placed by two instances counts twice.
std::size_t Scene::triangleCount() const {
  std::size_t count = 0;
  for (const MeshInstance& instance : instances) {
    if (const Mesh* mesh = meshOf(*this, instance)) count += meshTriangles(*mesh);
  }
  return count;
}

// Exact world-space bounds: every referenced vertex of every instance, transformed. Transforming
// the corners of each mesh's local box would be cheaper but loose under rotation, and the bounds
// drive automatic camera framing and the LGH grid.
void Scene::computeBounds() {
  bounds = Bounds{};
  for (const MeshInstance& instance : instances) {
    const Mesh* mesh = meshOf(*this, instance);
    if (mesh == nullptr) continue;
    for (const Primitive& primitive : mesh->primitives) {
      for (std::uint32_t index : primitive.indices) {
        if (index >= primitive.vertices.size()) continue;
        const glm::vec4 world =
            instance.world * glm::vec4(primitive.vertices[index].position, 1.0F);
        bounds.extend(glm::vec3(world));
      }
    }
  }
}

}  // namespace lgh
