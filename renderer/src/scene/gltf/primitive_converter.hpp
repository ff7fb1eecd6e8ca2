// Primitives: a glTF mesh primitive -> lgh::Primitive. Triangle strips and fans become triangle
// lists, line strips and loops line lists; points stay points. Indices are checked against the
// vertex count, positions must be finite, and what glTF lets a renderer repair is repaired with a
// warning: a trailing partial triangle or line dropped, flat normals where triangles have none
// (glTF's rule; lines and points without normals are drawn unlit, as the specification asks),
// smooth normals for zero or NaN ones, MikkTSpace tangents where missing or broken (see
// mikktspace.hpp), non-finite UVs and colours replaced by 0 and 1. Morph targets (by weight) and
// skins (by joint matrices) are applied on the CPU, before normals and tangents are finished.
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

// How one node instance deforms a mesh: morph target weights and, for a skin, the joint matrices
// (joint world matrix times inverse bind matrix). A skinned primitive comes out in world space.
struct Deformation {
  std::vector<float> morphWeights;       // empty: the base mesh
  std::vector<glm::mat4> jointMatrices;  // empty: no skin
  bool empty() const { return morphWeights.empty() && jointMatrices.empty(); }
};

class PrimitiveConverter {
 public:
  PrimitiveConverter(const tinygltf::Model& model, LoadContext& ctx, const AccessorReader& reader);

  // nullopt: skipped (an unknown mode, or nothing to draw), with a warning where that loses
  // content. `trianglesSoFar` counts towards limits.maxTriangles. `variant`: the
  // KHR_materials_variants index whose material mapping applies (-1: none).
  std::optional<Primitive> convert(int meshIndex, int primitiveIndex, std::size_t trianglesSoFar,
                                   const Deformation& deformation = {}, int variant = -1) const;

 private:
  int checkedMaterial(int material, const std::string& owner) const;

  // The material of the chosen KHR_materials_variants variant, else the primitive's own.
  int variantMaterial(const tinygltf::Primitive& source, int variant) const;

  void applyMorphTargets(const tinygltf::Primitive& source, const std::string& owner,
                         const std::vector<float>& weights, bool hasNormals, bool hasTangents,
                         Primitive& primitive) const;

  void applySkin(const tinygltf::Primitive& source, const std::string& owner,
                 const std::vector<glm::mat4>& jointMatrices, Primitive& primitive) const;

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

  // Reads NORMAL, TANGENT, TEXCOORD_0/1, COLOR_0; says which of NORMAL and TANGENT were there.
  void readAttributes(const tinygltf::Primitive& source, const std::string& owner,
                      Primitive& primitive, bool& hasNormals, bool& hasTangents) const;

  void finishNormals(Primitive& primitive, bool hasNormals, const std::string& owner) const;

  // The UV set the material's normal map (or clearcoat normal map, or extras.lgh's normal or
  // height map) uses; -1 without one.
  int tangentUvSet(int material) const;
  static int extrasTangentUvSet(const tinygltf::Material& source);
  bool hasClearcoatNormalTexture(int material) const;

  void finishTangents(Primitive& primitive, bool hasTangents, int uvSet,
                      const std::string& owner) const;

  const tinygltf::Model& model_;
  LoadContext& ctx_;
  const AccessorReader& reader_;
};

}  // namespace lgh::gltf
