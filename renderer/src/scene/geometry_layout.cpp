#include "scene/geometry_layout.hpp"

namespace lgh {

GeometryLayout geometryLayout(const Scene& scene) {
  GeometryLayout layout;
  for (const Mesh& mesh : scene.meshes) {
    auto& ranges = layout.meshes.emplace_back();
    forEachPrimitive(mesh, [&](const Primitive& primitive) {
      ranges.push_back({static_cast<GLsizei>(primitive.indices.size()),
                        static_cast<GLuint>(layout.indexCount),
                        static_cast<GLint>(layout.vertexCount)});
      layout.vertexCount += primitive.vertices.size();
      layout.indexCount += primitive.indices.size();
    });
  }
  return layout;
}

}  // namespace lgh
