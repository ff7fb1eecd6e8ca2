#include "scene/gltf/primitive_converter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "scene/mikktspace.hpp"
#include "scene/tangents.hpp"

namespace lgh::gltf {

bool isFinite(const glm::vec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

namespace {

Topology topologyOf(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS:
      return Topology::Points;
    case TINYGLTF_MODE_LINE:
    case TINYGLTF_MODE_LINE_LOOP:
    case TINYGLTF_MODE_LINE_STRIP:
      return Topology::Lines;
    default:
      return Topology::Triangles;
  }
}

bool isKnownMode(int mode) {
  return mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_TRIANGLE_FAN;
}

// Lists from glTF's modes: triangles with the winding of the spec's formulas, lines as pairs.
std::vector<std::uint32_t> toList(std::vector<std::uint32_t> indices, int mode) {
  std::vector<std::uint32_t> list;
  switch (mode) {
    case TINYGLTF_MODE_TRIANGLE_STRIP:
    case TINYGLTF_MODE_TRIANGLE_FAN:
      if (indices.size() < 3) return list;
      list.reserve((indices.size() - 2) * 3);
      for (std::size_t i = 0; i + 2 < indices.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
          const std::size_t odd = i % 2;
          list.insert(list.end(), {indices[i], indices[i + 1 + odd], indices[i + 2 - odd]});
        } else {
          list.insert(list.end(), {indices[i + 1], indices[i + 2], indices[0]});
        }
      }
      return list;
    case TINYGLTF_MODE_LINE_STRIP:
    case TINYGLTF_MODE_LINE_LOOP:
      if (indices.size() < 2) return list;
      for (std::size_t i = 0; i + 1 < indices.size(); ++i) {
        list.insert(list.end(), {indices[i], indices[i + 1]});
      }
      if (mode == TINYGLTF_MODE_LINE_LOOP) list.insert(list.end(), {indices.back(), indices[0]});
      return list;
    default:
      return indices;
  }
}

// Triangles (or, for lines and points, elements) a mode makes of `indexCount` indices.
std::size_t elementCountFor(std::size_t indexCount, int mode) {
  switch (mode) {
    case TINYGLTF_MODE_TRIANGLES:
      return indexCount / 3;
    case TINYGLTF_MODE_TRIANGLE_STRIP:
    case TINYGLTF_MODE_TRIANGLE_FAN:
      return indexCount >= 3 ? indexCount - 2 : 0;
    case TINYGLTF_MODE_LINE:
      return indexCount / 2;
    default:  // line strips and loops (at most one segment per index), points
      return indexCount;
  }
}

std::size_t indicesPerElement(Topology topology) {
  switch (topology) {
    case Topology::Triangles:
      return 3;
    case Topology::Lines:
      return 2;
    case Topology::Points:
      return 1;
  }
  return 1;
}

const char* elementName(Topology topology) {
  switch (topology) {
    case Topology::Triangles:
      return "triangles";
    case Topology::Lines:
      return "lines";
    case Topology::Points:
      return "points";
  }
  return "elements";
}

glm::vec4 readColor(const std::vector<float>& colors, std::size_t i, int components) {
  const std::size_t base = i * static_cast<std::size_t>(components);
  glm::vec4 color(colors[base], colors[base + 1], colors[base + 2], 1.0F);
  if (components == 4) color.w = colors[base + 3];
  return color;
}

// Normals whose length is off 1 by more than the Khronos validator's tolerance.
std::size_t countNonUnitNormals(const Primitive& primitive) {
  return static_cast<std::size_t>(
      std::count_if(primitive.vertices.begin(), primitive.vertices.end(), [](const Vertex& v) {
        return isUsableDirection(v.normal) && std::abs(glm::length(v.normal) - 1.0F) > 5e-5F;
      }));
}

// Normalises the asset's tangents in place; false when any is unusable (then all are rebuilt).
bool normalizeGivenTangents(Primitive& primitive) {
  for (Vertex& vertex : primitive.vertices) {
    const glm::vec3 t(vertex.tangent);
    if (!isFinite(vertex.tangent) || !isUsableDirection(t)) return false;
    if (std::abs(std::abs(vertex.tangent.w) - 1.0F) > 0.01F) return false;
    vertex.tangent = glm::vec4(glm::normalize(t), vertex.tangent.w < 0.0F ? -1.0F : 1.0F);
  }
  return true;
}

}  // namespace

PrimitiveConverter::PrimitiveConverter(const tinygltf::Model& model, LoadContext& ctx,
                                       const AccessorReader& reader)
    : model_(model), ctx_(ctx), reader_(reader) {}

std::optional<Primitive> PrimitiveConverter::convert(int meshIndex, int primitiveIndex,
                                                     std::size_t trianglesSoFar,
                                                     const Deformation& deformation,
                                                     int variant) const {
  const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(meshIndex)];
  const tinygltf::Primitive& source = mesh.primitives[static_cast<std::size_t>(primitiveIndex)];
  const std::string owner = fmt::format("/meshes/{}/primitives/{}", meshIndex, primitiveIndex);
  if (!isKnownMode(source.mode)) {
    ctx_.warnings.push_back(
        fmt::format("{}/mode: {} is not a glTF primitive mode; skipped", owner, source.mode));
    return std::nullopt;
  }
  Primitive primitive;
  primitive.topology = topologyOf(source.mode);
  primitive.material = checkedMaterial(variantMaterial(source, variant), owner);
  readPositions(source, owner, primitive);
  readIndices(source, owner, trianglesSoFar, primitive);
  if (primitive.indices.empty()) return std::nullopt;
  bool hasNormals = false;
  bool hasTangents = false;
  readAttributes(source, owner, primitive, hasNormals, hasTangents);
  if (!deformation.morphWeights.empty()) {
    applyMorphTargets(source, owner, deformation.morphWeights, hasNormals, hasTangents, primitive);
  }
  if (!deformation.jointMatrices.empty()) {
    applySkin(source, owner, deformation.jointMatrices, primitive);
  }
  if (primitive.topology != Topology::Triangles) {
    // glTF: lines and points without normals are rendered without lighting.
    primitive.unlit = !hasNormals;
    if (hasNormals) repairNormals(primitive);
    return primitive;
  }
  finishNormals(primitive, hasNormals, owner);
  finishTangents(primitive, hasTangents, tangentUvSet(primitive.material), owner);
  if (!hasTangents && hasClearcoatNormalTexture(primitive.material)) {
    // The Khronos validator's MESH_PRIMITIVE_NO_TANGENT_SPACE, an error; the specification lets a
    // client compute MikkTSpace tangents instead, which finishTangents did.
    ctx_.warnOnce(
        "a primitive without TANGENT uses a material with a clearcoatNormalTexture; MikkTSpace "
        "tangents generated");
  }
  return primitive;
}

bool PrimitiveConverter::hasClearcoatNormalTexture(int material) const {
  if (material < 0) return false;
  const tinygltf::Material& source = model_.materials[static_cast<std::size_t>(material)];
  const auto it = source.extensions.find("KHR_materials_clearcoat");
  return it != source.extensions.end() && it->second.Has("clearcoatNormalTexture");
}

int PrimitiveConverter::checkedMaterial(int material, const std::string& owner) const {
  if (material >= 0 && static_cast<std::size_t>(material) >= model_.materials.size()) {
    invalid(ctx_,
            fmt::format("{}/material names material {}, which does not exist", owner, material));
  }
  return material;
}

int PrimitiveConverter::variantMaterial(const tinygltf::Primitive& source, int variant) const {
  if (variant < 0) return source.material;
  const auto it = source.extensions.find("KHR_materials_variants");
  if (it == source.extensions.end() || !it->second.Has("mappings")) return source.material;
  const tinygltf::Value& mappings = it->second.Get("mappings");
  for (std::size_t m = 0; mappings.IsArray() && m < mappings.ArrayLen(); ++m) {
    const tinygltf::Value& mapping = mappings.Get(static_cast<int>(m));
    if (!mapping.Has("variants") || !mapping.Has("material")) continue;
    const tinygltf::Value& variants = mapping.Get("variants");
    for (std::size_t v = 0; variants.IsArray() && v < variants.ArrayLen(); ++v) {
      const tinygltf::Value& entry = variants.Get(static_cast<int>(v));
      if (entry.IsInt() && entry.GetNumberAsInt() == variant && mapping.Get("material").IsInt()) {
        return mapping.Get("material").GetNumberAsInt();
      }
    }
  }
  return source.material;
}

int PrimitiveConverter::attributeAccessor(const tinygltf::Primitive& source,
                                          const char* name) const {
  const auto it = source.attributes.find(name);
  return it == source.attributes.end() ? -1 : it->second;
}

std::vector<float> PrimitiveConverter::readAttribute(const tinygltf::Primitive& source,
                                                     const char* name, Semantic semantic,
                                                     const std::string& owner,
                                                     std::size_t vertexCount,
                                                     int* components) const {
  const int accessor = attributeAccessor(source, name);
  if (accessor < 0) return {};
  const std::string what = fmt::format("{}/attributes/{}", owner, name);
  std::vector<float> values = reader_.readFloats(accessor, semantic, what, components);
  if (values.size() != vertexCount * static_cast<std::size_t>(*components)) {
    invalid(ctx_,
            fmt::format("{}: /accessors/{} has {} elements but POSITION has {}", what, accessor,
                        values.size() / static_cast<std::size_t>(*components), vertexCount));
  }
  return values;
}

void PrimitiveConverter::readPositions(const tinygltf::Primitive& source, const std::string& owner,
                                       Primitive& primitive) const {
  const int accessor = attributeAccessor(source, "POSITION");
  if (accessor < 0) invalid(ctx_, fmt::format("{}/attributes has no POSITION", owner));
  int components = 0;
  const std::string what = fmt::format("{}/attributes/POSITION", owner);
  const std::vector<float> values =
      reader_.readFloats(accessor, Semantic::Position, what, &components);
  primitive.vertices.resize(values.size() / 3);
  for (std::size_t i = 0; i < primitive.vertices.size(); ++i) {
    const glm::vec3 position(values[i * 3], values[i * 3 + 1], values[i * 3 + 2]);
    if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z)) {
      invalid(ctx_, fmt::format("{}: /accessors/{} holds a non-finite position (NaN or Inf) at "
                                "vertex {}",
                                what, accessor, i));
    }
    primitive.vertices[i].position = position;
  }
}

void PrimitiveConverter::readIndices(const tinygltf::Primitive& source, const std::string& owner,
                                     std::size_t trianglesSoFar, Primitive& primitive) const {
  const std::size_t vertexCount = primitive.vertices.size();
  const std::string what = fmt::format("{}/indices", owner);
  const std::size_t indexCount =
      source.indices >= 0 ? reader_.elementCount(source.indices, what) : vertexCount;
  // Lines and points count against the triangle limit element for element: each is one draw
  // primitive, as cheap as a triangle or cheaper.
  checkTriangleBudget(trianglesSoFar + elementCountFor(indexCount, source.mode), owner);
  std::vector<std::uint32_t> indices;
  if (source.indices >= 0) {
    indices = reader_.readIndices(source.indices, what);
    checkIndexRange(indices, vertexCount, what, source.indices);
  } else {
    indices.resize(vertexCount);
    for (std::size_t i = 0; i < vertexCount; ++i) indices[i] = static_cast<std::uint32_t>(i);
  }
  primitive.indices = toList(std::move(indices), source.mode);
  const std::size_t per = indicesPerElement(primitive.topology);
  if (primitive.indices.size() % per != 0) {
    ctx_.warnings.push_back(
        fmt::format("{}: {} indices are not a whole number of {}; the last {} "
                    "dropped",
                    owner, primitive.indices.size(), elementName(primitive.topology),
                    primitive.indices.size() % per));
    primitive.indices.resize(primitive.indices.size() - primitive.indices.size() % per);
  }
}

void PrimitiveConverter::checkIndexRange(const std::vector<std::uint32_t>& indices,
                                         std::size_t vertexCount, const std::string& what,
                                         int accessor) const {
  for (std::size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= vertexCount) {
      invalid(ctx_, fmt::format("{}: /accessors/{} has index {} at position {}, out of range for "
                                "{} vertices",
                                what, accessor, indices[i], i, vertexCount));
    }
  }
}

void PrimitiveConverter::checkTriangleBudget(std::size_t triangles,
                                             const std::string& owner) const {
  if (triangles > ctx_.limits.maxTriangles) {
    tooLarge(ctx_, fmt::format("the asset has more than {} triangles (reached at {})",
                               ctx_.limits.maxTriangles, owner));
  }
}

void PrimitiveConverter::readAttributes(const tinygltf::Primitive& source, const std::string& owner,
                                        Primitive& primitive, bool& hasNormals,
                                        bool& hasTangents) const {
  const std::size_t count = primitive.vertices.size();
  int components = 0;
  const auto normals = readAttribute(source, "NORMAL", Semantic::Normal, owner, count, &components);
  const auto tangents =
      readAttribute(source, "TANGENT", Semantic::Tangent, owner, count, &components);
  const auto uv0 =
      readAttribute(source, "TEXCOORD_0", Semantic::TexCoord, owner, count, &components);
  const auto uv1 =
      readAttribute(source, "TEXCOORD_1", Semantic::TexCoord, owner, count, &components);
  int colorComponents = 4;
  const auto colors =
      readAttribute(source, "COLOR_0", Semantic::Color, owner, count, &colorComponents);
  // The reader has refused non-finite values already.
  for (std::size_t i = 0; i < count; ++i) {
    Vertex& v = primitive.vertices[i];
    if (!normals.empty()) v.normal = {normals[i * 3], normals[i * 3 + 1], normals[i * 3 + 2]};
    if (!tangents.empty()) {
      v.tangent = {tangents[i * 4], tangents[i * 4 + 1], tangents[i * 4 + 2], tangents[i * 4 + 3]};
    }
    if (!uv0.empty()) v.uv0 = glm::vec2(uv0[i * 2], uv0[i * 2 + 1]);
    if (!uv1.empty()) v.uv1 = glm::vec2(uv1[i * 2], uv1[i * 2 + 1]);
    if (!colors.empty()) v.color = readColor(colors, i, colorComponents);
  }
  hasNormals = !normals.empty();
  hasTangents = !tangents.empty();
}

void PrimitiveConverter::finishNormals(Primitive& primitive, bool hasNormals,
                                       const std::string& owner) const {
  if (!hasNormals) {
    generateFlatNormals(primitive);  // glTF: "client implementations MUST calculate flat normals"
    return;
  }
  if (const std::size_t nonUnit = countNonUnitNormals(primitive); nonUnit > 0) {
    ctx_.warnings.push_back(
        fmt::format("{}/attributes/NORMAL: {} normals not of unit length; "
                    "normalized",
                    owner, nonUnit));
  }
  if (const std::size_t repaired = repairNormals(primitive); repaired > 0) {
    ctx_.warnings.push_back(
        fmt::format("{}: {} zero-length or non-finite normals replaced by "
                    "smooth normals",
                    owner, repaired));
  }
}

// extras.lgh (material_extras.cpp) may give a normal or height map: parallax and relief mapping
// need the tangent frame too. The UV set of the first one given, or -1.
int PrimitiveConverter::extrasTangentUvSet(const tinygltf::Material& source) {
  if (!source.extras.IsObject() || !source.extras.Has("lgh")) return -1;
  const tinygltf::Value& parameters = source.extras.Get("lgh");
  if (!parameters.IsObject()) return -1;
  for (const char* key : {"normal_texture", "height_texture"}) {
    if (!parameters.Has(key) || !parameters.Get(key).IsObject()) continue;
    const tinygltf::Value& info = parameters.Get(key);
    return info.Has("tex_coord") && info.Get("tex_coord").IsInt()
               ? info.Get("tex_coord").GetNumberAsInt()
               : 0;
  }
  return -1;
}

int PrimitiveConverter::tangentUvSet(int material) const {
  if (material < 0) return -1;
  const tinygltf::Material& source = model_.materials[static_cast<std::size_t>(material)];
  int texCoord = -1;
  if (source.normalTexture.index >= 0) {
    texCoord = source.normalTexture.texCoord;
  } else if (const auto it = source.extensions.find("KHR_materials_clearcoat");
             it != source.extensions.end() && it->second.Has("clearcoatNormalTexture")) {
    const tinygltf::Value& info = it->second.Get("clearcoatNormalTexture");
    texCoord = info.Has("texCoord") && info.Get("texCoord").IsInt()
                   ? info.Get("texCoord").GetNumberAsInt()
                   : 0;
  }
  if (texCoord < 0) texCoord = extrasTangentUvSet(source);
  if (texCoord < 0) return -1;
  return texCoord == 1 ? 1 : 0;
}

void PrimitiveConverter::finishTangents(Primitive& primitive, bool hasTangents, int uvSet,
                                        const std::string& owner) const {
  if (hasTangents && normalizeGivenTangents(primitive)) {
    primitive.tangents = true;
    return;
  }
  if (hasTangents) {
    ctx_.warnings.push_back(
        fmt::format("{}: TANGENT has zero, non-finite or non-unit-w values; regenerated", owner));
  }
  // Tangents serve normal maps only: without one the shaders never read them (the default frame
  // stays), and MikkTSpace is the most expensive step of a load.
  if (uvSet >= 0) {
    generateMikkTSpaceTangents(primitive, uvSet);
    primitive.tangents = true;
    return;
  }
  for (Vertex& vertex : primitive.vertices) {
    vertex.tangent = glm::vec4(anyPerpendicular(vertex.normal), 1.0F);
  }
}

}  // namespace lgh::gltf
