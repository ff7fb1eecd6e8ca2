// Where each primitive of a scene lies when all of them share one vertex buffer and one index
// buffer: meshes in order, each mesh's triangle primitives, then its lines and points, vertices
// and indices each packed in that order. GpuScene draws from such a pair, and stageScene fills
// staging memory in the same layout, so that one copy moves each.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "gl/gl_api.hpp"
#include "scene/scene.hpp"

namespace lgh {

struct PrimitiveRange {
  GLsizei indexCount = 0;
  GLuint firstIndex = 0;  // in the index buffer
  GLint baseVertex = 0;   // added to each index: the primitive's first vertex
};

struct GeometryLayout {
  // Per mesh, in forEachPrimitive's order.
  std::vector<std::vector<PrimitiveRange>> meshes;
  std::size_t vertexCount = 0;
  std::size_t indexCount = 0;
  std::size_t vertexBytes() const { return vertexCount * sizeof(Vertex); }
  std::size_t indexBytes() const { return indexCount * sizeof(std::uint32_t); }
};

GeometryLayout geometryLayout(const Scene& scene);

// Calls fn(primitive, range) for every primitive of `mesh` (the layout's meshes[mesh]) in order.
template <typename Fn>
void forEachPrimitive(const Scene& scene, const GeometryLayout& layout, std::size_t mesh, Fn&& fn) {
  std::size_t p = 0;
  forEachPrimitive(scene.meshes[mesh],
                   [&](const Primitive& primitive) { fn(primitive, layout.meshes[mesh][p++]); });
}

}  // namespace lgh
