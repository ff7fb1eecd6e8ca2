// Primitives: a glTF mesh primitive -> lgh::Primitive. Triangle strips and fans become triangle
// lists; points and lines are skipped with a warning. Indices are checked against the vertex
// count, positions must be finite, and what glTF lets a renderer repair is repaired with a warning:
// a trailing partial triangle dropped, flat normals where there are none (glTF's rule), smooth
// normals for zero or NaN ones, tangents generated where missing or broken (see tangents.hpp),
// non-finite UVs and colours replaced by 0 and 1.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/gltf/accessor_reader.hpp"
#include "scene/gltf/load_context.hpp"
#include "scene/gltf/tinygltf.hpp"
#include "scene/scene.hpp"

namespace lgh::gltf {

bool isFinite(const glm::vec4& v);

class PrimitiveConverter {
 public:
  PrimitiveConverter(const tinygltf::Model& model, LoadContext& ctx, const AccessorReader& reader);

  // nullopt: skipped (not triangles, or no triangles), with a warning where that loses content.
  // `trianglesSoFar` counts towards limits.maxTriangles.
  std::optional<Primitive> convert(int meshIndex, int primitiveIndex,
                                   std::size_t trianglesSoFar) const;

 private:
  int checkedMaterial(int material, const std::string& owner) const;

  int attributeAccessor(const tinygltf::Primitive& source, const char* name) const;

  // Reads attribute `name` (count checked against the vertex count); empty when absent.
  std::vector<float> readAttribute(const tinygltf::Primitive& source, const char* name,
                                   Semantic semantic, const std::string& owner,
                                   std::size_t vertexCount, int* components) const;

  void readPositions(const tinygltf::Primitive& source, const std::string& owner,
                     Primitive& primitive) const;

  void readIndices(const tinygltf::Primitive& source, const std::string& owner,
                   std::size_t trianglesSoFar, Primitive& primitive) const;

  void checkIndexRange(const std::vector<std::uint32_t>& indices, std::size_t vertexCount,
                       const std::string& what, int accessor) const;

  void checkTriangleBudget(std::size_t triangles, const std::string& owner) const;

  void readAttributes(const tinygltf::Primitive& source, const std::string& owner,
                      Primitive& primitive) const;

  void finishNormals(Primitive& primitive, bool hasNormals, const std::string& owner) const;

  // The UV set the material's normal map uses (tangents serve normal mapping); 0 otherwise.
  int tangentUvSet(int material) const;

  void finishTangents(Primitive& primitive, bool hasTangents, int uvSet,
                      const std::string& owner) const;

  const tinygltf::Model& model_;
  LoadContext& ctx_;
  const AccessorReader& reader_;
};

}  // namespace lgh::gltf
