#include "vk/scene_geometry.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "lgh/error.hpp"
#include "scene/scene.hpp"

namespace lgh::vk {
namespace {

constexpr std::size_t kMaxElements = std::numeric_limits<std::uint32_t>::max();

bool inRange(const Primitive& primitive, std::size_t firstOfTriangle) {
  const std::size_t vertexCount = primitive.vertices.size();
  return std::all_of(primitive.indices.begin() + static_cast<std::ptrdiff_t>(firstOfTriangle),
                     primitive.indices.begin() + static_cast<std::ptrdiff_t>(firstOfTriangle + 3),
                     [vertexCount](std::uint32_t index) { return index < vertexCount; });
}

void appendPrimitive(const Primitive& primitive, std::size_t source, PackedGeometry& packed,
                     PackedMesh& mesh) {
  PackedPrimitive placed;
  placed.sourcePrimitive = static_cast<std::uint32_t>(source);
  placed.firstVertex = static_cast<std::uint32_t>(packed.positions.size());
  placed.vertexCount = static_cast<std::uint32_t>(primitive.vertices.size());
  placed.firstIndex = static_cast<std::uint32_t>(packed.indices.size());
  for (std::size_t first = 0; first + 3 <= primitive.indices.size(); first += 3) {
    if (!inRange(primitive, first)) {
      ++packed.droppedTriangles;
      continue;
    }
    packed.indices.insert(packed.indices.end(),
                          primitive.indices.begin() + static_cast<std::ptrdiff_t>(first),
                          primitive.indices.begin() + static_cast<std::ptrdiff_t>(first + 3));
    ++placed.triangleCount;
  }
  if (placed.triangleCount == 0) return;
  for (const Vertex& vertex : primitive.vertices) packed.positions.push_back(vertex.position);
  packed.triangleCount += placed.triangleCount;
  mesh.primitives.push_back(placed);
}

void checkSize(const PackedGeometry& packed) {
  if (packed.positions.size() > kMaxElements || packed.indices.size() > kMaxElements) {
    throw Error(ErrorCode::TooLarge,
                fmt::format("the scene has {} vertices and {} indices; the shadow tracer takes "
                            "at most {} of each",
                            packed.positions.size(), packed.indices.size(), kMaxElements));
  }
}

}  // namespace

PackedGeometry packGeometry(const Scene& scene) {
  PackedGeometry packed;
  packed.meshes.resize(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const std::vector<Primitive>& primitives = scene.meshes[m].primitives;
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      appendPrimitive(primitives[p], p, packed, packed.meshes[m]);
      checkSize(packed);
    }
  }
  return packed;
}

}  // namespace lgh::vk
